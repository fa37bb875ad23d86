// Desiccation: a mummify run's frames stepped on its surface (the volume's outer surface or the skin) in false
// colour (moisture, shrinkage, any field) or the skin's own colour, with the original shape as a ghost; and a
// form that starts a run with an environment and a duration and shows its frames as they are written.

import * as THREE from 'three';
import { describeRun, followJob, frameSurface, listRuns, startJob } from './api.js';
import { cameraControls, cutControls } from './stage.js';
import { steppedTimeline } from './timeline_control.js';
import { formatDays } from './time_units.js';
import { colourModes, coloursOf, legend, rangeOf, seriesRange } from './false_colour.js';
import { escapeHtml, html } from './util.js';

/// A BufferGeometry of a frame's surface at `positions` (mm) with per-vertex `colours` (linear RGB).
export function surfaceGeometry(frame, positions, colours) {
  const g = new THREE.BufferGeometry();
  g.setAttribute('position', new THREE.Float32BufferAttribute(positions, 3));
  g.setIndex(frame.triangles);
  if (colours) g.setAttribute('color', new THREE.Float32BufferAttribute(colours, 3));
  g.computeVertexNormals();
  return g;
}

/// Colours a series of surfaces (frames of one mesh) by a chosen mode: the "Colour" menu, the legend, and one
/// range per mode over the series' first and last frames, so colours compare across frames.
export class FrameColouring {
  /// `load(i)` resolves frame i of the series; `onChange()` redraws.
  constructor(parent, onChange) {
    this.box = html(parent, '<label>Colour <select id="colour-mode"></select></label>');
    this.select = this.box.querySelector('#colour-mode');
    this.legend = legend(this.box);
    this.select.onchange = () => onChange();
  }

  /// Switches to a series: its frames from `load`, `count` of them; keeps the chosen mode when it has it.
  async setSeries(load, count) {
    this.load = load;
    this.count = count;
    this.ranges = new Map();
    this.first = await load(0);
    this.last = await load(count - 1);
    const keep = this.select.value;
    this.modes = colourModes(this.first);
    this.select.innerHTML = '';
    for (const m of this.modes) this.select.add(new Option(m.label, m.id));
    const ids = this.modes.map((m) => m.id);
    this.select.value = [keep, 'moisture', 'uncertainty'].find((id) => ids.includes(id)) || ids[0];
  }

  get mode() {
    return this.modes.find((m) => m.id === this.select.value) || this.modes[0];
  }

  /// The rest shape of `frame`: its own rest positions, else the series' first frame.
  restOf(frame) {
    return frame.rest_positions || this.first.positions;
  }

  range(mode) {
    if (!this.ranges.has(mode.id)) {
      const a = rangeOf(mode.values(this.first, this.restOf(this.first)));
      const b = rangeOf(mode.values(this.last, this.restOf(this.last)));
      this.ranges.set(mode.id, seriesRange(mode.id, a, b));
    }
    return this.ranges.get(mode.id);
  }

  /// Per-vertex linear RGB of `frame` in the chosen mode; updates the legend.
  colours(frame) {
    const mode = this.mode;
    if (mode.id === 'colour') {
      this.legend.show(mode, [0, 1]);
      return Float32Array.from(frame.vectors.colour);
    }
    const range = this.range(mode);
    this.legend.show(mode, range);
    return coloursOf(mode.values(frame, this.restOf(frame)), range, mode.map, frame.vertex_count);
  }
}

