// The REST API (docs/api.md). Errors arrive as RFC 9457 problem+json; they become ApiError with
// the status, the detail and, for mission validation, errors[] with JSON-pointer fields.

import { getToken, requestToken, tokenAccepted } from './auth.js';
import { fetchUnlessBusy } from './busy.js';

export const BASE = '/api/v1';

export class ApiError extends Error {
  constructor(status, problem) {
    super(problem?.detail || problem?.title || `HTTP ${status}`);
    this.status = status;
    this.problem = problem || {};
    this.errors = Array.isArray(problem?.errors) ? problem.errors : [];
  }
}

export function apiUrl(path, params) {
  const url = new URL(BASE + path, window.location.origin);
  if (params) {
    for (const [k, v] of Object.entries(params)) {
      if (v === undefined || v === null || v === '') continue;
      if (Array.isArray(v)) v.forEach((item) => url.searchParams.append(k, item));
      else url.searchParams.set(k, v);
    }
  }
  return url.pathname + url.search;
}

async function problemOf(res) {
  const text = await res.text();
  try {
    return JSON.parse(text);
  } catch {
    return { detail: text.slice(0, 200) || res.statusText };
  }
}

/** fetch with the bearer token whenever the page has one: off this machine (a published Docker
 *  port, a LAN) every request needs it, reads included. A 401 asks for the token inline (never a
 *  modal), saying so when the token sent was refused, and sends the request again with each token
 *  the operator enters until one is taken; concurrent 401s share one prompt. A cancelled prompt
 *  leaves the 401 to the caller. A busy station's 429/503 is retried as it asks (busy.js). */
async function authedFetch(url, init = {}) {
  for (;;) {
    const headers = { ...(init.headers || {}) };
    const token = getToken();
    if (token) headers.Authorization = `Bearer ${token}`;
    const res = await fetchUnlessBusy(url, { ...init, headers });
    if (res.status !== 401) {
      tokenAccepted(token);
      return res;
    }
    // Another token was entered while this request was under way: try that one first.
    if (getToken() !== token) continue;
    try {
      await requestToken(token);
    } catch {
      return res; // the operator cancelled: the caller reports the 401
    }
  }
}

export async function getJson(path, params, { signal } = {}) {
  const res = await authedFetch(apiUrl(path, params), { headers: { Accept: 'application/json' }, signal });
  if (!res.ok) throw new ApiError(res.status, await problemOf(res));
  return res.json();
}

/** GET as text (CSV); returns {text, headers}. */
export async function getText(path, params, accept = 'text/csv') {
  const res = await authedFetch(apiUrl(path, params), { headers: { Accept: accept } });
  if (!res.ok) throw new ApiError(res.status, await problemOf(res));
  return { text: await res.text(), headers: res.headers };
}

/** GET as bytes (a binary download such as an MCAP file); returns {blob, headers}. */
export async function getBlob(path, params, accept) {
  const res = await authedFetch(apiUrl(path, params), { headers: { Accept: accept } });
  if (!res.ok) throw new ApiError(res.status, await problemOf(res));
  return { blob: await res.blob(), headers: res.headers };
}

/** POST with the bearer token (a 401 asks for it inline and is sent again with it, as every request). */
export async function postJson(path, body) {
  const headers = { Accept: 'application/json' };
  if (body !== undefined) headers['Content-Type'] = 'application/json';
  const res = await authedFetch(apiUrl(path), {
    method: 'POST',
    headers,
    body: body === undefined ? undefined : JSON.stringify(body),
  });
  if (!res.ok) throw new ApiError(res.status, await problemOf(res));
  const text = await res.text();
  return text ? JSON.parse(text) : {};
}

/** Every page of a keyset collection (`{items, next}`), up to maxItems. */
export async function getAllItems(path, params = {}, maxItems = 10000) {
  const out = [];
  let after;
  for (;;) {
    const page = await getJson(path, { ...params, limit: 1000, after });
    out.push(...page.items);
    if (page.next === null || page.next === undefined || out.length >= maxItems) break;
    after = page.next;
  }
  return out;
}
