// The dark theme for night work: the page's colours are CSS variables (app.css, html[data-theme]),
// the plots take theirs from plots.js. The choice is remembered in localStorage; without one the
// system's preference (prefers-color-scheme) decides.

import { emit } from './state.js';
import { applyPlotTheme } from './plots.js';
import { refreshView } from './router.js';

const KEY = 'avk-theme';

export function currentTheme() {
  return document.documentElement.dataset.theme === 'dark' ? 'dark' : 'light';
}

export function setTheme(name, { remember = true } = {}) {
  const theme = name === 'dark' ? 'dark' : 'light';
  document.documentElement.dataset.theme = theme;
  document.documentElement.style.colorScheme = theme; // form controls and scroll bars follow
  if (remember) {
    try {
      localStorage.setItem(KEY, theme);
    } catch {
      // private mode: the choice lasts for this page
    }
  }
  const b = document.getElementById('theme-toggle');
  if (b) {
    b.setAttribute('aria-pressed', String(theme === 'dark'));
    b.textContent = theme === 'dark' ? '☀ Light' : '◐ Dark';
    b.title = theme === 'dark' ? 'Light theme (t)' : 'Dark theme for night work (t)';
  }
  applyPlotTheme(theme);
  emit('theme', theme);
}

export function toggleTheme() {
  setTheme(currentTheme() === 'dark' ? 'light' : 'dark');
  refreshView();
}

/** Before the views draw: the remembered theme, else the system's. */
export function initTheme() {
  let stored = null;
  try {
    stored = localStorage.getItem(KEY);
  } catch {
    stored = null;
  }
  const system = window.matchMedia?.('(prefers-color-scheme: dark)').matches ? 'dark' : 'light';
  setTheme(stored ?? system, { remember: false });
  document.getElementById('theme-toggle')?.addEventListener('click', toggleTheme);
  // Following the system while the operator has not chosen.
  window.matchMedia?.('(prefers-color-scheme: dark)').addEventListener?.('change', (e) => {
    let chosen = null;
    try {
      chosen = localStorage.getItem(KEY);
    } catch {
      chosen = null;
    }
    if (!chosen) {
      setTheme(e.matches ? 'dark' : 'light', { remember: false });
      refreshView();
    }
  });
}
