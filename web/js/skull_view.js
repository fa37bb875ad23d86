// The skull editor: a skull (built-in, or a mesh or CT of the served folder) with its landmarks (detected with
// a confidence each, coloured by it), the face reconstructed on the server (an editing session of
// src/server/skull_sessions.hpp) drawn over it. Drag a landmark over the skull (a ray cast in the browser) and
// the face follows: while dragging, the newest position is sent whenever the previous answer has arrived; on
// release the final one, and the face's vertex positions are replaced in place. Click the skull to add the
// landmark picked in the list; remove the selected one with its button or the Delete key. After each change
// (not during a drag) the skull/skin violations are counted on the server and shown. Table, sex and build
// change the depths; the nose and mouth guides move with sliders, and the nose tip follows Krogman's rule
// from the anterior nasal spine (ans, its tip, and ss) with a factor slider; expressions play (the server's
// pose blended in over the neutral face); the landmarks and the head export as .mrk.json and GLB.
//
// window.forensim.skull exposes the state for the browser test: screenPosition(name), the face geometry,
// `latencies` (per drag release: ms until the updated face was drawn, and the server's update time) and the
// last `violations` answer.

import * as THREE from 'three';
import { deleteJson, getJson, postJson } from './api.js';
import { cameraControls } from './stage.js';
import { blendPositions, confidenceColour, float32Array, median, playWeight, uint32Array } from './skull_math.js';
import { escapeHtml, html } from './util.js';

const SKULL_COLOUR = 0xe3d7bd, SKIN_COLOUR = 0xd9a68a;
const ANTERIOR = [0, -1, 0];  // the guides' lateral (+x) x up (+z), LPS
const SPINE = ['ans', 'ss'];  // the landmarks the nose tip's guide is measured from
const GUIDES = [
  // key, label, axis of the guide line (0: a vertical line at x = value; 2: a horizontal one at z = value)
  ['nasal_aperture_left_mm', 'nose: aperture left', 0], ['nasal_aperture_right_mm', 'nose: aperture right', 0],
  ['mouth_corner_left_mm', 'mouth corner left', 0], ['mouth_corner_right_mm', 'mouth corner right', 0],
  ['upper_lip_border_mm', 'upper lip border', 2], ['lip_parting_mm', 'lip parting', 2],
  ['lower_lip_border_mm', 'lower lip border', 2],
];

function meshFrom(arrays, material) {
  const g = new THREE.BufferGeometry();
  g.setAttribute('position', new THREE.BufferAttribute(float32Array(arrays.positions_f32), 3));
  g.setIndex(new THREE.BufferAttribute(uint32Array(arrays.triangles_u32), 1));
  g.computeVertexNormals();
  return new THREE.Mesh(g, material);
}

// The open session, deleted on the server when the page moves on (a server keeps a few at most).
let openSession = null;
function closeSession() {
  if (openSession) fetch(openSession, { method: 'DELETE', keepalive: true }).catch(() => {});
  openSession = null;
}
window.addEventListener('hashchange', closeSession);
window.addEventListener('pagehide', closeSession);

const nextFrame = () => new Promise((r) => requestAnimationFrame(() => r(performance.now())));

function sessionForm(panel, params) {
  const form = html(panel, `
    <h2>Skull editor</h2>
    <label>Skull <input type="text" id="skull" value="builtin" title="builtin, or a mesh or CT in the served folder"></label>
    <label>Landmarks <select id="landmarks"><option value="auto">auto (detected)</option>
      <option value="template">template (built-in skull)</option></select></label>
    <label>Template <select id="detail"><option>full</option><option>coarse</option></select></label>
    <div class="row"><button id="load">Load</button></div>`);
  const $ = (id) => form.querySelector('#' + id);
  $('skull').value = params.get('skull') || 'builtin';
  $('landmarks').value = params.get('landmarks') || 'auto';
  $('detail').value = params.get('detail') || 'full';
  $('load').onclick = () => {
    const q = new URLSearchParams({ skull: $('skull').value, landmarks: $('landmarks').value, detail: $('detail').value });
    const hash = '#/skull?' + q.toString();
    if (location.hash === hash) window.dispatchEvent(new HashChangeEvent('hashchange'));
    else location.hash = hash;
  };
  return form;
}

