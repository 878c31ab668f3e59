// The page's one binary search (web/js/bisect.js) against a linear scan, on time arrays with
// repeats, gaps and out-of-range queries; and through a ring whose oldest sample is not at 0.

import { test } from 'node:test';
import assert from 'node:assert/strict';

import { firstAtOrAfter, lastAtOrBefore } from '../js/bisect.js';

// A small seeded generator: the cases are the same on every run.
function lcg(seed) {
  let s = seed >>> 0;
  return () => {
    s = (Math.imul(s, 1664525) + 1013904223) >>> 0;
    return s / 2 ** 32;
  };
}

function sortedTimes(rand, n) {
  const ts = [];
  let t = 100 * rand();
  for (let i = 0; i < n; i++) {
    if (rand() > 0.3) t += rand() < 0.1 ? 50 * rand() : 0.1 * Math.ceil(10 * rand());
    ts.push(t); // about a third repeat the time before them
  }
  return ts;
}

test('firstAtOrAfter and lastAtOrBefore agree with a linear scan', () => {
  const rand = lcg(19);
  for (let c = 0; c < 300; c++) {
    const ts = sortedTimes(rand, Math.floor(40 * rand()));
    const queries = [...ts, ...ts.map((t) => t + 0.05), -1e9, 1e9, ...ts.map((t) => t - 1e-9)];
    for (const q of queries) {
      let first = ts.findIndex((t) => t >= q);
      if (first < 0) first = ts.length;
      let last = -1;
      ts.forEach((t, i) => { if (t <= q) last = i; });
      assert.equal(firstAtOrAfter(ts.length, (i) => ts[i], q), first, `first ≥ ${q} in ${ts}`);
      assert.equal(lastAtOrBefore(ts.length, (i) => ts[i], q), Math.max(0, last), `last ≤ ${q} in ${ts}`);
    }
  }
});

test('repeated times: the first of them, the last of them', () => {
  const ts = [1, 2, 2, 2, 3];
  assert.equal(firstAtOrAfter(ts.length, (i) => ts[i], 2), 1);
  assert.equal(lastAtOrBefore(ts.length, (i) => ts[i], 2), 3);
  assert.equal(firstAtOrAfter(0, () => assert.fail('an empty range reads nothing'), 5), 0);
  assert.equal(lastAtOrBefore(0, () => assert.fail('an empty range reads nothing'), 5), 0);
});

test('through a ring: the index counts from the oldest sample, wherever it is stored', () => {
  const capacity = 8;
  const stored = [6, 7, 8, 1, 2, 3, 4, 5]; // the oldest (1) at slot 3
  const start = 3;
  const at = (i) => stored[(start + i) % capacity];
  for (let t = 0; t <= 9; t += 0.5) {
    const expected = Math.min(8, Math.max(0, Math.ceil(t) - 1));
    assert.equal(firstAtOrAfter(capacity, at, t), expected, `t = ${t}`);
  }
});
