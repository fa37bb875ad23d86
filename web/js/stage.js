// The 3D stage every view draws on: a three.js renderer on the page's canvas, orbit controls, lights,
// camera presets around the object's bounding box (forensim's frame is z-up), screenshot export and a
// frame-rate meter.
//
// Drawn on demand: a frame is drawn only after something asked for one with requestRender() (the camera
// controls' changes, the stage's own content, size and camera changes, any input in the side panel, and each
// view after it changes a mesh, a material or a uniform), so an idle page costs nothing and, on a CPU
// renderer (SwiftShader: a few frames/s), a change waits for at most the frame in progress instead of up to
// two. Drawing continues while something animates: a view's onFrame(now), called before each frame, asks for
// the next one while its timeline or expression plays. While the user drags (beginInteraction() to
// endInteraction(), or an orbit of the controls), a CPU renderer draws at half the pixel ratio.

import * as THREE from 'three';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';

const PRESETS = {
  front: new THREE.Vector3(0, -1, 0.15),
  back: new THREE.Vector3(0, 1, 0.15),
  left: new THREE.Vector3(-1, 0, 0.15),
  right: new THREE.Vector3(1, 0, 0.15),
  top: new THREE.Vector3(0.001, -0.001, 1),
  oblique: new THREE.Vector3(0.6, -0.8, 0.5),
};

/// The WebGL renderer's name, and whether it draws on the CPU (SwiftShader, llvmpipe: no GPU, as in headless
/// chromium), asked of a throwaway context.
export function webglRenderer() {
  try {
    const gl = document.createElement('canvas').getContext('webgl2');
    if (!gl) return { name: '', software: false };
    const info = gl.getExtension('WEBGL_debug_renderer_info');
    const name = String(gl.getParameter(info ? info.UNMASKED_RENDERER_WEBGL : gl.RENDERER));
    const lose = gl.getExtension('WEBGL_lose_context');
    if (lose) lose.loseContext();
    return { name, software: /swiftshader|llvmpipe|softpipe|software/i.test(name) };
  } catch {
    return { name: '', software: false };
  }
}

export class Stage {
  constructor(canvas) {
    this.canvas = canvas;
    // Multisampling on a CPU renderer costs more than half the frame rate (measured with SwiftShader: 1.4 against
    // 3.4 frames/s scrubbing 2048^2 wound maps), so it is kept for GPUs.
    this.webgl = webglRenderer();
    this.antialias = !this.webgl.software;
    // preserveDrawingBuffer: screenshots read the canvas after the frame was shown.
    this.renderer = new THREE.WebGLRenderer({ canvas, antialias: this.antialias, preserveDrawingBuffer: true });
    this.renderer.setPixelRatio(Math.min(window.devicePixelRatio, 2));  // this.pixelRatio, set below
    this.renderer.outputColorSpace = THREE.SRGBColorSpace;
    this.scene = new THREE.Scene();
    this.scene.background = new THREE.Color(0x30343a);
    this.camera = new THREE.PerspectiveCamera(30, 1, 0.001, 1000);
    this.camera.up.set(0, 0, 1);
    this.controls = new OrbitControls(this.camera, canvas);
    this.controls.enableDamping = false;
    this.scene.add(new THREE.HemisphereLight(0xffffff, 0x404040, 1.2));
    const key = new THREE.DirectionalLight(0xffffff, 2.0);
    key.position.set(1, -2, 3);
    this.camera.add(key);
    this.scene.add(this.camera);
    this.content = new THREE.Group();
    this.scene.add(this.content);
    this.box = new THREE.Box3(new THREE.Vector3(-1, -1, -1), new THREE.Vector3(1, 1, 1));
    this.frameTimes = [];  // when the last frames were drawn (ms, performance.now())
    this.drawn = 0;        // frames drawn since the page opened
    this.onFrame = null;   // (now) => called before each frame; it calls requestRender() to keep animating
    this.scheduled = false;
    this.interactions = 0;
    this.pixelRatio = Math.min(window.devicePixelRatio, 2);
    // Dragging on a CPU renderer: a quarter of the pixels, about four times the frame rate.
    this.dragPixelRatio = this.webgl.software ? this.pixelRatio / 2 : this.pixelRatio;
    this.controls.addEventListener('change', () => this.requestRender());
    this.controls.addEventListener('start', () => this.beginInteraction());
    this.controls.addEventListener('end', () => this.endInteraction());
    this.draw = (now) => {
      this.scheduled = false;
      this.frameTimes.push(now);
      if (this.frameTimes.length > 120) this.frameTimes.shift();
      if (this.onFrame) this.onFrame(now);
      if (this.controls.update()) this.requestRender();  // damping still moving the camera
      const ratio = this.interactions > 0 ? this.dragPixelRatio : this.pixelRatio;
      if (this.renderer.getPixelRatio() !== ratio) this.renderer.setPixelRatio(ratio);
      this.renderer.render(this.scene, this.camera);
      ++this.drawn;
    };
    new ResizeObserver(() => this.resize()).observe(canvas);
    this.resize();
  }

  /// Asks for a frame: drawn at the next animation frame, once however often it is asked for before.
  requestRender() {
    if (this.scheduled) return;
    this.scheduled = true;
    requestAnimationFrame(this.draw);
  }

