// The wound views: a wound run's healing timeline on its mesh, and the wound editor (paint strokes on a
// mesh with a brush by ray casting, generate the timeline with `forensim wound` on the server, scrub it).

import * as THREE from 'three';
import { GLTFLoader } from 'three/addons/loaders/GLTFLoader.js';
import { describeRun, fileUrl, followJob, startJob } from './api.js';
import { cameraControls, cutControls } from './stage.js';
import { continuousTimeline } from './timeline_control.js';
import { WoundTimeline } from './wound_timeline.js';
import { escapeHtml, html } from './util.js';

const gltfLoader = new GLTFLoader();

function loadGlb(url) {
  return new Promise((resolve, reject) => gltfLoader.load(url, (g) => resolve(g.scene), undefined,
    () => reject(new Error('cannot load ' + url))));
}

function meshesOf(object) {
  const out = [];
  object.traverse((o) => { if (o.isMesh) out.push(o); });
  return out;
}


/// Shows the timeline of a loaded WoundTimeline on `object` with the slider in `panel`.
function showTimeline(ctx, object, tl, title) {
  for (const m of meshesOf(object)) m.material = tl.material;
  const info = html(ctx.panel, `<h2>${escapeHtml(title)}</h2><div class="muted">${escapeHtml(tl.timeline.type)}, ` +
    `${tl.timeline.key_files.length} key positions, ${tl.timeline.texture_size[0]}&sup2; maps, ` +
    `${(tl.timeline.texels_per_mm || 0).toFixed(1)} texels/mm</div><div id="phase"></div>`);
  const phase = info.querySelector('#phase');
  const control = continuousTimeline(ctx.panel, ctx.stage, {
    t0: tl.startTime, t1: tl.endTime,
    onTime: (t) => {
      tl.setTime(t);
      phase.textContent = 'phase: ' + tl.phaseLabel();
      ctx.overlay.textContent = document.getElementById('time-label')?.textContent || '';
      document.body.dataset.time = String(t);
    },
  });
  const fps = html(ctx.panel, '<div class="muted" id="fps"></div>');
  const timer = setInterval(() => {
    if (!document.body.contains(fps)) return clearInterval(timer);
    const rate = ctx.stage.fps();
    fps.firstChild.textContent = rate > 0 ? `${rate.toFixed(0)} frames/s` : 'idle (drawn on change)';
  }, 500);
  window.forensim.timeline = tl;
  window.forensim.timelineControl = control;
  return control;
}

/// The run's map set and GLBs as download links (the export of the map set).
function exportList(parent, path, files) {
  const box = html(parent, '<h2>Export</h2>');
  const details = document.createElement('details');
  details.innerHTML = '<summary>maps and GLB</summary>';
  for (const f of files.filter((x) => /^maps\/|\.glb$|^timeline\.json$/.test(x.path))) {
    const a = document.createElement('a');
    a.href = fileUrl(path + '/' + f.path);
    a.download = f.path.split('/').pop();
    a.textContent = `${f.path} (${(f.bytes / 1024).toFixed(0)} KiB)`;
    a.style.display = 'block';
    details.appendChild(a);
  }
  box.appendChild(details);
}

export async function showWoundRun(ctx, path) {
  const run = await describeRun(path);
  if (!run.timeline) throw new Error(`run '${path}' has no timeline.json (not a wound run)`);
  const glb = run.files.map((f) => f.path).find((p) => /^wound_.*\.glb$/.test(p));
  if (!glb) throw new Error(`run '${path}' has no wound GLB`);
  const [object, tl] = await Promise.all([loadGlb(fileUrl(path + '/' + glb)), WoundTimeline.load(run, ctx.stage.renderer)]);
  ctx.stage.add(object);
  ctx.stage.fit(object);
  showTimeline(ctx, object, tl, `Wound run ${path}`);
  cameraControls(ctx.panel, ctx.stage, () => `${path.replace(/\//g, '_')}_${Math.round(tl.time)}s.png`);
  cutControls(ctx.panel, ctx.stage);
  exportList(ctx.panel, path, run.files);
  ctx.ready();
}

