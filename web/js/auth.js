// The control token. `avk serve` prints a dashboard URL carrying ?token=…; we keep it in
// sessionStorage (gone when the tab closes) and take it out of the address bar so that it does not
// end up in bookmarks, screenshots or the history. Every POST needs it; reads need it too from any
// address but loopback (a published Docker port, a LAN), so the page sends it on every request and
// on the stream whenever it has one.

const KEY = 'avk-token';

export function adoptTokenFromUrl() {
  const url = new URL(window.location.href);
  const token = url.searchParams.get('token');
  if (token) {
    sessionStorage.setItem(KEY, token);
    url.searchParams.delete('token');
    history.replaceState(null, '', url.pathname + url.search + url.hash);
  }
}

export function getToken() {
  return sessionStorage.getItem(KEY) || '';
}

const listeners = [];

/** fn() runs after the operator enters a token (the stream reconnects with it). */
export function onTokenChange(fn) {
  listeners.push(fn);
}

export function setToken(token) {
  if (token) sessionStorage.setItem(KEY, token);
  else sessionStorage.removeItem(KEY);
  for (const fn of listeners) fn(token);
}

let waiting = null; // {resolve, reject} of the prompt on screen

/** Shows the inline token bar (never a modal) and resolves with the token the operator enters,
 *  or rejects when they cancel. Concurrent callers share one prompt. */
export function requestToken() {
  const bar = document.getElementById('token-bar');
  const input = document.getElementById('token-input');
  if (waiting) return waiting.promise;
  let resolve;
  let reject;
  const promise = new Promise((res, rej) => {
    resolve = res;
    reject = rej;
  });
  waiting = { promise, resolve, reject };
  bar.hidden = false;
  input.value = '';
  input.focus();
  return promise;
}

export function initTokenBar() {
  const bar = document.getElementById('token-bar');
  const input = document.getElementById('token-input');
  bar.addEventListener('submit', (ev) => {
    ev.preventDefault();
    const token = input.value.trim();
    if (!token) return;
    setToken(token);
    bar.hidden = true;
    if (waiting) {
      waiting.resolve(token);
      waiting = null;
    }
  });
  document.getElementById('token-cancel').addEventListener('click', () => {
    bar.hidden = true;
    if (waiting) {
      waiting.reject(new Error('no control token given'));
      waiting = null;
    }
  });
}
