// When the station is busy (docs/api.md, "Request work"): a 503 (every request worker taken, the
// queue full) or a 429 (this address has its expensive requests running already) carries
// Retry-After, and nothing was done. The page waits as asked and asks again, a few times, rather
// than showing an error for a moment's load.

/** The attempts after the first. */
export const BUSY_RETRIES = 3;
/** Never wait longer than this for one retry, whatever the server says. */
export const MAX_BUSY_WAIT_MS = 5000;

/** How long to wait before retrying an answer with this status and Retry-After header, on the
 *  given retry (0 for the first); null: do not retry (not busy, no Retry-After, or retried enough).
 *  Retry-After is read as seconds; an HTTP date or anything else counts as one second. */
export function busyRetryDelayMs(status, retryAfter, retry) {
  if ((status !== 429 && status !== 503) || retryAfter == null || retry >= BUSY_RETRIES) return null;
  const seconds = /^\s*\d+\s*$/.test(retryAfter) ? Number(retryAfter) : 1;
  return Math.min(MAX_BUSY_WAIT_MS, Math.max(0, seconds * 1000));
}

/** fetch, retried while the station answers busy (busyRetryDelayMs). */
export async function fetchUnlessBusy(url, init) {
  for (let retry = 0; ; retry++) {
    const res = await fetch(url, init);
    const wait = busyRetryDelayMs(res.status, res.headers.get('Retry-After'), retry);
    if (wait === null) return res;
    await new Promise((resolve) => setTimeout(resolve, wait));
  }
}