export async function showWoundEditor(ctx, params) {
  const meshName = params.get('mesh') || 'forearm-uv';
  const form = html(ctx.panel, `
    <h2>Wound editor</h2>
    <label>Mesh <select id="mesh">
      <option value="forearm-uv">forearm-uv (built-in)</option><option value="cylinder">cylinder (built-in)</option>
    </select></label>
    <label>Type <select id="type"><option>abrasion</option><option>bruise</option></select></label>
    <label>Brush radius <input type="range" id="radius" min="1" max="20" step="0.5" value="4">
      <span id="radius-label">4 mm</span></label>
    <label>Seed <input type="number" id="seed" value="1" min="0"></label>
    <label>Resolution <select id="resolution"><option>256</option><option selected>512</option>
      <option>1024</option><option>2048</option></select></label>
    <div class="row">
      <button id="paint" class="on">Painting</button><button id="clear">Clear</button>
      <button id="generate" disabled>Generate</button>
    </div>
    <div class="muted" id="strokes">Paint on the mesh with the left button (the right button orbits).</div>
    <div id="job"></div>`);
  const $ = (id) => form.querySelector('#' + id);
  $('mesh').value = meshName;
  $('mesh').onchange = () => { location.hash = '#/wound?mesh=' + $('mesh').value; };
  $('radius').oninput = () => { $('radius-label').textContent = `${$('radius').value} mm`; };
  cameraControls(ctx.panel, ctx.stage, 'forensim_wound.png');

  const object = await loadGlb(`/api/meshes/${encodeURIComponent(meshName)}.glb`);
  const skin = new THREE.MeshStandardMaterial({ color: 0xd9a68a, roughness: 0.7, side: THREE.DoubleSide });
  for (const m of meshesOf(object)) m.material = skin;
  ctx.stage.add(object);
  ctx.stage.fit(object, meshName === 'cylinder' ? 'front' : 'top');
  const marks = new THREE.Group();
  ctx.stage.add(marks);

  // Strokes: surface points in mm (the GLB is in metres, as glTF specifies).
  const strokes = [];
  let painting = true, current = null;
  const raycaster = new THREE.Raycaster();
  const pointer = new THREE.Vector2();
  const canvas = ctx.stage.canvas;
  const markMaterial = new THREE.MeshBasicMaterial({ color: 0xc0392b, transparent: true, opacity: 0.55 });
  const hit = (event) => {
    const r = canvas.getBoundingClientRect();
    pointer.set(((event.clientX - r.left) / r.width) * 2 - 1, -((event.clientY - r.top) / r.height) * 2 + 1);
    raycaster.setFromCamera(pointer, ctx.stage.camera);
    const hits = raycaster.intersectObjects(meshesOf(object), false);
    return hits.length ? hits[0].point : null;
  };
  const addPoint = (p) => {
    const mm = [p.x * 1000, p.y * 1000, p.z * 1000];
    const radius = Number($('radius').value);
    const prev = current.points[current.points.length - 1];
    if (prev && Math.hypot(mm[0] - prev[0], mm[1] - prev[1], mm[2] - prev[2]) < radius / 3) return;
    current.points.push(mm.map((v) => Math.round(v * 1000) / 1000));
    const dot = new THREE.Mesh(new THREE.SphereGeometry(radius / 1000 / 2, 10, 8), markMaterial);
    dot.position.copy(p);
    marks.add(dot);
    ctx.stage.requestRender();
  };
  const updateInfo = () => {
    const n = strokes.reduce((s, k) => s + k.points.length, 0);
    $('strokes').textContent = `${strokes.length} stroke(s), ${n} point(s)`;
    $('generate').disabled = strokes.length === 0;
    document.body.dataset.strokes = String(strokes.length);
  };
  canvas.addEventListener('pointerdown', (event) => {
    if (!painting || event.button !== 0) return;
    const p = hit(event);
    if (!p) return;
    ctx.stage.controls.enabled = false;
    ctx.stage.beginInteraction();
    current = { points: [], radius_mm: Number($('radius').value) };
    addPoint(p);
  });
  canvas.addEventListener('pointermove', (event) => {
    if (!current) return;
    const p = hit(event);
    if (p) addPoint(p);
  });
  const finish = () => {
    if (!current) return;
    strokes.push(current);
    current = null;
    ctx.stage.controls.enabled = true;
    ctx.stage.endInteraction();
    updateInfo();
  };
  canvas.addEventListener('pointerup', finish);
  canvas.addEventListener('pointerleave', finish);
  $('paint').onclick = () => {
    painting = !painting;
    $('paint').classList.toggle('on', painting);
    $('paint').textContent = painting ? 'Painting' : 'Paint';
  };
  $('clear').onclick = () => {
    strokes.length = 0;
    for (const c of [...marks.children]) { marks.remove(c); c.geometry.dispose(); }
    ctx.stage.requestRender();
    updateInfo();
  };
  $('generate').onclick = async () => {
    $('generate').disabled = true;
    const output = `wound-${new Date().toISOString().replace(/[-:]/g, '').replace(/\..*/, '')}-${$('seed').value}`;
    const job = $('job');
    try {
      const started = await startJob({
        kind: 'wound', output, mesh: meshName, resolution: Number($('resolution').value),
        seed: Number($('seed').value), times: '',
        job: { version: 1, type: $('type').value, strokes },
      });
      const end = await followJob(started.id, (j) => {
        job.textContent = `${j.state} ${(100 * (j.progress.fraction || 0)).toFixed(0)} % (${j.seconds.toFixed(1)} s)`;
      });
      if (end.state !== 'succeeded') throw new Error(end.error || end.state);
      const tl = await WoundTimeline.load(await describeRun(output), ctx.stage.renderer);
      marks.visible = false;
      painting = false;
      $('paint').classList.remove('on');
      showTimeline(ctx, object, tl, `Generated: ${output}`);
      html(ctx.panel, `<a href="#/run?path=${encodeURIComponent(output)}">open the run</a>`);
      document.body.dataset.generated = output;
    } catch (e) {
      job.className = 'error';
      job.textContent = e.message + (e.field ? ` (${e.field})` : '');
      $('generate').disabled = false;
    }
  };
  updateInfo();
  ctx.ready();
}
