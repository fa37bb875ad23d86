// Desiccation: a mummify run's frames stepped on its surface in false colour (water, moisture), with the
// original shape as a ghost; and a form that starts a run with an environment and a duration and shows its
// frames as they are written.

import * as THREE from 'three';
import { describeRun, followJob, frameSurface, listRuns, startJob } from './api.js';
import { cameraControls, cutControls } from './stage.js';
import { steppedTimeline } from './timeline_control.js';
import { formatDays } from './time_units.js';
import { escapeHtml, html } from './util.js';

// Dry (brown) to wet (blue) through straw yellow.
const STOPS = [[0.545, 0.145, 0.0], [0.941, 0.753, 0.314], [0.173, 0.498, 0.722]];

export function falseColour(x) {
  const t = Math.min(1, Math.max(0, x)) * (STOPS.length - 1);
  const i = Math.min(STOPS.length - 2, Math.floor(t)), f = t - i;
  return STOPS[i].map((c, k) => c + (STOPS[i + 1][k] - c) * f);
}

function geometryOf(frame, positions, field, range) {
  const g = new THREE.BufferGeometry();
  g.setAttribute('position', new THREE.Float32BufferAttribute(positions, 3));
  g.setIndex(frame.triangles);
  const values = frame.scalars[field] || [];
  const colours = new Float32Array(3 * frame.vertex_count);
  const span = range[1] - range[0];
  for (let v = 0; v < frame.vertex_count; ++v) {
    colours.set(falseColour(span > 0 ? (values[v] - range[0]) / span : 1), 3 * v);
  }
  g.setAttribute('color', new THREE.Float32BufferAttribute(colours, 3));
  g.computeVertexNormals();
  return g;
}

async function showRun(ctx, path, job) {
  const run = await describeRun(path);
  if (!run.frames) throw new Error(`run '${path}' has no desiccation.pvd (not a mummify run)`);
  const facts = run.record.facts || {};
  html(ctx.panel, `<h2>Desiccation run ${escapeHtml(path)}</h2><div class="muted" id="run-facts">` +
    `${run.frames.length} frames` +
    (facts.mass_percent ? `; at the end mass ${facts.mass_percent.toFixed(1)} %, water ` +
      `${facts.water_percent.toFixed(1)} %, volume ${facts.volume_percent.toFixed(1)} % of initial` : '') + '</div>');
  const controls = html(ctx.panel, `<label>Field <select id="field"></select></label>
    <div class="legend"></div><div class="row muted"><span id="range-lo"></span><span style="margin-left:auto"
    id="range-hi"></span></div><label><input type="checkbox" id="ghost" checked> original shape</label>`);
  const cache = new Map();
  const load = async (i) => {
    if (!cache.has(i)) cache.set(i, frameSurface(`${path}/${run.frames[i].file}`));
    return cache.get(i);
  };
  const [first, last] = await Promise.all([load(0), load(run.frames.length - 1)]);
  // One range over the run (its first and last frames), so colours compare across frames.
  const rangeOf = (field) => {
    const a = first.ranges[field] || [0, 1], b = last.ranges[field] || a;
    return [Math.min(a[0], b[0]), Math.max(a[1], b[1])];
  };
  const fields = Object.keys(first.scalars);
  const select = controls.querySelector('#field');
  for (const f of fields) select.add(new Option(f, f));
  if (fields.includes('water_percent')) select.value = 'water_percent';
  const material = new THREE.MeshStandardMaterial({ vertexColors: true, roughness: 0.8, side: THREE.DoubleSide });
  const mesh = new THREE.Mesh(new THREE.BufferGeometry(), material);
  mesh.scale.setScalar(0.001);  // mm to m, as the wound views
  const ghost = new THREE.Mesh(geometryOf(first, first.rest_positions, select.value, [0, 1]),
    new THREE.MeshBasicMaterial({ color: 0xffffff, wireframe: true, transparent: true, opacity: 0.08 }));
  ghost.scale.setScalar(0.001);
  ctx.stage.add(mesh);
  ctx.stage.add(ghost);
  controls.querySelector('#ghost').onchange = (e) => { ghost.visible = e.target.checked; };
  let shown = 0, cut = null;
  const draw = async (i) => {
    const frame = await load(i);
    const field = select.value;
    const range = rangeOf(field);
    controls.querySelector('#range-lo').textContent = range[0].toPrecision(3);
    controls.querySelector('#range-hi').textContent = range[1].toPrecision(3);
    mesh.geometry.dispose();
    mesh.geometry = geometryOf(frame, frame.positions, field, range);
    if (cut) cut.apply();
    shown = i;
    document.body.dataset.frame = String(i);
    ctx.overlay.textContent = formatDays(run.frames[i].time_days);
  };
  select.onchange = () => draw(shown);
  const timeline = steppedTimeline(ctx.panel, ctx.stage, {
    count: run.frames.length,
    labelOf: (i) => `${formatDays(run.frames[i].time_days)} (frame ${i + 1} of ${run.frames.length})`,
    onStep: draw,
  });
  await timeline.go(0);
  ctx.stage.fit(mesh, 'oblique');
  cameraControls(ctx.panel, ctx.stage, () => `${path.replace(/\//g, '_')}_frame${shown}.png`);
  cut = cutControls(ctx.panel, ctx.stage);
  window.forensim.frames = { count: () => run.frames.length, go: (i) => timeline.go(i) };
  // While its job runs, new frames appear as the run writes them.
  if (job && job.state === 'running') {
    const timer = setInterval(async () => {
      if (!document.body.contains(controls)) return clearInterval(timer);
      const fresh = await describeRun(path).catch(() => null);
      if (fresh && fresh.frames.length > run.frames.length) {
        run.frames = fresh.frames;
        timeline.setCount(run.frames.length);
      }
    }, 2000);
  }
  ctx.ready();
}

