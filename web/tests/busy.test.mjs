// When the page retries a busy station's answer (web/js/busy.js): 429 and 503 with Retry-After,
// as long as the header says within a bound, a few times; anything else is the caller's.

import { test } from 'node:test';
import assert from 'node:assert/strict';

import { BUSY_RETRIES, MAX_BUSY_WAIT_MS, busyRetryDelayMs } from '../js/busy.js';

test('a busy answer is retried after its Retry-After, a few times', () => {
  assert.equal(busyRetryDelayMs(503, '1', 0), 1000);
  assert.equal(busyRetryDelayMs(429, '2', 1), 2000);
  assert.equal(busyRetryDelayMs(503, ' 0 ', 0), 0);
  assert.equal(busyRetryDelayMs(429, '1', BUSY_RETRIES - 1), 1000);
  assert.equal(busyRetryDelayMs(429, '1', BUSY_RETRIES), null);
});

test('the wait is bounded and a date counts as a second', () => {
  assert.equal(busyRetryDelayMs(503, '3600', 0), MAX_BUSY_WAIT_MS);
  assert.equal(busyRetryDelayMs(503, 'Wed, 21 Oct 2015 07:28:00 GMT', 0), 1000);
});

test('anything else is not retried', () => {
  for (const status of [200, 400, 401, 404, 500, 502]) assert.equal(busyRetryDelayMs(status, '1', 0), null, String(status));
  // A 503 without Retry-After (a proxy's, say) is not the station's "busy".
  assert.equal(busyRetryDelayMs(503, null, 0), null);
});