async function showRun(ctx, path, job) {
  const run = await describeRun(path);
  if (!run.frames) throw new Error(`run '${path}' has no desiccation.pvd (not a mummify run)`);
  const facts = run.record.facts || {};
  html(ctx.panel, `<h2>Desiccation run ${escapeHtml(path)}</h2><div class="muted" id="run-facts">` +
    `${run.frames.length} frames` +
    (facts.mass_percent ? `; at the end mass ${facts.mass_percent.toFixed(1)} %, water ` +
      `${facts.water_percent.toFixed(1)} %, volume ${facts.volume_percent.toFixed(1)} % of initial` : '') + '</div>');
  const series = { volume: run.frames };
  if (run.skin_frames && run.skin_frames.length) series.skin = run.skin_frames;
  const controls = html(ctx.panel, `<label>Surface <select id="surface"><option value="volume">volume (outer
    surface)</option>${series.skin ? '<option value="skin">skin</option>' : ''}</select></label>`);
  const surfaceSelect = controls.querySelector('#surface');
  const cache = new Map();
  const loader = (name) => (i) => {
    const key = `${name}:${i}`;
    if (!cache.has(key)) cache.set(key, frameSurface(`${path}/${series[name][i].file}`));
    return cache.get(key);
  };
  let shown = 0, cut = null, current = 'volume';
  const colouring = new FrameColouring(controls, () => draw(shown));
  html(controls, '<label><input type="checkbox" id="ghost" checked> original shape</label>');
  const material = new THREE.MeshStandardMaterial({ vertexColors: true, roughness: 0.8, side: THREE.DoubleSide });
  const mesh = new THREE.Mesh(new THREE.BufferGeometry(), material);
  mesh.scale.setScalar(0.001);  // mm to m, as the wound views
  const ghost = new THREE.Mesh(new THREE.BufferGeometry(),
    new THREE.MeshBasicMaterial({ color: 0xffffff, wireframe: true, transparent: true, opacity: 0.08 }));
  ghost.scale.setScalar(0.001);
  ctx.stage.add(mesh);
  ctx.stage.add(ghost);
  controls.querySelector('#ghost').onchange = (e) => { ghost.visible = e.target.checked; ctx.stage.requestRender(); };
  const frames = () => series[current];
  const draw = async (i) => {
    const frame = await loader(current)(i);
    mesh.geometry.dispose();
    mesh.geometry = surfaceGeometry(frame, frame.positions, colouring.colours(frame));
    if (cut) cut.apply();
    shown = i;
    document.body.dataset.frame = String(i);
    document.body.dataset.colour = colouring.mode.id;
    ctx.overlay.textContent = formatDays(frames()[i].time_days);
    ctx.stage.requestRender();
  };
  const useSeries = async (name) => {
    current = name;
    await colouring.setSeries(loader(name), frames().length);
    ghost.geometry.dispose();
    ghost.geometry = surfaceGeometry(colouring.first, colouring.restOf(colouring.first), null);
    document.body.dataset.surface = name;
    ctx.stage.requestRender();
  };
  await useSeries('volume');
  const timeline = steppedTimeline(ctx.panel, ctx.stage, {
    count: frames().length,
    labelOf: (i) => `${formatDays(frames()[i].time_days)} (frame ${i + 1} of ${frames().length})`,
    onStep: draw,
  });
  surfaceSelect.onchange = async () => {
    await useSeries(surfaceSelect.value);
    timeline.setCount(frames().length);
    await timeline.go(Math.min(shown, frames().length - 1));
  };
  await timeline.go(0);
  ctx.stage.fit(mesh, 'oblique');
  cameraControls(ctx.panel, ctx.stage, () => `${path.replace(/\//g, '_')}_frame${shown}.png`);
  cut = cutControls(ctx.panel, ctx.stage);
  window.forensim.frames = { count: () => frames().length, go: (i) => timeline.go(i) };
  // While its job runs, new frames appear as the run writes them.
  if (job && job.state === 'running') {
    const timer = setInterval(async () => {
      if (!document.body.contains(controls)) return clearInterval(timer);
      const fresh = await describeRun(path).catch(() => null);
      if (fresh && fresh.frames.length > run.frames.length) {
        series.volume = run.frames = fresh.frames;
        if (series.skin && fresh.skin_frames) series.skin = fresh.skin_frames;
        timeline.setCount(frames().length);
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
