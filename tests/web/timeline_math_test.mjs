// The wound timeline's bookkeeping in the browser (web/js/wound_timeline.js, web/js/time_units.js), checked
// in node: which key maps each timeline entry shows (holds share the maps written once), the bracketing
// pair and weight at any time (the interpolation the shader does), and the slider's time mapping.
//   node tests/web/timeline_math_test.mjs WEB_DIR

import assert from 'node:assert/strict';
import { resolve } from 'node:path';
import { pathToFileURL } from 'node:url';

const web = resolve(process.argv[2] || 'web');
const load = (m) => import(pathToFileURL(resolve(web, 'js', m)).href);
let three = true;
const tl = await load('wound_timeline.js').catch(() => { three = false; return null; });
const units = await load('time_units.js');
if (!three) {
  console.log('SKIP: three.js is not installed in web/node_modules (npm ci)');
  process.exit(77);
}

// Five entries; entry 3 holds entry 2 (same maps), an instant cut between entries 1 and 2.
const timeline = {
  entries: [{ time_s: 0 }, { time_s: 600 }, { time_s: 600 }, { time_s: 86400 }, { time_s: 864000 }],
  key_files: ['key0_vasoconstriction', 'key1_vasodilation', 'key2_scab', 'key4_maturation'],
};
const keys = tl.entryKeys(timeline);
assert.deepEqual(keys, [0, 1, 2, 2, 3]);
let b = tl.bracket(timeline, keys, 300);
assert.deepEqual([b.a, b.b, b.w], [0, 1, 0.5]);
b = tl.bracket(timeline, keys, 600);  // the instant cut: at its time the later key shows
assert.deepEqual([b.a, b.b, b.w], [2, 2, 0]);
b = tl.bracket(timeline, keys, 43500);  // inside a hold: both sides are key 2
assert.deepEqual([b.a, b.b], [2, 2]);
b = tl.bracket(timeline, keys, 86400 + 0.25 * (864000 - 86400));
assert.deepEqual([b.a, b.b], [2, 3]);
assert.ok(Math.abs(b.w - 0.25) < 1e-12);
assert.deepEqual([tl.bracket(timeline, keys, -5).a, tl.bracket(timeline, keys, 1e12).a], [0, 3]);
// Weights rise monotonically from 0 to 1 across an interval.
let last = -1;
for (let t = 86400; t < 864000; t += 7777) {
  const w = tl.bracket(timeline, keys, t).w;
  assert.ok(w > last && w >= 0 && w < 1);
  last = w;
}

// Slider: log scale, ends map to ends, round trip, monotone.
for (const t of [0, 1, 60, 3600, 86400, 864000]) {
  assert.ok(Math.abs(units.sliderToTime(units.timeToSlider(t, 0, 864000), 0, 864000) - t) < 1e-6 * (1 + t));
}
assert.equal(units.sliderToTime(0, 0, 864000), 0);
assert.ok(Math.abs(units.sliderToTime(1, 0, 864000) - 864000) < 1e-6);
assert.equal(units.formatInjuryTime(36 * 3600), '36.0 h');
assert.equal(units.formatInjuryTime(5 * 86400), '5.0 days');
assert.equal(units.formatInjuryTime(21 * 86400), '3.0 weeks');
assert.equal(units.formatInjuryTime(90), '1.5 min');
console.log('timeline math: all checks passed');
