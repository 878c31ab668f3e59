// The control token. `avk serve` prints a dashboard URL carrying ?token=…; we keep it in
// sessionStorage (gone when the tab closes) and take it out of the address bar so that it does not
// end up in bookmarks, screenshots or the history. Every POST needs it; reads need it too from any
// address but loopback (a published Docker port, a LAN), so the page sends it on every request and
// on the stream whenever it has one.
//
// The token bar asks for it inline (never a modal). It stays until a request sent with the token
// entered is answered with anything but 401: a refused token is said to be refused, the bar keeps
// its place, and the operator tries again. Hiding it on submit left a wrong token a dead end (the
// page showed DISCONNECTED and no mission, and nothing said why).

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

let waiting = null; // {promise, resolve, reject} of the prompt on screen
let refusals = 0; // tokens refused since the page loaded (the bar's data-refused, for the tests)
let entries = 0; // tokens entered in the bar so far: one refusal is counted per token entered
let counted = -1; // the entry whose refusal was counted

// What the bar says in each state: asked for (none was sent), refused (the one sent was not the
// station's), checking (entered, its request under way).
const SAY = {
  missing: 'The server wants its token (401).',
  refused: 'Token refused (401): the station does not accept this token. Enter it again.',
  checking: 'Checking the token…',
};

function showBar(stateName) {
  const bar = document.getElementById('token-bar');
  const say = document.getElementById('token-state');
  bar.dataset.state = stateName;
  bar.dataset.refused = String(refusals);
  if (say) say.textContent = SAY[stateName];
  bar.hidden = false;
}

/** Shows the inline token bar and resolves with the token the operator enters, or rejects when
 *  they cancel. Concurrent callers share one prompt. `refusedToken`: the token the station just
 *  refused (the bar says so), '' when the request carried none. */
export function requestToken(refusedToken = '') {
  const input = document.getElementById('token-input');
  if (refusedToken) {
    // Several requests refused with the same token are one refusal.
    if (counted !== entries) refusals++;
    counted = entries;
    showBar('refused');
  } else if (!waiting) {
    showBar('missing');
  }
  if (waiting) return waiting.promise;
  let resolve;
  let reject;
  const promise = new Promise((res, rej) => {
    resolve = res;
    reject = rej;
  });
  waiting = { promise, resolve, reject };
  input.value = '';
  input.focus();
  return promise;
}

/** A request sent with `token` was answered with anything but 401: the station takes it, so the
 *  bar, still up while the entered token was being checked, goes. */
export function tokenAccepted(token) {
  const bar = document.getElementById('token-bar');
  if (!bar || bar.hidden || waiting || !token || token !== getToken()) return;
  bar.hidden = true;
  bar.dataset.state = 'accepted';
}

export function initTokenBar() {
  const bar = document.getElementById('token-bar');
  const input = document.getElementById('token-input');
  bar.addEventListener('submit', (ev) => {
    ev.preventDefault();
    const token = input.value.trim();
    if (!token) return;
    entries++;
    showBar('checking');
    setToken(token);
    if (waiting) {
      const w = waiting;
      waiting = null;
      w.resolve(token);
    }
  });
  document.getElementById('token-cancel').addEventListener('click', () => {
    bar.hidden = true;
    bar.dataset.state = 'cancelled';
    if (waiting) {
      const w = waiting;
      waiting = null;
      w.reject(new Error('no control token given'));
    }
  });
}
