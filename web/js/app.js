// forensim serve's front end: a hash router over the views (runs, a run, the wound editor, desiccation,
// the skull editor)
// sharing one 3D stage. Each view marks document.body.dataset.ready = "1" once drawn, which the browser
// tests wait for.

import { Stage } from './stage.js';
import { showDesiccation } from './desiccation_view.js';
import { showRuns } from './runs_view.js';
import { showSkullEditor } from './skull_view.js';
import { showSurfaceRun } from './surface_view.js';
import { showWoundEditor, showWoundRun } from './wound_view.js';
import { describeRun } from './api.js';

const stage = new Stage(document.getElementById('canvas'));
const panel = document.getElementById('panel');
const overlay = document.getElementById('overlay');
const status = document.getElementById('status');
window.forensim = { stage };
// The stage draws on demand: any input in the side panel asks for a frame (views ask for their own after
// changes that arrive later, such as a server's answer).
for (const type of ['input', 'change', 'click']) panel.addEventListener(type, () => stage.requestRender());

async function showRun(ctx, params) {
  const path = params.get('path') || '';
  const run = await describeRun(path);
  if (run.kind === 'mummify') return showDesiccation(ctx, params);
  if (run.timeline) return showWoundRun(ctx, path);
  return showSurfaceRun(ctx, path);
}

const views = {
  runs: showRuns, run: showRun, wound: showWoundEditor, desiccation: showDesiccation, skull: showSkullEditor,
};

let generation = 0;
async function route() {
  const hash = location.hash.replace(/^#\/?/, '') || 'runs';
  const [name, query] = hash.split('?');
  const params = new URLSearchParams(query || '');
  const view = views[name] || showRuns;
  const mine = ++generation;
  document.body.dataset.ready = '0';
  document.body.dataset.view = name;
  for (const a of document.querySelectorAll('nav a')) {
    a.classList.toggle('active', a.dataset.view === name || (name === 'run' && a.dataset.view === 'runs'));
  }
  stage.clear();
  panel.innerHTML = '';
  overlay.textContent = '';
  status.textContent = 'loading\u2026';
  status.className = '';
  const ctx = {
    stage, panel, overlay,
    ready: () => {
      if (mine !== generation) return;
      status.textContent = '';
      document.body.dataset.ready = '1';
      stage.requestRender();
    },
  };
  try {
    await view(ctx, params);
  } catch (e) {
    if (mine !== generation) return;
    status.textContent = e.message;
    status.className = 'error';
    document.body.dataset.ready = 'error';
  }
}

window.addEventListener('hashchange', route);
route();
