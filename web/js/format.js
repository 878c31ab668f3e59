// Number and text formatting shared by the views; '–' stands for "no value".

export function num(v, digits = 1) {
  return typeof v === 'number' && Number.isFinite(v) ? v.toFixed(digits) : '–';
}

/** "12.3 ± 0.4 m"; just "12.3 m" for the mean of one value (n = 1, or an sd the station left out):
 *  a spread of one value is no spread, and "± 0.0" would say it was measured to be nil. */
export function meanSd(ms, digits = 1, unit = '', n = ms?.n) {
  if (!ms || typeof ms.mean !== 'number') return '–';
  const sd = typeof ms.sd === 'number' && n !== 1 ? ` ± ${ms.sd.toFixed(digits)}` : '';
  return `${ms.mean.toFixed(digits)}${sd}${unit}`;
}

/** Signed smallest difference a − b of two headings, in (−180, 180]. */
export function headingDiff(a, b) {
  let d = (a - b) % 360;
  if (d <= -180) d += 360;
  if (d > 180) d -= 360;
  return d;
}

export function wrap360(h) {
  const w = h % 360;
  return w < 0 ? w + 360 : w;
}

export function el(tag, attrs = {}, ...children) {
  const e = document.createElement(tag);
  for (const [k, v] of Object.entries(attrs)) {
    if (v === undefined || v === null || v === false) continue;
    if (k === 'class') e.className = v;
    else if (k === 'text') e.textContent = v;
    else if (k.startsWith('on') && typeof v === 'function') e.addEventListener(k.slice(2), v);
    else e.setAttribute(k, v === true ? '' : v);
  }
  for (const c of children) {
    if (c === null || c === undefined || c === false) continue;
    e.append(c instanceof Node ? c : document.createTextNode(String(c)));
  }
  return e;
}

/** Fills a <table> from column specs [{key|get, label, fmt}] and rows. */
export function fillTable(table, columns, rows, { rowClass } = {}) {
  table.replaceChildren();
  const thead = el('thead', {}, el('tr', {}, ...columns.map((c) => el('th', { scope: 'col', text: c.label }))));
  const tbody = el('tbody');
  for (const r of rows) {
    const tr = el('tr', { class: rowClass ? rowClass(r) : undefined });
    for (const c of columns) {
      const v = c.get ? c.get(r) : r[c.key];
      const text = c.fmt ? c.fmt(v, r) : v === null || v === undefined ? '–' : String(v);
      tr.append(v instanceof Node ? el('td', {}, v) : el('td', { text }));
    }
    tbody.append(tr);
  }
  table.append(thead, tbody);
}

export function setStatus(elm, text, kind = '') {
  elm.textContent = text;
  elm.className = `small ${kind === 'ok' ? 'ok-note' : kind === 'error' ? 'err-note' : ''}`;
}
