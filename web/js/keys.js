// Keyboard shortcuts, discoverable: `?` (or the ? button in the header) opens a list of them.
// Single keys without modifiers, off while the focus is in a field so that typing a mission's
// numbers never switches a view. Alt+1…8 (router.js) work everywhere, fields included.

import { VIEWS, currentView } from './router.js';
import { acknowledge, toggleMute } from './alarms.js';
import { toggleTheme } from './theme.js';

const KEYS = [
  ['1 … 8', 'switch view: Live, Replay, Mission, CKT, Compare, Model, Encounter, Export'],
  ['f', 'fit the Live track plot to the track'],
  ['a', 'acknowledge the alarms'],
  ['m', 'mute or unmute the alarm sound'],
  ['t', 'toggle the dark theme'],
  ['?', 'show this list'],
  ['Esc', 'close this list'],
];

let lastFocus = null;

function typing(target) {
  if (!(target instanceof Element)) return false;
  return target.isContentEditable || ['INPUT', 'TEXTAREA', 'SELECT'].includes(target.tagName);
}

export function helpOpen() {
  return !document.getElementById('help-overlay').hidden;
}

export function openHelp() {
  const o = document.getElementById('help-overlay');
  if (!o.hidden) return;
  lastFocus = document.activeElement;
  // A dialog only while open (a hidden one would still be found by assistive tools' lists).
  o.setAttribute('role', 'dialog');
  o.setAttribute('aria-modal', 'true');
  o.hidden = false;
  document.getElementById('help-close').focus();
}

export function closeHelp() {
  const o = document.getElementById('help-overlay');
  if (o.hidden) return;
  o.hidden = true;
  o.removeAttribute('role');
  o.removeAttribute('aria-modal');
  if (lastFocus instanceof HTMLElement) lastFocus.focus();
}

function onKey(ev) {
  if (ev.key === 'Escape' && helpOpen()) {
    ev.preventDefault();
    closeHelp();
    return;
  }
  if (ev.ctrlKey || ev.metaKey || ev.altKey || ev.isComposing || typing(ev.target)) return;
  const n = Number(ev.key);
  let done = true;
  if (Number.isInteger(n) && n >= 1 && n <= VIEWS.length) {
    closeHelp();
    window.location.hash = `#${VIEWS[n - 1]}`;
  } else if (ev.key === '?') {
    if (helpOpen()) closeHelp();
    else openHelp();
  } else if (ev.key === 'f') {
    if (currentView() === 'live') document.getElementById('live-fit')?.click();
  } else if (ev.key === 'a') {
    acknowledge();
  } else if (ev.key === 'm') {
    toggleMute();
  } else if (ev.key === 't') {
    toggleTheme();
  } else {
    done = false;
  }
  if (done) ev.preventDefault();
}

export function initKeys() {
  const dl = document.getElementById('help-keys');
  dl.replaceChildren(
    ...KEYS.flatMap(([k, what]) => {
      const dt = document.createElement('dt');
      for (const [i, part] of k.split(' … ').entries()) {
        if (i) dt.append(' … ');
        const kbd = document.createElement('kbd');
        kbd.textContent = part;
        dt.append(kbd);
      }
      const dd = document.createElement('dd');
      dd.textContent = what;
      return [dt, dd];
    }),
  );
  document.getElementById('help-toggle').addEventListener('click', openHelp);
  document.getElementById('help-close').addEventListener('click', closeHelp);
  // A click on the shade outside the box closes it as Esc does.
  document.getElementById('help-overlay').addEventListener('click', (ev) => {
    if (ev.target.id === 'help-overlay') closeHelp();
  });
  window.addEventListener('keydown', onKey);
}
