// A wound run's healing timeline on its mesh, scrubbed in real time: the key positions' map sets (colour,
// roughness, normal; written by `forensim wound` into maps/) are loaded once as textures, and any moment is
// the linear interpolation of its two neighbouring key positions (Linnenbank 2015, section 3.2), done in the
// fragment shader: a MeshStandardMaterial whose map, roughness and normal samples are mixed with a second
// set by a uniform weight. Moving the slider changes two texture bindings and one float.

import * as THREE from 'three';
import { fileUrl } from './api.js';

const loader = new THREE.TextureLoader();

function loadTexture(url, srgb) {
  return new Promise((resolve, reject) => {
    loader.load(url, (t) => {
      t.flipY = false;  // glTF UVs (v down), as the run's GLB carries them
      t.colorSpace = srgb ? THREE.SRGBColorSpace : THREE.NoColorSpace;
      t.wrapS = t.wrapT = THREE.ClampToEdgeWrapping;
      t.anisotropy = 4;
      resolve(t);
    }, undefined, () => reject(new Error('cannot load ' + url)));
  });
}

/// Mixes every sample of `sampler` in `chunk` with the same sample of `sampler + 'B'`.
function mixedChunk(chunk, sampler, uv) {
  const one = `texture2D( ${sampler}, ${uv} )`;
  if (!chunk.includes(one)) throw new Error(`three.js shader chunk changed: no ${one}`);
  return chunk.split(one).join(`mix( ${one}, texture2D( ${sampler}B, ${uv} ), woundMix )`);
}

/// The key position (index into timeline.key_files) each timeline entry shows: entries that hold the
/// previous one share its maps, so `forensim wound` wrote maps only for the first of each run of entries.
export function entryKeys(timeline) {
  const byEntry = new Map();
  timeline.key_files.forEach((prefix, k) => byEntry.set(Number(/^key(\d+)_/.exec(prefix)[1]), k));
  const keys = [];
  let current = 0;
  timeline.entries.forEach((_, i) => {
    if (byEntry.has(i)) current = byEntry.get(i);
    keys.push(current);
  });
  return keys;
}

/// The two key positions around time `t` (s) and the weight of the second: t between entries i and i + 1
/// gives w = (t - t_i) / (t_{i+1} - t_i); instant cuts (equal times) jump; outside, the end keys.
export function bracket(timeline, keys, t) {
  const e = timeline.entries;
  if (t <= e[0].time_s) return { a: keys[0], b: keys[0], w: 0 };
  for (let i = 0; i + 1 < e.length; ++i) {
    const t0 = e[i].time_s, t1 = e[i + 1].time_s;
    if (t >= t0 && t < t1) return { a: keys[i], b: keys[i + 1], w: (t - t0) / (t1 - t0), entry: i };
  }
  const last = keys[keys.length - 1];
  return { a: last, b: last, w: 0, entry: e.length - 1 };
}

export class WoundTimeline {
  /// `run`: /api/run's description of a wound run. With `renderer`, every map is uploaded at once, so the
  /// first pass of the slider over a key position does not stall on its upload.
  static async load(run, renderer = null) {
    const tl = new WoundTimeline();
    tl.run = run;
    tl.timeline = run.timeline;
    tl.keys = entryKeys(tl.timeline);
    const base = run.path ? run.path + '/maps/' : 'maps/';
    tl.maps = await Promise.all(tl.timeline.key_files.map(async (prefix) => {
      const [color, roughness, normal] = await Promise.all([
        loadTexture(fileUrl(base + prefix + '_color.png'), true),
        loadTexture(fileUrl(base + prefix + '_roughness.png'), false),
        loadTexture(fileUrl(base + prefix + '_normal.png'), false),
      ]);
      return { color, roughness, normal };
    }));
    if (renderer) for (const m of tl.maps) for (const t of Object.values(m)) renderer.initTexture(t);
    tl.material = tl.makeMaterial();
    tl.setTime(0);
    return tl;
  }

  makeMaterial() {
    const m0 = this.maps[0];
    const material = new THREE.MeshStandardMaterial({
      map: m0.color, roughnessMap: m0.roughness, normalMap: m0.normal, roughness: 1, metalness: 0,
      side: THREE.DoubleSide,
    });
    this.uniforms = {
      mapB: { value: m0.color }, roughnessMapB: { value: m0.roughness }, normalMapB: { value: m0.normal },
      woundMix: { value: 0 },
    };
    material.onBeforeCompile = (shader) => {
      Object.assign(shader.uniforms, this.uniforms);
      const chunks = THREE.ShaderChunk;
      shader.fragmentShader = shader.fragmentShader
        .replace('#include <common>', '#include <common>\nuniform sampler2D mapB;\nuniform sampler2D roughnessMapB;\n' +
                 'uniform sampler2D normalMapB;\nuniform float woundMix;')
        .replace('#include <map_fragment>', mixedChunk(chunks.map_fragment, 'map', 'vMapUv'))
        .replace('#include <roughnessmap_fragment>',
                 mixedChunk(chunks.roughnessmap_fragment, 'roughnessMap', 'vRoughnessMapUv'))
        .replace('#include <normal_fragment_maps>',
                 mixedChunk(chunks.normal_fragment_maps, 'normalMap', 'vNormalMapUv'));
    };
    material.customProgramCacheKey = () => 'forensim-wound-mix';
    return material;
  }

  get startTime() { return this.timeline.entries[0].time_s; }
  get endTime() { return this.timeline.entries[this.timeline.entries.length - 1].time_s; }

  /// Shows the wound `t` seconds after injury. Returns {a, b, w, entry}.
  setTime(t) {
    const k = bracket(this.timeline, this.keys, t);
    const A = this.maps[k.a], B = this.maps[k.b];
    this.material.map = A.color;
    this.material.roughnessMap = A.roughness;
    this.material.normalMap = A.normal;
    this.uniforms.mapB.value = B.color;
    this.uniforms.roughnessMapB.value = B.roughness;
    this.uniforms.normalMapB.value = B.normal;
    this.uniforms.woundMix.value = k.w;
    this.time = t;
    this.current = k;
    return k;
  }

  /// The label of the phase shown at the current time.
  phaseLabel() {
    const e = this.timeline.entries[this.current.entry ?? 0];
    return e ? e.label || e.phase : '';
  }

  dispose() {
    for (const m of this.maps) for (const t of Object.values(m)) t.dispose();
    this.material.dispose();
  }
}