export async function showSkullEditor(ctx, params) {
  sessionForm(ctx.panel, params);
  const status = html(ctx.panel, '<div class="muted" id="skull-status">building the reconstruction\u2026</div>').firstChild;
  const request = {
    skull: params.get('skull') || 'builtin', landmarks: params.get('landmarks') || 'auto',
    template_detail: params.get('detail') || 'full',
  };
  const t0 = performance.now();
  const s = await postJson('/api/skull/sessions', request);
  const base = '/api/skull/sessions/' + encodeURIComponent(s.id);
  openSession = base;
  status.textContent = `session ${s.id}: ${s.landmarks.length} landmarks (${s.landmark_origin.split(':')[0]}), ` +
    `${s.face.vertex_count} face vertices; ready in ${((performance.now() - t0) / 1000).toFixed(1)} s`;
  document.body.dataset.skullSession = s.id;

  // The scene: skull, face, landmark markers, depth vectors, guide lines (all in mm).
  const skull = meshFrom(s.skull_mesh, new THREE.MeshStandardMaterial({ color: SKULL_COLOUR, roughness: 0.8 }));
  const skinMaterial = new THREE.MeshStandardMaterial({ color: SKIN_COLOUR, roughness: 0.7, side: THREE.DoubleSide });
  const face = meshFrom(s.face, skinMaterial);
  const neutral = face.geometry.attributes.position.array.slice();
  const markers = new THREE.Group(), vectors = new THREE.Group(), guideLines = new THREE.Group();
  const root = new THREE.Group();
  root.add(skull, markers, vectors, guideLines, face);
  ctx.stage.add(root);
  ctx.stage.fit(root, 'front');
  const headSize = new THREE.Box3().setFromObject(skull).getSize(new THREE.Vector3());
  const sphere = new THREE.SphereGeometry(0.01 * headSize.length(), 14, 10);  // about 3 mm on an adult skull

  let landmarks = s.landmarks, addable = s.addable, selected = '', faceVersion = 0, drag = null;
  const poses = new Map();  // expression name -> positions of the current face
  const state = { latencies: [], face, skull, markers, faceVersion: () => faceVersion, violations: null };
  let guidesReady = false;
  const landmarkAt = (name) => {
    const l = landmarks.find((x) => x.name === name);
    return l ? (l.skull_mm || l.position_mm) : null;
  };
  // The spine from ans and ss, or null when either is missing or ans does not stand in front of ss.
  const spine = () => {
    const tip = landmarkAt('ans'), ss = landmarkAt('ss');
    if (!tip || !ss) return null;
    const length = ANTERIOR.reduce((sum, a, k) => sum + a * (tip[k] - ss[k]), 0);
    if (!(length > 0.5)) return null;
    return { tip, base: tip.map((v, k) => v - ANTERIOR[k] * length), length };
  };
  const updateSpine = () => {
    if (!guidesReady) return;
    const sp = spine();
    $('spine-on').disabled = !sp && !$('spine-on').checked;
    $('spine-info').textContent = sp ? `spine ans to ss: ${sp.length.toFixed(1)} mm` :
      (landmarkAt('ans') && landmarkAt('ss') ? 'ans does not stand in front of ss' :
        'needs the landmarks ans (the spine\'s tip: add it from the list) and ss');
  };
  window.forensim.skull = state;

  // Panel: view toggles, depths, landmarks, guides, expressions, export.
  const controls = html(ctx.panel, `
    <h2>View</h2>
    <label><input type="checkbox" id="transparent" checked> skin transparent</label>
    <label><input type="checkbox" id="show-vectors" checked> depth vectors</label>
    <label><input type="checkbox" id="show-face" checked> face</label>
    <h2>Tissue depths</h2>
    <label>Table <select id="table"><option>ttable_2023</option><option>rhine_1983</option></select></label>
    <label>Sex <select id="sex"><option value="">any</option><option>female</option><option>male</option></select></label>
    <label>Build <select id="build"><option value="">as the group</option><option>slender</option><option>normal</option>
      <option>obese</option></select></label>
    <div class="muted" id="depth-group"></div>
    <h2>Landmarks</h2>
    <div class="muted">Drag a landmark over the skull to move it (the right button orbits). Colour: confidence
      (red low, green high).</div>
    <label>Add <select id="add-name"></select></label>
    <div class="row"><button id="add">Click the skull to add</button>
      <button id="remove" disabled title="or the Delete key">Remove selected</button></div>
    <div id="landmark-info" class="muted"></div>
    <div id="skull-timing" class="muted"></div>
    <div id="violations" class="muted"></div>
    <h2>Nose and mouth guides</h2>
    <label><input type="checkbox" id="guides-on"> apply the guides</label>
    <div id="guide-sliders"></div>
    <label><input type="checkbox" id="spine-on"> nose tip by Krogman's rule (anterior nasal spine)</label>
    <label>spine lengths in front of mid-philtrum <span id="krogman-label"></span>
      <input type="range" id="krogman" min="0" max="6" step="0.1" value="3"></label>
    <div class="muted" id="spine-info"></div>
    <h2>Expressions</h2>
    <div class="row" id="expressions"></div>
    <h2>Export</h2>
    <div id="exports"></div>
    <label>Save as run <input type="text" id="save-name" value="skull-edit"></label>
    <div class="row"><button id="save">Save</button></div><div id="saved" class="muted"></div>`);
  const $ = (id) => controls.querySelector('#' + id);
  const fail = (e) => {
    status.className = 'error';
    status.textContent = e.message + (e.field ? ` (${e.field})` : '');
  };

  const setTransparent = () => {
    skinMaterial.transparent = $('transparent').checked;
    skinMaterial.opacity = $('transparent').checked ? 0.4 : 1;
    skinMaterial.depthWrite = !$('transparent').checked;
    skinMaterial.needsUpdate = true;
    ctx.stage.requestRender();
  };
  $('transparent').onchange = setTransparent;
  $('show-vectors').onchange = () => { vectors.visible = $('show-vectors').checked; ctx.stage.requestRender(); };
  $('show-face').onchange = () => { face.visible = $('show-face').checked; ctx.stage.requestRender(); };
  setTransparent();

  const drawLandmarks = () => {
    for (const m of [...markers.children]) { markers.remove(m); m.material.dispose(); }
    for (const v of [...vectors.children]) { vectors.remove(v); v.geometry.dispose(); v.material.dispose(); }
    const points = [];
    for (const l of landmarks) {
      const c = confidenceColour(l.confidence);
      const m = new THREE.Mesh(sphere, new THREE.MeshStandardMaterial({
        color: new THREE.Color(...c), emissive: l.name === selected ? 0x666666 : 0x000000, roughness: 0.5,
      }));
      m.position.fromArray(l.skull_mm || l.position_mm);
      if (l.name === selected) m.scale.setScalar(1.5);
      m.userData.name = l.name;
      markers.add(m);
      if (l.skin_mm) points.push(...(l.skull_mm || l.position_mm), ...l.skin_mm);
    }
    const g = new THREE.BufferGeometry();
    g.setAttribute('position', new THREE.Float32BufferAttribute(points, 3));
    vectors.add(new THREE.LineSegments(g, new THREE.LineBasicMaterial({ color: 0x4fc3f7 })));
    const add = $('add-name');
    add.innerHTML = addable.map((a) => `<option value="${escapeHtml(a.name)}">${escapeHtml(a.name)} ` +
      `(${escapeHtml(a.full_name)}${a.moves_face ? '' : '; not on the face'})</option>`).join('');
    $('add').disabled = !addable.length;
    const info = landmarks.find((l) => l.name === selected);
    if (drag) drag.marker = markers.children.find((m) => m.userData.name === drag.name);
    $('remove').disabled = !info;
    updateSpine();
    $('landmark-info').textContent = info ? `${info.name} (${info.full_name || ''}): ${info.source}, confidence ` +
      `${info.confidence.toFixed(2)}${info.depth_mm ? `, depth ${info.depth_mm.toFixed(1)} mm` : ''}` : '';
    ctx.stage.requestRender();
  };

  const setFace = (positions) => {
    const attribute = face.geometry.attributes.position;
    attribute.array.set(positions);
    attribute.needsUpdate = true;
    face.geometry.computeVertexNormals();
    face.geometry.computeBoundingSphere();
    document.body.dataset.faceVersion = String(++faceVersion);
    ctx.stage.requestRender();
  };
  const newFace = (answer) => {
    const positions = float32Array(answer.face.positions_f32);
    neutral.set(positions);
    poses.clear();
    setFace(positions);
    if (answer.landmarks) landmarks = answer.landmarks;
    if (answer.addable) addable = answer.addable;
    drawLandmarks();
    if (!drag) countViolations();
  };

  // Skull/skin violations of the current face: counted on the server after a change has settled (a count
  // takes longer than an update, and would hold up a drag's requests), the newest answer shown.
  let violationTimer = null, violationAsk = 0;
  const countViolations = (delay = 500) => {
    clearTimeout(violationTimer);
    const mine = ++violationAsk;
    $('violations').textContent = 'counting skull/skin violations\u2026';
    violationTimer = setTimeout(async () => {
      if (drag) { countViolations(delay); return; }
      try {
        const v = await getJson(base + '/violations');
        if (mine !== violationAsk) return;
        state.violations = v;
        $('violations').textContent = `skull through skin: ${v.skull_through_skin} vertices; skin inside skull: ` +
          `${v.skin_inside_skull} vertices (counted in ${v.count_ms.toFixed(0)} ms)`;
        document.body.dataset.violations = String(mine);
      } catch (e) {
        if (mine === violationAsk) $('violations').textContent = `violations not counted: ${e.message}`;
      }
    }, delay);
  };

  // Dragging and adding landmarks: ray casts against the markers and the skull.
  const raycaster = new THREE.Raycaster();
  const pointer = new THREE.Vector2();
  const canvas = ctx.stage.canvas;
  const cast = (event, objects) => {
    const r = canvas.getBoundingClientRect();
    pointer.set(((event.clientX - r.left) / r.width) * 2 - 1, -((event.clientY - r.top) / r.height) * 2 + 1);
    raycaster.setFromCamera(pointer, ctx.stage.camera);
    return raycaster.intersectObjects(objects, false)[0] || null;
  };
  let adding = false, inFlight = null, pending = null, lastSent = null, lastAnswer = null;
  const send = (name, position) => {
    lastSent = position.map((v) => +v.toFixed(3));
    return postJson(base + '/landmarks', { name, position: lastSent });
  };
  // While dragging: at most one request in flight; the newest position waits for it.
  const sendLive = (name, position) => {
    if (inFlight) { pending = position; return; }
    const sent = position.map((v) => +v.toFixed(3));
    inFlight = send(name, position).then((a) => {
      lastAnswer = { position: sent, answer: a };
      if (drag) newFace(a);
    }).catch(() => {}).finally(() => {
      inFlight = null;
      if (pending && drag) { const p = pending; pending = null; sendLive(name, p); }
    });
  };
  canvas.addEventListener('pointerdown', (event) => {
    if (event.button !== 0) return;
    if (adding) {
      const hit = cast(event, [skull]);
      if (!hit) return;
      adding = false;
      $('add').classList.remove('on');
      const name = $('add-name').value;
      selected = name;
      send(name, hit.point.toArray()).then((a) => {
        newFace(a);
        if (SPINE.includes(name) && $('spine-on').checked) sendGuides();
      }).catch(fail);
      return;
    }
    const hit = cast(event, markers.children);
    if (!hit) return;
    ctx.stage.controls.enabled = false;
    ctx.stage.beginInteraction();
    selected = hit.object.userData.name;
    drag = { name: selected, marker: hit.object, position: null };
    drawLandmarks();
  });
  canvas.addEventListener('pointermove', (event) => {
    if (!drag) return;
    const hit = cast(event, [skull]);
    if (!hit) return;
    drag.position = hit.point.toArray();
    drag.marker.position.copy(hit.point);
    ctx.stage.requestRender();
    sendLive(drag.name, drag.position);
  });
  const release = async () => {
    if (!drag) return;
    const { name, position } = drag;
    drag = null;
    pending = null;
    ctx.stage.controls.enabled = true;
    if (!position) {
      ctx.stage.endInteraction();
      return;
    }
    const released = performance.now();
    try {
      // The answer for the final position: the live request's when it went from there, else a new one, sent
      // at once (the server serves the session's requests in order, so it answers after the live one).
      const final = position.map((v) => +v.toFixed(3));
      const live = inFlight && lastSent && lastSent.every((v, k) => v === final[k]) ? inFlight : null;
      if (live) await live;
      const waited = performance.now();
      const same = lastAnswer && lastAnswer.position.every((v, k) => v === final[k]);
      const answer = same ? lastAnswer.answer : await send(name, position);
      const received = performance.now();
      newFace(answer);
      if (SPINE.includes(name) && $('spine-on').checked) sendGuides();
      const applied = performance.now();
      const drawn = await nextFrame();
      ctx.stage.endInteraction();  // drawn at the drag's pixel ratio first, then at the full one
      // The frame after the one that drew the face starts once that one was shown (the compositor waits for
      // the renderer), so it tells when the new face was on screen.
      const shown = await nextFrame();
      const latency = {
        total_ms: drawn - released, wait_ms: waited - released, request_ms: received - waited,
        apply_ms: applied - received, frame_ms: drawn - applied, shown_ms: shown - released,
        server_ms: answer.update_ms, reused: same,
      };
      state.latencies.push(latency);
      $('skull-timing').textContent = `face updated ${latency.total_ms.toFixed(0)} ms after release (server ` +
        `${answer.update_ms.toFixed(0)} ms; median of ${state.latencies.length}: ` +
        `${median(state.latencies.map((l) => l.total_ms)).toFixed(0)} ms)`;
    } catch (e) {
      ctx.stage.endInteraction();
      fail(e);
      drawLandmarks();
    }
  };
  canvas.addEventListener('pointerup', release);
  canvas.addEventListener('pointerleave', release);
  $('add').onclick = () => { adding = !adding; $('add').classList.toggle('on', adding); };
  // Removing the selected landmark: its pair leaves the warp (refused while fewer than 4 pairs would remain).
  const removeSelected = async () => {
    if (!selected || drag) return;
    const name = selected;
    try {
      const a = await deleteJson(base + '/landmarks/' + encodeURIComponent(name));
      selected = '';
      newFace(a);
      status.className = 'muted';
      $('landmark-info').textContent = `${name} removed (${a.warp_pairs} warp pairs)`;
      if (SPINE.includes(name) && $('spine-on').checked) sendGuides();
    } catch (e) { fail(e); }
  };
  $('remove').onclick = removeSelected;
  const onKey = (event) => {
    if (!document.body.contains(controls)) { window.removeEventListener('keydown', onKey); return; }
    if (event.key !== 'Delete' && event.key !== 'Backspace') return;
    if (/^(INPUT|SELECT|TEXTAREA)$/.test(event.target.tagName)) return;
    event.preventDefault();
    removeSelected();
  };
  window.addEventListener('keydown', onKey);
  state.screenPosition = (name) => {
    const l = landmarks.find((x) => x.name === name);
    if (!l) return null;
    const p = new THREE.Vector3().fromArray(l.skull_mm || l.position_mm).project(ctx.stage.camera);
    const r = canvas.getBoundingClientRect();
    return { x: r.left + (p.x + 1) / 2 * r.width, y: r.top + (1 - p.y) / 2 * r.height };
  };

  // Tissue depths.
  const depthInfo = (d) => {
    $('depth-group').textContent = `${d.table_name}: ${d.group}, ${d.variant}` + (d.notes.length ? ` (${d.notes.join('; ')})` : '');
  };
  depthInfo(s.depths);
  $('table').value = s.depths.table;
  const setDepths = async () => {
    try {
      const a = await postJson(base + '/depths', { table: $('table').value, sex: $('sex').value, build: $('build').value });
      depthInfo(a.depths);
      newFace(a);
      status.className = 'muted';
    } catch (e) { fail(e); }
  };
  $('table').onchange = $('sex').onchange = $('build').onchange = setDepths;

  // Guides: one slider per value, starting where the face is; lines in front of the face show them. The nose
  // tip's guide is the anterior nasal spine: its tip the landmark ans, its base on the spine's axis (the
  // guides' anterior direction) at the depth of subspinale ss (as skull_guides.hpp measures it).
  const sliders = $('guide-sliders');
  const values = { ...s.guide_values };
  for (const [key, label] of GUIDES) {
    if (values[key] === undefined) continue;
    const v = values[key];
    html(sliders, `<label>${label} <span id="${key}-label">${v.toFixed(1)} mm</span>
      <input type="range" id="${key}" min="${(v - 15).toFixed(1)}" max="${(v + 15).toFixed(1)}" step="0.5" value="${v}"></label>`);
  }
  const drawGuides = () => {
    for (const l of [...guideLines.children]) { guideLines.remove(l); l.geometry.dispose(); l.material.dispose(); }
    guideLines.visible = $('guides-on').checked;
    const box = new THREE.Box3().setFromBufferAttribute(face.geometry.attributes.position);
    const y = box.min.y - 2, cx = (box.min.x + box.max.x) / 2, mouth = values.lip_parting_mm ?? 0;
    const points = [];
    for (const [key, , axis] of GUIDES) {
      const v = values[key];
      if (v === undefined) continue;
      if (axis === 0) points.push(v, y, mouth - 0.12 * headSize.z, v, y, mouth + 0.25 * headSize.z);
      else points.push(cx - 0.2 * headSize.x, y, v, cx + 0.2 * headSize.x, y, v);
    }
    const sp = spine();
    if ($('spine-on').checked && sp) {
      // The spine, and its extension to where Krogman's rule puts the nose tip's depth.
      const reach = sp.length * (1 + Number($('krogman').value));
      points.push(...sp.base, ...sp.tip.map((v, k) => v + ANTERIOR[k] * reach));
      guideLines.visible = true;
    }
    const g = new THREE.BufferGeometry();
    g.setAttribute('position', new THREE.Float32BufferAttribute(points, 3));
    guideLines.add(new THREE.LineSegments(g, new THREE.LineBasicMaterial({ color: 0xffd54f })));
  };
  const sendGuides = async () => {
    drawGuides();
    try {
      let guides = $('guides-on').checked ? { ...values } : null;
      const sp = $('spine-on').checked ? spine() : null;
      if (sp) {
        guides = { ...(guides || {}), nasal_spine_base: sp.base, nasal_spine_tip: sp.tip,
                   krogman_factor: Number($('krogman').value) };
      }
      newFace(await postJson(base + '/guides', { guides }));
      document.body.dataset.guides = guides ? 'on' : 'off';
    } catch (e) { fail(e); }
  };
  for (const input of sliders.querySelectorAll('input')) {
    input.oninput = () => {
      values[input.id] = Number(input.value);
      sliders.querySelector(`#${input.id}-label`).textContent = `${Number(input.value).toFixed(1)} mm`;
      drawGuides();
    };
    input.onchange = () => { if ($('guides-on').checked) sendGuides(); };
  }
  $('guides-on').onchange = sendGuides;
  $('krogman').value = s.guides?.krogman_factor ?? 3;
  $('krogman-label').textContent = Number($('krogman').value).toFixed(1);
  $('krogman').oninput = () => {
    $('krogman-label').textContent = Number($('krogman').value).toFixed(1);
    drawGuides();
  };
  $('krogman').onchange = () => { if ($('spine-on').checked) sendGuides(); };
  $('spine-on').onchange = sendGuides;
  guidesReady = true;
  updateSpine();
  drawGuides();

  // Expressions: the server's pose of the current face, played over the neutral face.
  let playing = null;
  for (const name of s.expressions.filter((n) => n !== 'neutral')) {
    const b = document.createElement('button');
    b.textContent = name;
    b.dataset.expression = name;
    b.onclick = async () => {
      try {
        if (!poses.has(name)) {
          const a = await postJson(base + '/expressions', { name });
          poses.set(name, float32Array(a.positions_f32));
        }
        playing = { pose: poses.get(name), start: performance.now(), name };
        ctx.stage.requestRender();
      } catch (e) { fail(e); }
    };
    $('expressions').appendChild(b);
  }
  const work = new Float32Array(neutral.length);
  const PLAY_S = 2.0;
  ctx.stage.onFrame = (now) => {
    if (!playing) return;
    ctx.stage.requestRender();  // the next pose, and the neutral face once played
    const t = (now - playing.start) / 1000;
    const attribute = face.geometry.attributes.position;
    attribute.array.set(blendPositions(work, neutral, playing.pose, playWeight(t, PLAY_S)));
    attribute.needsUpdate = true;
    face.geometry.computeVertexNormals();
    if (t >= PLAY_S) {
      document.body.dataset.played = playing.name;
      playing = null;
    }
  };

  // Export: downloads, and a run folder in the served folder.
  html($('exports'), `<a href="${base}/skull_landmarks.mrk.json" download="skull_landmarks.mrk.json" id="export-mrk">skull landmarks (.mrk.json)</a><br>
    <a href="${base}/skin_landmarks.mrk.json" download="skin_landmarks.mrk.json">skin landmarks (.mrk.json)</a><br>
    <a href="${base}/head.glb" download="head.glb" id="export-glb">head with skull and expressions (GLB)</a>`);
  $('save').onclick = async () => {
    try {
      const a = await postJson(base + '/save', { output: $('save-name').value });
      $('saved').innerHTML = `saved: <a href="#/run?path=${encodeURIComponent(a.output)}">${escapeHtml(a.output)}</a>`;
    } catch (e) { fail(e); }
  };

  cameraControls(ctx.panel, ctx.stage, 'forensim_skull.png');
  drawLandmarks();
  countViolations(0);
  document.body.dataset.faceVersion = '0';
  ctx.ready();
}
