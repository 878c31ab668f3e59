// Plane geometry in the local grid (x east, y north, metres; headings clockwise from north).

export function signedArea(poly) {
  let a = 0;
  for (let i = 0; i < poly.length; i++) {
    const [x1, y1] = poly[i];
    const [x2, y2] = poly[(i + 1) % poly.length];
    a += x1 * y2 - x2 * y1;
  }
  return a / 2;
}

/**
 * The polygon moved inwards by d along its edge normals: each edge is offset, and neighbouring
 * offset edges are intersected. Exact for a convex region (what the container's buffer is); for a
 * concave one it is an approximation, good enough to draw the buffer line.
 */
export function insetPolygon(poly, d) {
  const n = poly.length;
  if (n < 3 || !(d > 0)) return poly.slice();
  const ccw = signedArea(poly) > 0;
  // Offset line of edge i: a point on it and its direction.
  const lines = [];
  for (let i = 0; i < n; i++) {
    const [x1, y1] = poly[i];
    const [x2, y2] = poly[(i + 1) % n];
    const len = Math.hypot(x2 - x1, y2 - y1) || 1;
    const dx = (x2 - x1) / len;
    const dy = (y2 - y1) / len;
    // The inward normal is the left one for a counter-clockwise polygon.
    const nx = ccw ? -dy : dy;
    const ny = ccw ? dx : -dx;
    lines.push({ px: x1 + nx * d, py: y1 + ny * d, dx, dy });
  }
  const out = [];
  for (let i = 0; i < n; i++) {
    const a = lines[(i - 1 + n) % n];
    const b = lines[i];
    const den = a.dx * b.dy - a.dy * b.dx;
    if (Math.abs(den) < 1e-9) {
      out.push([b.px, b.py]); // parallel neighbours: the offset vertex itself
      continue;
    }
    const t = ((b.px - a.px) * b.dy - (b.py - a.py) * b.dx) / den;
    out.push([a.px + a.dx * t, a.py + a.dy * t]);
  }
  // An inset wider than the region turns inside out (the orientation flips): draw nothing then.
  if (Math.sign(signedArea(out)) !== Math.sign(signedArea(poly))) return [];
  return out;
}

/** x[] and y[] of a closed ring for a line plot. */
export function ring(poly) {
  if (!poly || poly.length === 0) return { x: [], y: [] };
  const x = poly.map((p) => p[0]);
  const y = poly.map((p) => p[1]);
  x.push(poly[0][0]);
  y.push(poly[0][1]);
  return { x, y };
}

/** A point `len` metres from (x, y) along a heading. */
export function along(x, y, headingDeg, len) {
  const h = (headingDeg * Math.PI) / 180;
  return [x + len * Math.sin(h), y + len * Math.cos(h)];
}

/** The rings Live and Replay draw for a mission's operating region (its file's
 *  `operating_region`): the region, its buffer (inset by buffer_m, default 10) and the return
 *  point; empty rings without a region. */
export function regionRings(region) {
  if (!(region?.polygon_m?.length >= 3)) return { region: { x: [], y: [] }, buffer: { x: [], y: [] }, bufferM: null, ret: { x: [], y: [] } };
  const bufferM = region.buffer_m ?? 10;
  return {
    region: ring(region.polygon_m),
    buffer: ring(insetPolygon(region.polygon_m, bufferM)),
    bufferM,
    ret: region.return_point_m ? { x: [region.return_point_m[0]], y: [region.return_point_m[1]] } : { x: [], y: [] },
  };
}
