// The run viewer's false colour (web/js/false_colour.js), checked in node: per-vertex dual areas sum to the
// surface's area, shrinkage of a uniformly scaled surface is 1 - s^2 everywhere and 0 at rest, the modes a
// frame offers follow its fields, and colour maps and ranges hit their ends.
//   node tests/web/false_colour_test.mjs WEB_DIR

import assert from 'node:assert/strict';
import { resolve } from 'node:path';
import { pathToFileURL } from 'node:url';

const web = resolve(process.argv[2] || 'web');
const near = (a, b, what) => a.forEach((x, k) => assert.ok(Math.abs(x - b[k]) < 1e-6, `${what}: ${a} vs ${b}`));
const fc = await import(pathToFileURL(resolve(web, 'js', 'false_colour.js')).href);

// A closed octahedron of "radius" 2 mm: 8 equilateral faces of side 2 sqrt(2).
const positions = [2, 0, 0, -2, 0, 0, 0, 2, 0, 0, -2, 0, 0, 0, 2, 0, 0, -2];
const triangles = [0, 2, 4, 2, 1, 4, 1, 3, 4, 3, 0, 4, 2, 0, 5, 1, 2, 5, 3, 1, 5, 0, 3, 5];
const frame = { vertex_count: 6, positions, triangles, scalars: {} };
const areas = fc.vertexAreas(positions, triangles, 6);
const faceArea = (Math.sqrt(3) / 4) * 8;  // side^2 = 8
const total = areas.reduce((s, a) => s + a, 0);
assert.ok(Math.abs(total - 8 * faceArea) < 1e-12, `dual areas sum to the area (${total})`);
for (const a of areas) assert.ok(Math.abs(a - (4 * faceArea) / 3) < 1e-12, 'each vertex has a third of its 4 faces');

// Uniform scale by s: every vertex loses 1 - s^2 of its area; a moved (not scaled) copy loses nothing.
const s = 0.9;
const scaled = { ...frame, positions: positions.map((x) => s * x) };
for (const v of fc.shrinkagePercent(scaled, positions)) assert.ok(Math.abs(v - 100 * (1 - s * s)) < 1e-9, `${v}`);
const moved = { ...frame, positions: positions.map((x, i) => x + (i % 3 === 0 ? 5 : 0)) };
for (const v of fc.shrinkagePercent(moved, positions)) assert.ok(Math.abs(v) < 1e-9);
// Stretching one vertex outwards grows its area: negative shrinkage there.
const pulled = { ...frame, positions: positions.map((x, i) => (i === 0 ? 3 : x)) };
assert.ok(fc.shrinkagePercent(pulled, positions)[0] < 0);

// Modes: shrinkage always; moisture, uncertainty and the skin's colour only when the frame has them.
const ids = (f) => fc.colourModes(f).map((m) => m.id);
assert.deepEqual(ids(frame), ['shrinkage']);
const skin = { ...frame, scalars: { moisture_ratio: [1, 1, 1, 1, 1, 1], part: [0, 0, 0, 0, 0, 0] },
               vectors: { colour: Array(18).fill(0.5) } };
assert.deepEqual(ids(skin), ['colour', 'moisture', 'shrinkage', 'field:part']);
const recon = { ...frame, scalars: { uncertainty: [1, 2, 3, 4, 5, 6] } };
const u = fc.colourModes(recon).find((m) => m.id === 'uncertainty');
assert.equal(u.unit, 'mm');
assert.deepEqual(fc.rangeOf(u.values(recon)), [1, 6]);
assert.deepEqual(fc.rangeOf([NaN, 2, -1, Infinity]), [-1, 2]);
// A series' range: the union of its ends; shrinkage symmetric about 0, so no change is the map's middle.
assert.deepEqual(fc.seriesRange('uncertainty', [1, 3], [2, 6]), [1, 6]);
assert.deepEqual(fc.seriesRange('shrinkage', [-3.5, 0], [-1, 5.25]), [-5.25, 5.25]);
assert.deepEqual(fc.seriesRange('shrinkage', [0, 0], [0, 0]), [-0.1, 0.1]);
const mid = fc.COLOUR_MAPS.shrinkage[(fc.COLOUR_MAPS.shrinkage.length - 1) / 2];
near(Array.from(fc.coloursOf([0], fc.seriesRange('shrinkage', [-2, 0], [0, 1]), fc.COLOUR_MAPS.shrinkage, 1)), mid,
     'no shrinkage in the pale middle');

// Colour maps: the ends are the first and last stops; values outside the range clamp.
for (const [name, map] of Object.entries(fc.COLOUR_MAPS)) {
  near(fc.mapColour(map, 0), map[0], name + ' at 0');
  near(fc.mapColour(map, 1), map[map.length - 1], name + ' at 1');
  near(fc.mapColour(map, -3), map[0], name + ' below 0');
  near(fc.mapColour(map, 7), map[map.length - 1], name + ' above 1');
}
const c = fc.coloursOf([1, 6, 3.5, 1, 1, 1], [1, 6], fc.COLOUR_MAPS.uncertainty, 6);
near(Array.from(c.slice(3, 6)), fc.COLOUR_MAPS.uncertainty[4], 'the top of the range');
near(Array.from(c.slice(6, 9)), fc.COLOUR_MAPS.uncertainty[2], 'the middle of the range');
console.log('false colour: all checks passed');
