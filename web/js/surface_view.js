// Any other run (a reconstruction, a converted mesh): its surfaces, each a triangle .vtu drawn in false
// colour by its per-vertex fields (an "uncertainty" field in mm among them), or else its GLB as written.

import * as THREE from 'three';
import { GLTFLoader } from 'three/addons/loaders/GLTFLoader.js';
import { describeRun, fileUrl, frameSurface } from './api.js';
import { FrameColouring, surfaceGeometry } from './desiccation_view.js';
import { cameraControls, cutControls } from './stage.js';
import { escapeHtml, html } from './util.js';

export async function showSurfaceRun(ctx, path) {
  const run = await describeRun(path);
  const surfaces = run.files.map((f) => f.path).filter((p) => p.endsWith('.vtu'));
  const glbs = run.files.map((f) => f.path).filter((p) => p.endsWith('.glb'));
  html(ctx.panel, `<h2>${escapeHtml(run.kind || 'run')} run ${escapeHtml(path)}</h2>`);
  const name = () => `${path.replace(/\//g, '_')}.png`;
  if (!surfaces.length) {
    if (!glbs.length) throw new Error(`run '${path}' has no surface (.vtu) or GLB to show`);
    const gltf = await new GLTFLoader().loadAsync(fileUrl(`${path}/${glbs[0]}`));
    ctx.stage.add(gltf.scene);
    ctx.stage.fit(gltf.scene, 'front');
    html(ctx.panel, `<div class="muted">${escapeHtml(glbs[0])} as written (no per-vertex fields to colour)</div>`);
    cutControls(ctx.panel, ctx.stage);
  } else {
    const controls = html(ctx.panel, '<label>Surface <select id="surface"></select></label>');
    const select = controls.querySelector('#surface');
    for (const s of surfaces) select.add(new Option(s, s));
    const mesh = new THREE.Mesh(new THREE.BufferGeometry(),
      new THREE.MeshStandardMaterial({ vertexColors: true, roughness: 0.8, side: THREE.DoubleSide }));
    mesh.scale.setScalar(0.001);  // mm to m
    ctx.stage.add(mesh);
    let frame = null, cut = null;
    const draw = () => {
      mesh.geometry.dispose();
      mesh.geometry = surfaceGeometry(frame, frame.positions, colouring.colours(frame));
      if (cut) cut.apply();
      document.body.dataset.colour = colouring.mode.id;
      ctx.stage.requestRender();
    };
    const colouring = new FrameColouring(controls, draw);
    const open = async () => {
      frame = await frameSurface(`${path}/${select.value}`);
      await colouring.setSeries(async () => frame, 1);
      draw();
    };
    select.onchange = open;
    await open();
    ctx.stage.fit(mesh, 'front');
    cut = cutControls(ctx.panel, ctx.stage);
  }
  cameraControls(ctx.panel, ctx.stage, name);
  ctx.ready();
}
