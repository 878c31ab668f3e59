// Waiting in the browser tests: every wait is for a condition, with a limit scaled by
// AVK_E2E_SLOW (default 4) so that a 2-core machine running other builds beside the browser
// reaches none of them. A limit is how long to wait before calling the page broken, not a speed
// the page must have.

export const SLOW = Number(process.env.AVK_E2E_SLOW || 4);
export const slow = (ms) => ms * SLOW;

export function sleep(ms) {
  return new Promise((r) => setTimeout(r, ms));
}

/** Polls fn until it returns a truthy value; fails with `what` after slow(timeoutMs). */
export async function until(what, fn, timeoutMs = 20000, stepMs = 250) {
  const end = Date.now() + slow(timeoutMs);
  let last;
  while (Date.now() < end) {
    try {
      last = await fn();
      if (last) return last;
    } catch (e) {
      last = e;
    }
    await sleep(stepMs);
  }
  throw new Error(`timed out after ${slow(timeoutMs)} ms waiting for ${what} (last: ${last instanceof Error ? last.message : JSON.stringify(last)})`);
}
