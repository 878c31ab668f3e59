#!/usr/bin/env node
// Draws one encounter of a scenario file (docs/encounter-format.md) as an SVG: what the avk and
// instantaneous methods chose (`avk maneuver evaluate`) and how those choices flew in the
// simulator (`avk maneuver fly`, exactly the encounter bench's flights).
//
//   node scripts/encounter-figure.mjs --db FILE --scenarios FILE --name SCENARIO --out FILE.svg
//        [--sim-config FILE] [--vehicle KIND] [--vehicle-id ID] [--avk PATH]
//
// The database is copied to a temporary folder first, so the figure never writes to it.
import { execFileSync } from 'node:child_process';
import { copyFileSync, existsSync, mkdtempSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { parseArgs } from 'node:util';

const { values: opt } = parseArgs({
  options: {
    db: { type: 'string' },
    scenarios: { type: 'string' },
    name: { type: 'string' },
    out: { type: 'string' },
    'sim-config': { type: 'string' },
    vehicle: { type: 'string', default: 'catamaran:m200' },
    'vehicle-id': { type: 'string' },
    avk: { type: 'string', default: 'build/server/avk' },
  },
});
for (const required of ['db', 'scenarios', 'name', 'out']) {
  if (!opt[required]) {
    console.error(`encounter-figure: --${required} is required`);
    process.exit(2);
  }
}

// ---- the scenario and the avk answers -----------------------------------------------------------

const file = JSON.parse(readFileSync(opt.scenarios, 'utf8'));
const scenario = file.scenarios.find((s) => s.name === opt.name);
if (!scenario) {
  console.error(`encounter-figure: no scenario '${opt.name}' in ${opt.scenarios}`);
  process.exit(2);
}
const horizon = file.horizon_s ?? 120;
const standoff = scenario.standoff_m ?? file.standoff_m ?? 10;
const own = scenario.own;
const contactArgs = scenario.contacts.flatMap((c) => [
  '--contact',
  [c.x_m, c.y_m, c.course_deg, c.speed_mps].join(','),
]);

const avk = (args) => JSON.parse(execFileSync(opt.avk, args, { encoding: 'utf8' }));

const work = mkdtempSync(join(tmpdir(), 'encounter-figure-'));
const db = join(work, 'copy.db');
copyFileSync(opt.db, db);
for (const suffix of ['-wal', '-shm']) {
  if (existsSync(opt.db + suffix)) copyFileSync(opt.db + suffix, db + suffix);
}

const simArgs = ['--vehicle', opt.vehicle];
if (opt['sim-config']) simArgs.push('--sim-config', opt['sim-config']);

const methods = {};
try {
  for (const method of ['avk', 'instantaneous']) {
    const evaluation = avk([
      'maneuver', 'evaluate', '--db', db, '--own', `0,0,${own.heading_deg},${own.speed_mps}`,
      ...contactArgs, '--standoff', String(standoff), '--horizon', String(horizon),
      '--method', method, '--format', 'json',
      ...(opt['vehicle-id'] ? ['--vehicle', opt['vehicle-id']] : []),
    ]);
    const chosen = evaluation.chosen ? evaluation.candidates[evaluation.chosen.index] : null;
    // No candidate clears: the bench holds the course, so the figure flies Δψ = 0.
    const dheading = chosen ? chosen.dheading_deg : 0;
    const flight = avk([
      'maneuver', 'fly', '--own', `${own.heading_deg},${own.speed_mps}`, '--dheading',
      String(dheading), ...contactArgs, '--horizon', String(horizon), ...simArgs,
      '--path-step', '0.2',
    ]);
    methods[method] = { evaluation, chosen, dheading, flight };
  }
} finally {
  rmSync(work, { recursive: true, force: true });
}

// ---- geometry -----------------------------------------------------------------------------------

const rad = (deg) => (deg * Math.PI) / 180;
const contactAt = (c, t) => [
  c.x_m + c.speed_mps * t * Math.sin(rad(c.course_deg)),
  c.y_m + c.speed_mps * t * Math.cos(rad(c.course_deg)),
];

// A [[t, x, y], ...] path (with optional values per point) up to time `end`, resampled every
// `step` s so that the band's normals turn smoothly.
function resample(path, end, step, values = null) {
  const out = [];
  const last = Math.min(end, path[path.length - 1][0]);
  let i = 0;
  for (let t = 0; ; t = Math.min(t + step, last)) {
    while (i + 1 < path.length - 1 && path[i + 1][0] < t) i++;
    const [t0, x0, y0] = path[i];
    const [t1, x1, y1] = path[Math.min(i + 1, path.length - 1)];
    const f = t1 > t0 ? Math.min(1, Math.max(0, (t - t0) / (t1 - t0))) : 0;
    const w = values ? values[i] + f * (values[Math.min(i + 1, values.length - 1)] - values[i]) : 0;
    out.push({ t, x: x0 + f * (x1 - x0), y: y0 + f * (y1 - y0), w });
    if (t >= last) break;
  }
  return out;
}

// The corridor: the path offset by ± its half width along the path's normal.
function band(points) {
  const left = [];
  const right = [];
  points.forEach((p, k) => {
    const a = points[Math.max(0, k - 1)];
    const b = points[Math.min(points.length - 1, k + 1)];
    const len = Math.hypot(b.x - a.x, b.y - a.y) || 1;
    const nx = -(b.y - a.y) / len;
    const ny = (b.x - a.x) / len;
    left.push([p.x + nx * p.w, p.y + ny * p.w]);
    right.push([p.x - nx * p.w, p.y - ny * p.w]);
  });
  return [...left, ...right.reverse()];
}

const cpaOf = (m) => {
  const k = m.flight.cpa.reduce((best, c, j, all) => (c.distance_m < all[best].distance_m ? j : best), 0);
  return { contact: k, ...m.flight.cpa[k] };
};
const end = Math.min(horizon, Math.max(...Object.values(methods).map((m) => cpaOf(m).time_s)) + 20);

const A = methods.avk;
const I = methods.instantaneous;
const avkPath = A.chosen ? resample(A.chosen.path, end, 0.5, A.chosen.half_width_m) : null;
const avkBand = avkPath && A.chosen.half_width_m?.length ? band(avkPath) : null;
const instPath = I.chosen ? resample(I.chosen.path, end, 0.5) : null;
const flown = (m) => resample(m.flight.track, end, 0.2);

// ---- the SVG ------------------------------------------------------------------------------------

const colours = { avk: '#1f5fbf', instantaneous: '#d4442a', contact: '#444' };
const W = 900;
const H = 700;
const plot = { left: 70, top: 60, right: 620, bottom: 640 };

const pts = [[0, 0]];
for (const c of scenario.contacts) pts.push(contactAt(c, 0), contactAt(c, end));
for (const m of Object.values(methods)) for (const p of flown(m)) pts.push([p.x, p.y]);
if (avkBand) pts.push(...avkBand);
if (instPath) for (const p of instPath) pts.push([p.x, p.y]);
for (const m of Object.values(methods)) {
  const cpa = cpaOf(m);
  const [cx, cy] = contactAt(scenario.contacts[cpa.contact], cpa.time_s);
  pts.push([cx - standoff, cy - standoff], [cx + standoff, cy + standoff]);
}
const pad = 4;
let [x0, x1] = [Math.min(...pts.map((p) => p[0])) - pad, Math.max(...pts.map((p) => p[0])) + pad];
let [y0, y1] = [Math.min(...pts.map((p) => p[1])) - pad, Math.max(...pts.map((p) => p[1])) + pad];
const scale = Math.min((plot.right - plot.left) / (x1 - x0), (plot.bottom - plot.top) / (y1 - y0));
// Equal scale: centre the data and widen the shorter axis to fill the plot.
const xc = (x0 + x1) / 2;
const yc = (y0 + y1) / 2;
x0 = xc - (plot.right - plot.left) / scale / 2;
x1 = xc + (plot.right - plot.left) / scale / 2;
y0 = yc - (plot.bottom - plot.top) / scale / 2;
y1 = yc + (plot.bottom - plot.top) / scale / 2;
const X = (x) => +(plot.left + (x - x0) * scale).toFixed(1);
const Y = (y) => +(plot.bottom - (y - y0) * scale).toFixed(1);
const esc = (text) =>
  String(text).replace(/[&<>"]/g, (ch) => ({ '&': '&amp;', '<': '&lt;', '>': '&gt;', '"': '&quot;' })[ch]);
const poly = (list) => list.map(([x, y]) => `${X(x)},${Y(y)}`).join(' ');
const line = (points) => poly(points.map((p) => [p.x, p.y]));

const svg = [];
svg.push(
  `<svg xmlns="http://www.w3.org/2000/svg" width="${W}" height="${H}" viewBox="0 0 ${W} ${H}" ` +
    `font-family="DejaVu Sans, Arial, sans-serif" font-size="13">`,
  `<rect width="${W}" height="${H}" fill="white"/>`,
  `<defs><marker id="arrow" viewBox="0 0 10 10" refX="9" refY="5" markerWidth="9" ` +
    `markerHeight="9" orient="auto-start-reverse"><path d="M0,0 L10,5 L0,10 z" ` +
    `fill="${colours.contact}"/></marker>` +
    `<clipPath id="plot"><rect x="${plot.left}" y="${plot.top}" width="${plot.right - plot.left}" ` +
    `height="${plot.bottom - plot.top}"/></clipPath></defs>`,
);

// Grid and axes, in metres.
const span = Math.max(x1 - x0, y1 - y0);
const tick = [1, 2, 5, 10, 20, 25, 50, 100, 200, 500].find((s) => span / s <= 12) ?? 1000;
for (let x = Math.ceil(x0 / tick) * tick; x <= x1; x += tick) {
  svg.push(
    `<line x1="${X(x)}" y1="${plot.top}" x2="${X(x)}" y2="${plot.bottom}" stroke="#e4e4e4"/>`,
    `<text x="${X(x)}" y="${plot.bottom + 18}" text-anchor="middle" fill="#333">${x}</text>`,
  );
}
for (let y = Math.ceil(y0 / tick) * tick; y <= y1; y += tick) {
  svg.push(
    `<line x1="${plot.left}" y1="${Y(y)}" x2="${plot.right}" y2="${Y(y)}" stroke="#e4e4e4"/>`,
    `<text x="${plot.left - 8}" y="${Y(y) + 4}" text-anchor="end" fill="#333">${y}</text>`,
  );
}
svg.push(
  `<rect x="${plot.left}" y="${plot.top}" width="${plot.right - plot.left}" ` +
    `height="${plot.bottom - plot.top}" fill="none" stroke="#888"/>`,
  `<text x="${(plot.left + plot.right) / 2}" y="${plot.bottom + 40}" text-anchor="middle">` +
    `east (m)</text>`,
  `<text transform="translate(${plot.left - 48},${(plot.top + plot.bottom) / 2}) rotate(-90)" ` +
    `text-anchor="middle">north (m)</text>`,
);

svg.push(`<g clip-path="url(#plot)">`);
// The AVK corridor and predicted path, the instantaneous ray.
if (avkBand) {
  svg.push(
    `<polygon points="${poly(avkBand)}" fill="${colours.avk}" fill-opacity="0.15" ` +
      `stroke="${colours.avk}" stroke-opacity="0.35" stroke-width="0.8"/>`,
  );
}
if (avkPath) {
  svg.push(
    `<polyline points="${line(avkPath)}" fill="none" stroke="${colours.avk}" ` +
      `stroke-width="2" stroke-dasharray="7 5"/>`,
  );
}
if (instPath) {
  svg.push(
    `<polyline points="${line(instPath)}" fill="none" stroke="${colours.instantaneous}" ` +
      `stroke-width="2" stroke-dasharray="7 5"/>`,
  );
}
// The contacts: t = 0 dot, straight track with an arrow.
scenario.contacts.forEach((c, k) => {
  const [sx, sy] = contactAt(c, 0);
  const [mx, my] = contactAt(c, end * 0.6);
  const [ex, ey] = contactAt(c, end);
  // The arrow part-way along, so that it does not cover the own vehicle's start.
  svg.push(
    `<polyline points="${poly([[sx, sy], [mx, my]])}" fill="none" stroke="${colours.contact}" ` +
      `stroke-width="1.6" marker-end="url(#arrow)"/>`,
    `<line x1="${X(mx)}" y1="${Y(my)}" x2="${X(ex)}" y2="${Y(ey)}" stroke="${colours.contact}" ` +
      `stroke-width="1.6"/>`,
    `<circle cx="${X(sx)}" cy="${Y(sy)}" r="4.5" fill="${colours.contact}"/>`,
    `<text x="${X(sx)}" y="${Y(sy) + 20}" text-anchor="middle" fill="${colours.contact}">` +
      `contact${scenario.contacts.length > 1 ? ` ${k + 1}` : ''} (t = 0)</text>`,
  );
});
// The flown tracks, each with its CPA: the contact's standoff circle at that moment and the
// closest-approach segment.
for (const [name, m] of Object.entries(methods)) {
  const colour = colours[name];
  const cpa = cpaOf(m);
  const [cx, cy] = contactAt(scenario.contacts[cpa.contact], cpa.time_s);
  const track = flown(m);
  const at = resample(m.flight.track, cpa.time_s, cpa.time_s || 1).at(-1);
  svg.push(
    `<circle cx="${X(cx)}" cy="${Y(cy)}" r="${(standoff * scale).toFixed(1)}" fill="none" ` +
      `stroke="${colour}" stroke-width="1.2" stroke-dasharray="3 3"/>`,
    `<circle cx="${X(cx)}" cy="${Y(cy)}" r="3" fill="white" stroke="${colour}" stroke-width="1.5"/>`,
    `<polyline points="${line(track)}" fill="none" stroke="${colour}" stroke-width="2.6"/>`,
    `<line x1="${X(at.x)}" y1="${Y(at.y)}" x2="${X(cx)}" y2="${Y(cy)}" stroke="${colour}" ` +
      `stroke-width="1"/>`,
    `<circle cx="${X(at.x)}" cy="${Y(at.y)}" r="3.5" fill="${colour}"/>`,
  );
  // The distance beside the own vehicle's end of the segment, away from the contact.
  const outward = at.x <= cx ? -1 : 1;
  svg.push(
    `<text x="${X(at.x) + outward * 8}" y="${Y(at.y) + (at.y >= cy ? -6 : 14)}" ` +
      `text-anchor="${outward < 0 ? 'end' : 'start'}" fill="${colour}" font-weight="bold">` +
      `${cpa.distance_m.toFixed(1)} m</text>`,
  );
}
svg.push(
  `<circle cx="${X(0)}" cy="${Y(0)}" r="4.5" fill="black"/>`,
  `<text x="${X(0) + 9}" y="${Y(0) - 6}">own (t = 0)</text>`,
  `</g>`,
);

// Title and legend.
const signed = (d) => `${d > 0 ? '+' : d < 0 ? '−' : ''}${Math.abs(d).toFixed(0)}°`;
const choice = (label, m) =>
  `${label} ${m.chosen ? `chose ${signed(m.dheading)}` : 'found none (course held)'} ` +
  `(flown CPA ${m.flight.min_cpa_m.toFixed(1)} m)`;
const title =
  `${scenario.name}: ${choice('AVK', A)}, ${choice('instantaneous', I).replace(' chose', '')}, ` +
  `standoff ${standoff} m`;
svg.push(`<text x="${W / 2}" y="32" text-anchor="middle" font-size="14.5">${esc(title)}</text>`);

const legend = [
  ['line', colours.avk, '', 'AVK: flown track'],
  ['line', colours.avk, '7 5', 'AVK: predicted path (CKT)'],
  ['band', colours.avk, '', `AVK: ${Math.round((A.evaluation.corridor ?? 0.9) * 100)} % corridor`],
  ['line', colours.instantaneous, '', 'instantaneous: flown track'],
  ['line', colours.instantaneous, '7 5', 'instantaneous: predicted ray'],
  ['arrow', colours.contact, '', 'contact track (dot: t = 0)'],
  ['circle', '#666', '3 3', `standoff ${standoff} m around the`],
  ['none', '', '', 'contact at each flown CPA'],
];
const lx = plot.right + 20;
let ly = plot.top + 10;
svg.push(`<text x="${lx}" y="${ly}" font-weight="bold">legend</text>`);
ly += 22;
for (const [kind, colour, dash, text] of legend) {
  if (kind === 'line') {
    svg.push(`<line x1="${lx}" y1="${ly - 4}" x2="${lx + 34}" y2="${ly - 4}" stroke="${colour}" ` +
      `stroke-width="2.4"${dash ? ` stroke-dasharray="${dash}"` : ''}/>`);
  } else if (kind === 'band') {
    svg.push(`<rect x="${lx}" y="${ly - 10}" width="34" height="12" fill="${colour}" ` +
      `fill-opacity="0.15" stroke="${colour}" stroke-opacity="0.35"/>`);
  } else if (kind === 'arrow') {
    svg.push(`<line x1="${lx + 4}" y1="${ly - 4}" x2="${lx + 34}" y2="${ly - 4}" stroke="${colour}" ` +
      `stroke-width="1.6" marker-end="url(#arrow)"/>`,
      `<circle cx="${lx + 4}" cy="${ly - 4}" r="4" fill="${colour}"/>`);
  } else if (kind === 'circle') {
    svg.push(`<circle cx="${lx + 17}" cy="${ly - 4}" r="8" fill="none" stroke="${colour}" ` +
      `stroke-dasharray="${dash}"/>`);
  }
  svg.push(`<text x="${lx + 44}" y="${ly}">${text}</text>`);
  ly += kind === 'circle' ? 16 : 24;
}
ly += 16;
const notes = [
  `own ${own.heading_deg}° at ${own.speed_mps} m/s`,
  `flown: ${A.flight.sim_vehicle}, seed ${A.flight.seed}`,
  `shown to t = ${end.toFixed(0)} s`,
  '',
  'flown CPA (line to the contact):',
  ...Object.entries(methods).map(
    ([name, m]) =>
      `  ${name}: ${cpaOf(m).distance_m.toFixed(1)} m at t = ${cpaOf(m).time_s.toFixed(1)} s`,
  ),
];
for (const n of notes) {
  svg.push(`<text x="${lx}" y="${ly}" fill="#555" font-size="12">${n}</text>`);
  ly += 18;
}
svg.push('</svg>');
writeFileSync(opt.out, svg.join('\n') + '\n');

for (const [name, m] of Object.entries(methods)) {
  const cpa = cpaOf(m);
  console.log(
    `${opt.name}: ${name} ${m.chosen ? `chose ${signed(m.dheading)}` : 'chose none (course held)'}` +
      ` -> flown CPA ${m.flight.min_cpa_m.toFixed(1)} m at t = ${cpa.time_s.toFixed(1)} s`,
  );
}
console.log(`wrote ${opt.out}`);