function startForm(ctx) {
  const form = html(ctx.panel, `<h2>Start a desiccation run</h2>
    <label>Body <select id="phantom"><option value="arm">arm phantom</option>
      <option value="head">head phantom</option></select></label>
    <label>Days <input type="number" id="days" value="7" min="0.1" max="3650" step="0.5"></label>
    <label>Frames <input type="number" id="frames" value="6" min="1" max="100"></label>
    <label>Air temperature (&deg;C) <input type="number" id="temperature" value="35" min="-40" max="80"></label>
    <label>Relative humidity (%) <input type="number" id="humidity" value="20" min="0" max="99"></label>
    <label>Wind (m/s) <input type="number" id="wind" value="1" min="0" max="50" step="0.5"></label>
    <label><input type="checkbox" id="ground"> lying on the ground</label>
    <button id="start">Start</button> <span id="job"></span>`);
  const $ = (id) => form.querySelector('#' + id);
  $('start').onclick = async () => {
    $('start').disabled = true;
    const output = `mummify-${new Date().toISOString().replace(/[-:]/g, '').replace(/\..*/, '')}`;
    try {
      const job = await startJob({
        kind: 'mummify', output,
        job: {
          version: 1, body: { phantom: $('phantom').value, size: 'small' }, days: Number($('days').value),
          frames: Number($('frames').value),
          environment: { temperature_c: Number($('temperature').value), humidity_percent: Number($('humidity').value),
                         wind_m_per_s: Number($('wind').value), on_ground: $('ground').checked },
        },
      });
      let opened = false;
      await followJob(job.id, async (j) => {
        $('job').textContent = `${j.state} ${(100 * (j.progress.fraction || 0)).toFixed(0)} %`;
        if (!opened && j.state === 'running' && j.progress.done > 0) {
          opened = true;
          ctx.stage.clear();
          const keep = form;
          ctx.panel.innerHTML = '';
          ctx.panel.appendChild(keep);
          await showRun(ctx, output, j).catch(() => { opened = false; });
        }
      }, 1000);
      if (!opened) location.hash = '#/desiccation?path=' + encodeURIComponent(output);
    } catch (e) {
      $('job').className = 'error';
      $('job').textContent = e.message + (e.field ? ` (${e.field})` : '');
    } finally {
      $('start').disabled = false;
    }
  };
}

export async function showDesiccation(ctx, params) {
  const path = params.get('path');
  if (path) return showRun(ctx, path);
  startForm(ctx);
  const runs = (await listRuns()).runs.filter((r) => r.command === 'mummify');
  const list = html(ctx.panel, '<h2>Desiccation runs</h2>');
  if (!runs.length) list.appendChild(Object.assign(document.createElement('div'), { className: 'muted', textContent: 'none yet' }));
  for (const r of runs) {
    const a = document.createElement('a');
    a.href = '#/desiccation?path=' + encodeURIComponent(r.path);
    a.textContent = r.path || '(served folder)';
    a.style.display = 'block';
    list.appendChild(a);
  }
  ctx.ready();
}
