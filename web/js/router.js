// Hash routing (#live, #replay, #mission, #ckt, #compare, #model, #encounter, #export): the address names the view,
// so views can be bookmarked and the back button works. The tabs are plain links (Tab and Enter
// reach them); Alt+1…8 jump to a view from anywhere, and the arrow keys move along the tabs.

import { resizeWithin } from './plots.js';

export const VIEWS = ['live', 'replay', 'mission', 'ckt', 'compare', 'model', 'encounter', 'export'];

let handlers = {};
let current = null;

export function currentView() {
  return current;
}

function viewFromHash() {
  const name = window.location.hash.replace(/^#/, '').split(/[?&/]/)[0];
  return VIEWS.includes(name) ? name : 'live';
}

function activate() {
  const next = viewFromHash();
  if (next === current) return;
  const prev = current;
  current = next;
  for (const v of VIEWS) {
    const section = document.getElementById(`view-${v}`);
    section.hidden = v !== next;
    const tab = document.querySelector(`#tabs a[data-view="${v}"]`);
    if (v === next) tab.setAttribute('aria-current', 'page');
    else tab.removeAttribute('aria-current');
  }
  document.title = `AVK Station · ${next[0].toUpperCase()}${next.slice(1)}`;
  if (prev) handlers[prev]?.(false);
  handlers[next]?.(true);
  // Plots drawn while hidden were sized for nothing: fit them now that the view is laid out.
  requestAnimationFrame(() => resizeWithin(document.getElementById(`view-${next}`)));
}

/** Draws the view on screen again (the theme changed: its plots take the new colours). */
export function refreshView() {
  if (!current) return;
  handlers[current]?.(true);
  requestAnimationFrame(() => resizeWithin(document.getElementById(`view-${current}`)));
}

export function initRouter(viewHandlers) {
  handlers = viewHandlers;
  window.addEventListener('hashchange', activate);
  const tabs = [...document.querySelectorAll('#tabs a')];
  document.getElementById('tabs').addEventListener('keydown', (ev) => {
    const i = tabs.indexOf(document.activeElement);
    if (i < 0) return;
    let j = null;
    if (ev.key === 'ArrowRight') j = (i + 1) % tabs.length;
    else if (ev.key === 'ArrowLeft') j = (i - 1 + tabs.length) % tabs.length;
    else if (ev.key === 'Home') j = 0;
    else if (ev.key === 'End') j = tabs.length - 1;
    if (j !== null) {
      ev.preventDefault();
      tabs[j].focus();
    }
  });
  window.addEventListener('keydown', (ev) => {
    if (!ev.altKey || ev.ctrlKey || ev.metaKey) return;
    const n = Number(ev.key);
    if (n >= 1 && n <= VIEWS.length) {
      ev.preventDefault();
      window.location.hash = `#${VIEWS[n - 1]}`;
    }
  });
  activate();
}
