// The skull editor's helpers (web/js/skull_math.js), checked in node: the server's base64 float32 and uint32
// arrays decode to the values encoded, the confidence colour runs continuously from red to green, an
// expression's play weight rises from 0 to 1 and back, the blend reaches the pose, and the median.
//   node tests/web/skull_math_test.mjs WEB_DIR

import assert from 'node:assert/strict';
import { resolve } from 'node:path';
import { pathToFileURL } from 'node:url';

const web = resolve(process.argv[2] || 'web');
const m = await import(pathToFileURL(resolve(web, 'js', 'skull_math.js')).href);

// Round trip through the byte layout the server writes (little-endian float32 / uint32, base64).
const values = new Float32Array([0, -1.5, 3.25, 1e-3, -81.617, 1e5]);
const b64 = Buffer.from(values.buffer).toString('base64');
assert.deepEqual(Array.from(m.float32Array(b64)), Array.from(values));
const indices = new Uint32Array([0, 1, 2, 70000, 4294967295]);
assert.deepEqual(Array.from(m.uint32Array(Buffer.from(indices.buffer).toString('base64'))), Array.from(indices));

// Confidence colour: red at 0, green at 1, continuous (no jump at 0.5), clamped outside [0, 1].
const [r0, g0] = m.confidenceColour(0), [r1, g1] = m.confidenceColour(1);
assert.ok(r0 > 2 * g0 && g1 > 2 * r1, 'red at 0, green at 1');
const below = m.confidenceColour(0.5 - 1e-9), above = m.confidenceColour(0.5 + 1e-9);
for (let k = 0; k < 3; ++k) assert.ok(Math.abs(below[k] - above[k]) < 1e-6, 'continuous at 0.5');
assert.deepEqual(m.confidenceColour(-1), m.confidenceColour(0));
assert.deepEqual(m.confidenceColour(2), m.confidenceColour(1));
for (let c = 0; c <= 1; c += 0.05) for (const v of m.confidenceColour(c)) assert.ok(v >= 0 && v <= 1);

// Play weight: 0 at both ends and outside, 1 in the middle, never outside [0, 1], symmetric about the middle.
assert.equal(m.playWeight(0, 2), 0);
assert.equal(m.playWeight(2, 2), 0);
assert.equal(m.playWeight(-1, 2), 0);
assert.equal(m.playWeight(1, 2), 1);
for (let t = 0; t <= 2; t += 0.01) {
  const w = m.playWeight(t, 2);
  assert.ok(w >= 0 && w <= 1);
  assert.ok(Math.abs(w - m.playWeight(2 - t, 2)) < 1e-9, `symmetric at ${t}`);
}

// Blend: w = 0 the neutral face, w = 1 the pose, w = 0.5 halfway.
const neutral = new Float32Array([0, 0, 0, 1, 2, 3]), pose = new Float32Array([2, 0, -2, 1, 4, 3]);
const out = new Float32Array(6);
assert.deepEqual(Array.from(m.blendPositions(out, neutral, pose, 0)), Array.from(neutral));
assert.deepEqual(Array.from(m.blendPositions(out, neutral, pose, 1)), Array.from(pose));
assert.deepEqual(Array.from(m.blendPositions(out, neutral, pose, 0.5)), [1, 0, -1, 1, 3, 3]);

assert.equal(m.median([5, 1, 3]), 3);
assert.equal(m.median([4, 1, 3, 2]), 2.5);
assert.ok(Number.isNaN(m.median([])));
console.log('skull editor helpers: all checks passed');