  /// A drag begins (a landmark, a brush stroke): until the matching endInteraction(), frames are drawn at the
  /// reduced pixel ratio of a CPU renderer.
  beginInteraction() {
    ++this.interactions;
  }

  /// The drag ended: the next frame is drawn at the full pixel ratio.
  endInteraction() {
    this.interactions = Math.max(0, this.interactions - 1);
    this.requestRender();
  }

  resize() {
    const w = Math.max(1, this.canvas.clientWidth), h = Math.max(1, this.canvas.clientHeight);
    this.renderer.setSize(w, h, false);
    this.camera.aspect = w / h;
    this.camera.updateProjectionMatrix();
    this.requestRender();
  }

  /// Removes what the previous view showed (disposing its GPU resources).
  clear() {
    this.onFrame = null;
    for (const child of [...this.content.children]) {
      this.content.remove(child);
      child.traverse((o) => {
        if (o.geometry) o.geometry.dispose();
        if (o.material) (Array.isArray(o.material) ? o.material : [o.material]).forEach((m) => m.dispose());
      });
    }
    this.interactions = 0;
    this.requestRender();
  }

  add(object) {
    this.content.add(object);
    this.requestRender();
  }

  /// Frames the camera on `object` (or the whole content) from a preset direction.
  fit(object = this.content, preset = 'oblique') {
    this.box = new THREE.Box3().setFromObject(object);
    if (this.box.isEmpty()) return;
    this.preset(preset);
  }

  preset(name) {
    const dir = (PRESETS[name] || PRESETS.oblique).clone().normalize();
    const centre = this.box.getCenter(new THREE.Vector3());
    const radius = this.box.getSize(new THREE.Vector3()).length() / 2;
    const distance = radius / Math.sin(THREE.MathUtils.degToRad(this.camera.fov / 2)) * 1.05;
    this.camera.near = distance / 100;
    this.camera.far = distance * 10;
    this.camera.updateProjectionMatrix();
    this.camera.position.copy(centre).addScaledVector(dir, distance);
    this.controls.target.copy(centre);
    this.controls.update();
    this.requestRender();
  }

  static presetNames() {
    return Object.keys(PRESETS);
  }

  /// Frames per second over the frames drawn in the last two seconds (0 when fewer than two were: the page
  /// draws only on change).
  fps() {
    const now = performance.now();
    const t = this.frameTimes.filter((x) => now - x < 2000);
    if (t.length < 2) return 0;
    return (1000 * (t.length - 1)) / (t[t.length - 1] - t[0]);
  }

  /// Saves what the canvas shows as a PNG download named `name`.
  screenshot(name = 'forensim.png') {
    this.renderer.setPixelRatio(this.pixelRatio);
    this.renderer.render(this.scene, this.camera);
    const url = this.canvas.toDataURL('image/png');
    const a = document.createElement('a');
    a.href = url;
    a.download = name;
    document.body.appendChild(a);
    a.click();
    a.remove();
    return url;
  }
}

/// Buttons for the camera presets and a screenshot, appended to `parent`.
export function cameraControls(parent, stage, screenshotName) {
  const box = document.createElement('div');
  box.innerHTML = '<h2>Camera</h2>';
  const row = document.createElement('div');
  row.className = 'row';
  for (const name of Stage.presetNames()) {
    const b = document.createElement('button');
    b.textContent = name;
    b.dataset.preset = name;
    b.onclick = () => stage.preset(name);
    row.appendChild(b);
  }
  const shot = document.createElement('button');
  shot.textContent = 'Screenshot';
  shot.id = 'screenshot';
  shot.onclick = () => stage.screenshot(typeof screenshotName === 'function' ? screenshotName() : screenshotName);
  row.appendChild(shot);
  box.appendChild(row);
  parent.appendChild(box);
}

/// A cutting plane across the content: on/off, axis and position within the bounding box.
export function cutControls(parent, stage) {
  const box = document.createElement('div');
  box.innerHTML = `<h2>Cutting plane</h2><label><input type="checkbox" id="cut-on"> cut along
    <select id="cut-axis"><option value="0">x</option><option value="1">y</option><option value="2" selected>z</option>
    </select></label><input type="range" id="cut-at" min="0" max="1000" value="500">`;
  parent.appendChild(box);
  const on = box.querySelector('#cut-on'), axis = box.querySelector('#cut-axis'), at = box.querySelector('#cut-at');
  const plane = new THREE.Plane();
  stage.renderer.localClippingEnabled = true;
  const apply = () => {
    const k = Number(axis.value);
    const lo = stage.box.min.getComponent(k), hi = stage.box.max.getComponent(k);
    const normal = new THREE.Vector3().setComponent(k, -1);
    plane.set(normal, lo + (hi - lo) * (at.value / 1000));  // keeps the side below the cut
    stage.content.traverse((o) => {
      if (!o.material) return;
      for (const m of Array.isArray(o.material) ? o.material : [o.material]) {
        const want = on.checked ? [plane] : [];
        if (m.clippingPlanes?.length !== want.length) m.needsUpdate = true;
        m.clippingPlanes = want;
        m.clipShadows = true;
      }
    });
    stage.requestRender();
  };
  on.onchange = axis.onchange = at.oninput = apply;
  return { apply };
}
