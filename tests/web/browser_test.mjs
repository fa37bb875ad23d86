// Browser tests of forensim serve's front end: starts `forensim serve` on a free loopback port over a
// scratch folder holding a small wound run, a small desiccation run (made by the forensim executable) and a
// surface run with an "uncertainty" field, drives Debian's chromium headless through playwright-core, and
// checks each view: the runs list, a wound run's timeline scrubbed (the wound's colour changes with time), the
// wound editor (a stroke painted by ray cast, the timeline generated on the server and scrubbed), a
// desiccation run stepped frame by frame and coloured by moisture, shrinkage and the skin's colour, the
// surface run coloured by its uncertainty, a run holding only a GLB, and the skull editor on the built-in skull
// (landmarks dragged with the mouse, the face redrawn; see skullEditor). No console errors or page errors are
// allowed.
//
// Golden screenshots: the 3D canvas of each view, drawn at a fixed window size from a camera preset and
// halved, is compared with tests/golden/web/NAME.png over the pixels that show the object in either picture:
// it passes when their mean absolute difference is at most 3 (of 255) and at most 2 % of them differ by more
// than 32 in a channel (two different views of the same arm differ by 15 and 18 %). Headless chromium
// draws WebGL with SwiftShader (on the CPU), so the pictures are stable on one machine type. Regenerate the
// goldens after an intended change of the views with
//   FORENSIM_UPDATE_GOLDENS=1 node tests/web/browser_test.mjs --forensim build/release/bin/forensim --web web
// (or FORENSIM_UPDATE_GOLDENS=1 ctest --test-dir build/release -R web_browser) and commit them.
//
// Measured and printed, not asserted: frames per second while the time slider of a 2048^2 wound map set is
// moved every frame (requestAnimationFrame callbacks counted over 3 s, and the stage's frames drawn in them; --fps-resolution N to change the
// maps' size, 0 to skip), and the skull editor's time from a landmark drag's release to the updated face drawn.
// Screenshots of every view go to --shots DIR when given; --only skull tests the skull editor alone (--only
// wound, desiccation or surface another view alone)
// (--skull-detail coarse for a quicker template).
//
//   node tests/web/browser_test.mjs --forensim build/release/bin/forensim --web web [--shots DIR]
//        [--goldens tests/golden/web] [--fps-resolution 2048] [--only skull|wound|desiccation|surface] [--skull-detail full|coarse]
// Exit codes: 0 pass, 1 fail, 77 skipped (no chromium or no playwright-core).

import { spawn, spawnSync } from 'node:child_process';
import { existsSync, mkdtempSync, mkdirSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { createRequire } from 'node:module';
import { tmpdir } from 'node:os';
import { dirname, join, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';

const args = Object.fromEntries(process.argv.slice(2).reduce((pairs, a, i, all) => {
  if (a.startsWith('--')) pairs.push([a.slice(2), all[i + 1]]);
  return pairs;
}, []));
const forensim = resolve(args.forensim || 'build/release/bin/forensim');
const web = resolve(args.web || 'web');
const chromiumPath = args.chromium || '/usr/bin/chromium';
const goldens = resolve(args.goldens || join(dirname(fileURLToPath(import.meta.url)), '../golden/web'));
const updateGoldens = ['1', 'yes', 'true'].includes(process.env.FORENSIM_UPDATE_GOLDENS || '');
const fpsResolution = Number(args['fps-resolution'] ?? 2048);
// --only wound|desiccation|surface|skull: that view alone (quicker, for working on it); the wound part includes
// the frame rate of the large map set.
const only = args.only || '';
if (only && !['wound', 'desiccation', 'surface', 'skull'].includes(only)) {
  console.log(`--only ${only}: expected wound, desiccation, surface or skull`);
  process.exit(2);
}
const want = (part) => !only || only === part;
const SKIP = 77;

function skip(why) {
  console.log(`SKIP: ${why}`);
  process.exit(SKIP);
}
if (!existsSync(chromiumPath)) skip(`no chromium at ${chromiumPath} (scripts/install-deps installs Debian's chromium)`);
let chromium;
try {
  chromium = createRequire(join(web, 'package.json'))('playwright-core').chromium;
} catch {
  skip(`no playwright-core in ${web}/node_modules (scripts/install-deps runs npm ci there)`);
}
if (!existsSync(join(web, 'node_modules/three/build/three.module.js'))) skip('no three.js in web/node_modules');

const failures = [];
function check(condition, what) {
  console.log(`${condition ? 'ok  ' : 'FAIL'} ${what}`);
  if (!condition) failures.push(what);
}

function run(argv) {
  const r = spawnSync(forensim, argv, { encoding: 'utf8' });
  if (r.status !== 0) throw new Error(`forensim ${argv.join(' ')} failed (${r.status}): ${r.stderr}`);
}

// The same in the background (the large wound run for the frame rate is made while the views are tested).
function runLater(argv) {
  return new Promise((ok, fail) => {
    const child = spawn(forensim, argv, { stdio: ['ignore', 'ignore', 'pipe'] });
    let err = '';
    child.stderr.on('data', (d) => { err += d; });
    child.on('exit', (code) => (code === 0 ? ok() : fail(new Error(`forensim ${argv.join(' ')} failed (${code}): ${err}`))));
  });
}

// A run folder as a reconstruction writes its skin: run.json and skin.vtu (ASCII VTK triangles, mm), a
// head-sized ellipsoid (90 x 110 x 120 mm semi-axes, 48 x 24 segments) with the point field "uncertainty"
// (mm), growing from 1 mm at the front (-y) to 4 mm at the back.
function writeSurfaceRun(folder) {
  mkdirSync(folder, { recursive: true });
  const rings = 24, segments = 48, points = [], uncertainty = [], triangles = [];
  for (let i = 0; i <= rings; ++i) {
    const theta = Math.PI * i / rings;
    for (let j = 0; j < segments; ++j) {
      const phi = 2 * Math.PI * j / segments;
      const d = [Math.sin(theta) * Math.cos(phi), Math.sin(theta) * Math.sin(phi), Math.cos(theta)];
      points.push(90 * d[0], 110 * d[1], 120 * d[2]);
      uncertainty.push(2.5 + 1.5 * d[1]);
    }
  }
  const at = (i, j) => i * segments + (j % segments);
  for (let i = 0; i < rings; ++i) {
    for (let j = 0; j < segments; ++j) {
      triangles.push(at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j), at(i + 1, j + 1), at(i, j + 1));
    }
  }
  const cells = triangles.length / 3, n = points.length / 3;
  const offsets = Array.from({ length: cells }, (_, c) => 3 * (c + 1));
  writeFileSync(join(folder, 'run.json'), JSON.stringify({ command: 'reconstruct', outputs: ['skin.vtu'] }));
  writeFileSync(join(folder, 'skin.vtu'), `<?xml version="1.0"?>
<VTKFile type="UnstructuredGrid" version="1.0" byte_order="LittleEndian" header_type="UInt64">
<UnstructuredGrid><Piece NumberOfPoints="${n}" NumberOfCells="${cells}">
<Points><DataArray type="Float64" NumberOfComponents="3" format="ascii">${points.map((x) => x.toFixed(4)).join(' ')}</DataArray></Points>
<Cells><DataArray type="Int64" Name="connectivity" format="ascii">${triangles.join(' ')}</DataArray>
<DataArray type="Int64" Name="offsets" format="ascii">${offsets.join(' ')}</DataArray>
<DataArray type="UInt8" Name="types" format="ascii">${Array(cells).fill(5).join(' ')}</DataArray></Cells>
<PointData><DataArray type="Float64" Name="uncertainty" format="ascii">${uncertainty.map((x) => x.toFixed(4)).join(' ')}</DataArray></PointData>
</Piece></UnstructuredGrid></VTKFile>
`);
}

// The skull editor: loads the built-in skull (landmarks detected, with confidences), compares the view with
// its golden, drags landmark g (glabella) up and down over the skull with the mouse several times and checks
// that the face's vertices moved; then skin transparency, a build change, an expression played, the guides,
// the exports, the violation counts and a landmark (pogonion) removed with the Delete key. Measured and
// printed, not asserted: the median time from a drag's release to the updated face drawn (goal: under
// 200 ms), and the server's share of it.
async function skullEditor({ page, base, open, golden, shot, canvasColour, distance, settle }) {
  const t0 = Date.now();
  await open(`#/skull?skull=builtin&landmarks=auto&detail=${args['skull-detail'] || 'full'}`, 600000);
  console.log(`skull editor ready in ${((Date.now() - t0) / 1000).toFixed(1)} s (template, detection, reconstruction)`);
  const info = await page.evaluate(() => {
    const { skull } = window.forensim;
    return { markers: skull.markers.children.length, vertices: skull.face.geometry.attributes.position.count };
  });
  check(info.markers >= 20 && info.vertices > 1000, `skull editor: ${info.markers} landmarks, ${info.vertices} face vertices`);
  const colours = await page.evaluate(() => new Set(window.forensim.skull.markers.children.map((m) => m.material.color.getHexString())).size);
  check(colours > 1, `landmarks coloured by confidence (${colours} colours)`);
  await settle();
  await golden('skull_editor.png');
  await shot('skull_editor.png');

  const facePositions = () => page.evaluate(() => Array.from(window.forensim.skull.face.geometry.attributes.position.array));
  const before = await facePositions();
  let afterFirst = null;
  const drags = 7;
  const dragStart = await page.evaluate(() => ({ drawn: window.forensim.stage.drawn, at: performance.now() }));
  for (let i = 0; i < drags; ++i) {
    const p = await page.evaluate(() => window.forensim.skull.screenPosition('g'));
    const version = await page.evaluate(() => window.forensim.skull.faceVersion());
    const dy = i % 2 ? 12 : -12;
    await page.mouse.move(p.x, p.y);
    await page.mouse.down();
    for (let k = 1; k <= 4; ++k) await page.mouse.move(p.x, p.y + (dy * k) / 4);
    await page.mouse.up();
    await page.waitForFunction((n) => window.forensim.skull.latencies.length >= n, i + 1, { timeout: 60000 });
    const after = await page.evaluate(() => window.forensim.skull.faceVersion());
    if (i === 0) {
      check(after > version, `the face was redrawn after the drag (version ${version} -> ${after})`);
      afterFirst = await facePositions();
    }
  }
  const moved = await facePositions();
  let largest = 0;
  for (let i = 0; i < before.length; i += 3) {
    largest = Math.max(largest, Math.hypot(afterFirst[i] - before[i], afterFirst[i + 1] - before[i + 1],
                                           afterFirst[i + 2] - before[i + 2]));
  }
  check(largest > 0.05, `dragging g moved the face (largest vertex displacement ${largest.toFixed(2)} mm)`);
  const g = await page.evaluate(() => window.forensim.skull.markers.children.length);
  check(g === info.markers, 'the landmark set kept its size while dragging');
  const latencies = await page.evaluate(() => window.forensim.skull.latencies);
  const med = (xs) => { const v = [...xs].sort((a, b) => a - b); const m = v.length >> 1; return v.length % 2 ? v[m] : (v[m - 1] + v[m]) / 2; };
  const total = latencies.map((l) => l.total_ms), server = latencies.map((l) => l.server_ms);
  const part = (key) => med(latencies.map((l) => l[key])).toFixed(0);
  const fps = await page.evaluate((d) => (window.forensim.stage.drawn - d.drawn) * 1000 / (performance.now() - d.at),
                                  dragStart);
  console.log(`measured: drag release to updated face drawn: median ${med(total).toFixed(0)} ms over ${total.length} drags ` +
              `(${Math.min(...total).toFixed(0)} to ${Math.max(...total).toFixed(0)} ms; medians: waiting for the live ` +
              `request ${part('wait_ms')} ms, final request ${part('request_ms')} ms, applying ${part('apply_ms')} ms, ` +
              `next frame ${part('frame_ms')} ms; server update ${med(server).toFixed(0)} ms; shown on screen (the ` +
              `following frame began) after ${part('shown_ms')} ms; ` +
              `${fps.toFixed(1)} frames/s drawn over the drags; goal under 200 ms)`);
  await shot('skull_editor_dragged.png');

  // Skin transparency: the opaque skin hides the skull at the face's centre.
  const clear = await canvasColour(0.5, 0.45, 10);
  await page.click('#transparent');
  await settle();
  const opaque = await canvasColour(0.5, 0.45, 10);
  check(distance(clear, opaque) > 0.02, `skin transparency toggles (${distance(clear, opaque).toFixed(3)})`);
  await page.click('#transparent');
  // Build: obese depths make the face larger.
  const version = await page.evaluate(() => window.forensim.skull.faceVersion());
  await page.selectOption('#build', 'obese');
  await page.waitForFunction((v) => window.forensim.skull.faceVersion() > v, version);
  const obese = await facePositions();
  let changed = 0;
  for (let i = 0; i < obese.length; ++i) changed = Math.max(changed, Math.abs(obese[i] - moved[i]));
  check(changed > 0.5, `the obese build moves the face (${changed.toFixed(2)} mm): ${await page.textContent('#depth-group')}`);
  // An expression plays and ends.
  await page.click('button[data-expression="smile"]');
  await page.waitForFunction(() => document.body.dataset.played === 'smile', null, { timeout: 120000 });
  check(true, 'the smile expression played');
  // Guides on: the second warp answers.
  await page.click('#guides-on');
  await page.waitForFunction(() => document.body.dataset.guides === 'on', null, { timeout: 60000 });
  check(true, 'the nose and mouth guides applied');
  // Exports.
  const id = await page.evaluate(() => document.body.dataset.skullSession);
  const mrk = await (await fetch(`${base}api/skull/sessions/${id}/skull_landmarks.mrk.json`)).json();
  const points = mrk.markups[0].controlPoints;
  const gPoint = points.find((c) => c.label === 'g');
  check(points.length === info.markers && gPoint && /source=edited/.test(gPoint.description),
        `landmarks export as .mrk.json (${points.length} points, g ${gPoint ? gPoint.description : 'missing'})`);
  const glb = Buffer.from(await (await fetch(`${base}api/skull/sessions/${id}/head.glb?expressions=smile`)).arrayBuffer());
  check(glb.subarray(0, 4).toString() === 'glTF', `the head exports as GLB (${(glb.length / 1024).toFixed(0)} KiB)`);

  // The violation counts, asked for after the changes settled.
  const violationsShown = () => page.waitForFunction(() => /skull through skin: \d+ vertices/.test(
    document.getElementById('violations').textContent), null, { timeout: 120000 });
  await violationsShown();
  check(true, `violations shown: "${await page.textContent('#violations')}"`);
  // Removing a landmark: click pogonion's marker to select it, press Delete; the chin loses its pair.
  const beforeRemoval = await facePositions();
  const removalVersion = await page.evaluate(() => window.forensim.skull.faceVersion());
  const asked = await page.evaluate(() => Number(document.body.dataset.violations || 0));
  const pg = await page.evaluate(() => window.forensim.skull.screenPosition('pg'));
  await page.mouse.move(pg.x, pg.y);
  await page.mouse.down();
  await page.mouse.up();
  check(await page.isEnabled('#remove'), 'a clicked landmark is selected for removal');
  await page.keyboard.press('Delete');
  await page.waitForFunction((v) => window.forensim.skull.faceVersion() > v, removalVersion);
  const afterRemoval = await facePositions();
  let removalMoved = 0;
  for (let i = 0; i < afterRemoval.length; ++i) removalMoved = Math.max(removalMoved, Math.abs(afterRemoval[i] - beforeRemoval[i]));
  const left = await page.evaluate(() => window.forensim.skull.markers.children.map((m) => m.userData.name));
  check(left.length === info.markers - 1 && !left.includes('pg') && removalMoved > 0.05,
        `removing pg changes the face (${removalMoved.toFixed(2)} mm; ${left.length} landmarks left)`);
  await page.waitForFunction((n) => Number(document.body.dataset.violations || 0) > n &&
    /skull through skin: \d+/.test(document.getElementById('violations').textContent), asked, { timeout: 120000 });
  console.log(`measured: after removing pg, ${await page.textContent('#violations')}`);

  // The nose tip by Krogman's rule needs ans (the spine's tip) in front of ss (subspinale); the built-in
  // skull's detected ans does not stand in front of its ss (the phantom has no protruding spine), so there the
  // control is off with the reason given; elsewhere switching it on moves the face.
  const spineInfo = await page.textContent('#spine-info');
  const spineOff = await page.isDisabled('#spine-on');
  check(/spine ans to ss/.test(spineInfo) !== spineOff && spineInfo.length > 0,
        `the nose tip guide ${spineOff ? 'is off' : 'is available'}: "${spineInfo}"`);
  if (/spine ans to ss/.test(spineInfo)) {
    const unguidedNose = await facePositions();
    await page.evaluate(() => { document.body.dataset.guides = ''; });
    await page.click('#spine-on');
    await page.waitForFunction(() => document.body.dataset.guides === 'on', null, { timeout: 60000 });
    const guidedNose = await facePositions();
    let noseMoved = 0;
    for (let i = 0; i < guidedNose.length; ++i) noseMoved = Math.max(noseMoved, Math.abs(guidedNose[i] - unguidedNose[i]));
    check(noseMoved > 0.05, `Krogman's rule moves the nose tip (${noseMoved.toFixed(2)} mm)`);
  }
}

const started = Date.now();
const served = mkdtempSync(join(tmpdir(), 'forensim-web-'));
let server, browser;
try {
  const t0 = Date.now();
  if (want('wound')) {
    run(['wound', '--builtin', 'cylinder', '--resolution', '256', '--times', '36h', '--picture-size', '0',
         '-o', join(served, 'wound-run')]);
  }
  if (want('desiccation')) {
    run(['mummify', '--phantom', 'arm', '--size', 'small', '--days', '2', '--frames', '2', '--no-pictures',
         '-o', join(served, 'dry-run')]);
  }
  if (want('surface')) writeSurfaceRun(join(served, 'surface-run'));
  console.log(`runs made in ${((Date.now() - t0) / 1000).toFixed(1)} s`);
  const bigRun = fpsResolution > 0 && want('wound')
    ? runLater(['wound', '--builtin', 'forearm-uv', '--resolution', String(fpsResolution), '--times', '36h',
                '--picture-size', '0', '-o', join(served, 'wound-big')]).then(() => Date.now() - t0)
    : null;
  if (bigRun) bigRun.catch(() => {});  // awaited (and its failure reported) at the frame-rate step

  server = spawn(forensim, ['serve', '--port', '0', '--web', web, served], { stdio: ['ignore', 'pipe', 'pipe'] });
  const base = await new Promise((ok, fail) => {
    let out = '';
    server.stdout.on('data', (d) => {
      out += d;
      const m = /http:\/\/127\.0\.0\.1:(\d+)\//.exec(out);
      if (m) ok(`http://127.0.0.1:${m[1]}/`);
    });
    server.on('exit', (code) => fail(new Error(`forensim serve exited (${code}): ${out}`)));
    setTimeout(() => fail(new Error('forensim serve did not start')), 20000);
  });
  console.log(`serving ${served} at ${base}`);

  browser = await chromium.launch({
    executablePath: chromiumPath,
    args: ['--headless', '--no-sandbox', '--disable-gpu', '--disable-background-networking',
           '--disable-component-update', '--disable-sync', '--no-first-run', '--enable-unsafe-swiftshader',
           '--use-angle=swiftshader'],
  });
  const page = await browser.newPage({ viewport: { width: 960, height: 600 } });
  page.setDefaultTimeout(120000);  // loaded CI machines draw software WebGL slowly
  page.setDefaultNavigationTimeout(120000);
  const consoleErrors = [];
  page.on('console', (m) => { if (m.type() === 'error') consoleErrors.push(m.text()); });
  page.on('pageerror', (e) => consoleErrors.push(String(e)));
  const shots = args.shots ? resolve(args.shots) : null;
  if (shots) mkdirSync(shots, { recursive: true });
  const shot = async (name) => { if (shots) await page.screenshot({ path: join(shots, name) }); };

  const open = async (hash, timeout = 60000) => {
    await page.goto(base + hash);
    await page.waitForFunction(() => ['1', 'error'].includes(document.body.dataset.ready), null, { timeout });
    const state = await page.evaluate(() => document.body.dataset.ready);
    if (state !== '1') throw new Error(`${hash}: ${await page.textContent('#status')}`);
  };
  // Mean linear RGB of a square around a point of the 3D canvas (fractions of its size).
  const canvasColour = (fx = 0.5, fy = 0.5, half = 6) => page.evaluate(([x, y, h]) => {
    const src = document.getElementById('canvas');
    const c = document.createElement('canvas');
    c.width = src.width;
    c.height = src.height;
    const g = c.getContext('2d');
    g.drawImage(src, 0, 0);
    const px = Math.round(x * c.width), py = Math.round(y * c.height);
    const d = g.getImageData(px - h, py - h, 2 * h, 2 * h).data;
    const sum = [0, 0, 0];
    for (let i = 0; i < d.length; i += 4) for (let k = 0; k < 3; ++k) sum[k] += d[i + k];
    return sum.map((s) => s / (d.length / 4) / 255);
  }, [fx, fy, half]);
  const distance = (a, b) => Math.hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]);
  const settle = () => page.waitForTimeout(400);
  const legendTitle = () => page.textContent('#legend-title');

  // The 3D canvas halved (a PNG data URL), compared with the golden of that name within the tolerance above.
  const golden = async (name) => {
    const goldenPath = join(goldens, name);
    const want = existsSync(goldenPath) && !updateGoldens ? readFileSync(goldenPath).toString('base64') : null;
    const r = await page.evaluate(async (wantB64) => {
      const src = document.getElementById('canvas');
      window.forensim.stage.renderer.render(window.forensim.stage.scene, window.forensim.stage.camera);
      const c = document.createElement('canvas');
      c.width = Math.round(src.width / 2);
      c.height = Math.round(src.height / 2);
      const g = c.getContext('2d');
      g.drawImage(src, 0, 0, c.width, c.height);
      const got = g.getImageData(0, 0, c.width, c.height);
      const out = { png: c.toDataURL('image/png'), width: c.width, height: c.height };
      if (!wantB64) return out;
      const image = new Image();
      image.src = 'data:image/png;base64,' + wantB64;
      await image.decode();
      out.goldenSize = [image.width, image.height];
      if (image.width !== c.width || image.height !== c.height) return out;
      const d = document.createElement('canvas');
      d.width = image.width;
      d.height = image.height;
      const dg = d.getContext('2d');
      dg.drawImage(image, 0, 0);
      const ref = dg.getImageData(0, 0, d.width, d.height).data;
      // Over the pixels that show the object in either picture (off the background, the corner's colour, by
      // more than 8), so a small object's change is not diluted by the empty background around it.
      const bg = [ref[0], ref[1], ref[2]];
      let sum = 0, differing = 0, object = 0;
      for (let i = 0; i < ref.length; i += 4) {
        let worst = 0, off = 0;
        for (let k = 0; k < 3; ++k) {
          const e = Math.abs(ref[i + k] - got.data[i + k]);
          sum += e;
          worst = Math.max(worst, e);
          off = Math.max(off, Math.abs(ref[i + k] - bg[k]), Math.abs(got.data[i + k] - bg[k]));
        }
        if (off > 8) ++object;
        if (worst > 32) ++differing;
      }
      out.mean = sum / (3 * Math.max(1, object));
      out.share = differing / Math.max(1, object);
      out.object = object / (ref.length / 4);
      return out;
    }, want);
    const png = Buffer.from(r.png.split(',')[1], 'base64');
    if (shots) writeFileSync(join(shots, 'canvas_' + name), png);
    if (!want) {
      if (!updateGoldens) {
        check(false, `golden ${name}: none in ${goldens} (make it with FORENSIM_UPDATE_GOLDENS=1)`);
        return;
      }
      mkdirSync(goldens, { recursive: true });
      writeFileSync(goldenPath, png);
      console.log(`golden ${name} written (${r.width}x${r.height}, ${(png.length / 1024).toFixed(0)} KiB)`);
      return;
    }
    if (r.mean === undefined) {
      check(false, `golden ${name}: size ${r.width}x${r.height}, golden ${r.goldenSize.join('x')}`);
      return;
    }
    check(r.mean <= 3 && r.share <= 0.02, `golden ${name}: over the object's pixels (${(100 * r.object).toFixed(0)} % ` +
          `of the picture) mean difference ${r.mean.toFixed(2)} of 255, ${(100 * r.share).toFixed(2)} % differ by ` +
          'more than 32');
  };

  if (!only) {
  // 1. The runs list.
  await open('#/runs');
  const runs = await page.$$eval('#runs a', (as) => as.map((a) => a.dataset.run));
  check(['wound-run', 'dry-run', 'surface-run'].every((r) => runs.includes(r)), `runs listed: ${runs.join(', ')}`);
  await shot('runs.png');

  }
  if (want('wound')) {
  // 2. A wound run: its timeline scrubbed in the shader. The wound is the middle of the cylinder's UV square,
  // seen from the front preset; fresh (0 s) and scab (36 h) colours differ.
  await open('#/run?path=wound-run');
  await page.click('button[data-preset="right"]');  // the CLI's default stroke faces +x
  const woundAt = async (seconds) => {
    await page.evaluate((t) => window.forensim.timelineControl.setTime(t), seconds);
    await settle();
    return canvasColour();
  };
  const fresh = await woundAt(3600);
  const scab = await woundAt(36 * 3600);
  const label = await page.textContent('#time-label');
  check(/h|days/.test(label), `time shown in real units: "${label}"`);
  check(distance(fresh, scab) > 0.03, `wound colour changes from 1 h to 36 h (${distance(fresh, scab).toFixed(3)})`);
  await shot('wound_run.png');
  await golden('wound_run.png');
  // Scrubbing by the slider itself.
  for (let v = 0; v <= 1000; v += 250) await page.locator('#time-slider').fill(String(v));
  check(Number(await page.evaluate(() => document.body.dataset.time)) > 36 * 3600, 'the slider at its end shows the end');
  await page.click('#play');
  await page.waitForTimeout(700);
  await page.click('#play');
  const t = Number(await page.evaluate(() => document.body.dataset.time));
  check(t > 0, `play advances the time (${t.toFixed(0)} s)`);

  // 3. The wound editor: paint one stroke on the cylinder by dragging across its front, generate, scrub.
  await open('#/wound?mesh=cylinder');
  const box = await page.locator('#canvas').boundingBox();
  const cx = box.x + box.width / 2, cy = box.y + box.height / 2;
  await page.mouse.move(cx - 40, cy);
  await page.mouse.down();
  for (let i = 0; i <= 8; ++i) await page.mouse.move(cx - 40 + 10 * i, cy + 3 * Math.sin(i));
  await page.mouse.up();
  const strokes = await page.evaluate(() => document.body.dataset.strokes);
  check(strokes === '1', `one stroke painted (${strokes})`);
  await page.selectOption('#resolution', '256');
  const before = await canvasColour();
  await page.click('#generate');
  await page.waitForFunction(() => document.body.dataset.generated, null, { timeout: 180000 });
  await page.evaluate(() => window.forensim.timelineControl.setTime(36 * 3600));
  await settle();
  const painted = await canvasColour();
  check(distance(before, painted) > 0.02, `the painted stroke shows the wound at 36 h (${distance(before, painted).toFixed(3)})`);
  const late = await woundAt(1e9);
  check(distance(painted, late) > 0.01, `the wound changes by the end of the timeline (${distance(painted, late).toFixed(3)})`);
  await woundAt(36 * 3600);
  await shot('wound_editor.png');
  await golden('wound_editor.png');

  }
  if (want('desiccation')) {
  // 4. Desiccation: step the run's frames; the surface colour (water) changes.
  await open('#/desiccation?path=dry-run');
  check(await page.evaluate(() => document.body.dataset.frame) === '0', 'frame 0 shown');
  const wet = await canvasColour(0.5, 0.5, 20);
  await page.click('#next-frame');
  await page.waitForFunction(() => document.body.dataset.frame === '1');
  await page.click('#next-frame');
  await page.waitForFunction(() => document.body.dataset.frame === '2');
  await settle();
  const dry = await canvasColour(0.5, 0.5, 20);
  check(distance(wet, dry) > 0.005, `the surface dries between frames 0 and 2 (${distance(wet, dry).toFixed(3)})`);
  const frameLabel = await page.textContent('#frame-label');
  check(/day 2/.test(frameLabel), `frame time in days: "${frameLabel}"`);
  await shot('desiccation.png');
  await golden('desiccation_moisture.png');
  check(/moisture.*%/.test(await legendTitle()), `moisture legend with its unit: "${await legendTitle()}"`);
  // Shrinkage: the local area lost against the rest shape, 0 at frame 0 and growing as the arm dries.
  const colourBy = async (mode) => {
    await page.selectOption('#colour-mode', mode);
    await page.waitForFunction((m) => document.body.dataset.colour === m, mode);
    await settle();
  };
  await colourBy('shrinkage');
  const shrinkHigh = Number(await page.textContent('#range-hi'));
  check(/shrinkage.*% of the rest area/.test(await legendTitle()) && shrinkHigh > 0,
        `shrinkage legend: "${await legendTitle()}", up to ${shrinkHigh} %`);
  const shrunk = await canvasColour(0.5, 0.5, 20);
  await page.click('#prev-frame');
  await page.click('#prev-frame');
  await page.waitForFunction(() => document.body.dataset.frame === '0');
  await settle();
  const unshrunk = await canvasColour(0.5, 0.5, 20);
  check(distance(shrunk, unshrunk) > 0.01, `shrinkage shows between frames 0 and 2 (${distance(shrunk, unshrunk).toFixed(3)})`);
  await page.click('#next-frame');
  await page.click('#next-frame');
  await page.waitForFunction(() => document.body.dataset.frame === '2');
  await golden('desiccation_shrinkage.png');
  await shot('desiccation_shrinkage.png');
  // The skin series in its own colour.
  await page.selectOption('#surface', 'skin');
  await page.waitForFunction(() => document.body.dataset.surface === 'skin');
  await colourBy('colour');
  const skinColour = await canvasColour(0.5, 0.5, 20);
  check(distance(skinColour, shrunk) > 0.02, `the skin in its colour differs from the shrinkage map (${distance(skinColour, shrunk).toFixed(3)})`);
  await golden('desiccation_skin.png');
  await page.selectOption('#surface', 'volume');
  await page.waitForFunction(() => document.body.dataset.surface === 'volume');
  await colourBy('moisture');
  await page.click('#cut-on');
  await page.locator('#cut-at').fill('300');
  await settle();
  const cutOpen = await canvasColour(0.5, 0.5, 20);
  check(distance(cutOpen, dry) > 0.005, `the cutting plane changes the view (${distance(cutOpen, dry).toFixed(3)})`);

  }
  if (want('surface')) {
  // 5. A surface run with an uncertainty field: coloured by it, with the unit in the legend.
  await open('#/run?path=surface-run');
  check(await page.evaluate(() => document.body.dataset.colour) === 'uncertainty', 'uncertainty shown first');
  check(/uncertainty, mm/.test(await legendTitle()) && Number(await page.textContent('#range-hi')) > 3.9,
        `uncertainty legend: "${await legendTitle()}" to ${await page.textContent('#range-hi')}`);
  await page.click('button[data-preset="front"]');
  await settle();
  const certain = await canvasColour();
  await page.click('button[data-preset="back"]');
  await settle();
  const uncertain = await canvasColour();
  check(uncertain[0] > certain[0] + 0.2, `front (1 mm) and back (4 mm) in different colours (${certain.map((c) => c.toFixed(2))}` +
        ` / ${uncertain.map((c) => c.toFixed(2))})`);
  await page.click('button[data-preset="oblique"]');
  await settle();
  await golden('surface_uncertainty.png');
  await shot('surface_uncertainty.png');
  const download = page.waitForEvent('download');
  await page.click('#screenshot');
  check((await download).suggestedFilename().endsWith('.png'), 'the screenshot button saves a PNG');

  // A run with only a GLB (here the server's built-in cylinder) shows it as written.
  const glb = Buffer.from(await (await fetch(base + 'api/meshes/cylinder.glb')).arrayBuffer());
  mkdirSync(join(served, 'glb-run'));
  writeFileSync(join(served, 'glb-run', 'mesh.glb'), glb);
  writeFileSync(join(served, 'glb-run', 'run.json'), JSON.stringify({ command: 'convert', outputs: ['mesh.glb'] }));
  await open('#/run?path=glb-run');
  await page.click('button[data-preset="front"]');
  await settle();
  const background = await canvasColour(0.02, 0.02, 3), glbCentre = await canvasColour();
  check(distance(background, glbCentre) > 0.1, `a GLB-only run shows its mesh (${distance(background, glbCentre).toFixed(3)})`);

  }
  if (!only) {
  // 6. The desiccation start form and the editor's default mesh load without errors.
  await open('#/desiccation');
  await open('#/wound', 180000);
  }

  // 7. The skull editor on the built-in skull with detected landmarks and the full template.
  if (want('skull')) await skullEditor({ page, base, open, golden, shot, canvasColour, distance, settle });

  // 8. Measured, not asserted: the frame rate while the time slider of a large map set moves every frame.
  if (bigRun) {
    const madeAfter = await bigRun;
    console.log(`${fpsResolution}^2 wound run ready ${(madeAfter / 1000).toFixed(0)} s after the start`);
    await open('#/run?path=wound-big', 300000);
    // requestAnimationFrame callbacks over `seconds`, the slider moved (an input event) in each when `scrub`.
    const frameRate = (scrub, seconds) => page.evaluate(([scrubbing, ms]) => new Promise((done) => {
      const slider = document.getElementById('time-slider');
      let frames = 0, start = 0, drawn = 0;
      const step = (now) => {
        if (!start) {
          start = now;
          drawn = window.forensim.stage.drawn;
        }
        if (scrubbing) {
          slider.value = String(Math.round(1000 * (((now - start) / ms) % 1)));
          slider.dispatchEvent(new Event('input'));
        }
        if (now - start < ms) {
          ++frames;
          requestAnimationFrame(step);
        } else {
          const { stage } = window.forensim;
          done({ frames, drawn: stage.drawn - drawn, seconds: (now - start) / 1000, width: stage.canvas.width, height: stage.canvas.height,
                 renderer: stage.webgl.name, antialias: stage.antialias });
        }
      };
      requestAnimationFrame(step);
    }), [scrub, 1000 * seconds]);
    const still = await frameRate(false, 2);
    const fps = await frameRate(true, 3);
    console.log(`measured: ${(fps.frames / fps.seconds).toFixed(1)} frames/s while scrubbing ${fpsResolution}^2 ` +
                `maps (${fps.frames} frames in ${fps.seconds.toFixed(1)} s, ${fps.drawn} of them drawn; ` +
                `${(still.frames / still.seconds).toFixed(1)} animation frames/s with the slider still, ` +
                `${still.drawn} drawn (the page draws on change); canvas ${fps.width}x${fps.height}, ` +
                `${fps.antialias ? '' : 'no '}multisampling, headless chromium: ${fps.renderer || 'unknown renderer'})`);
  }
  check(consoleErrors.length === 0, `no console errors${consoleErrors.length ? ': ' + consoleErrors.join(' | ') : ''}`);
  writeFileSync(join(served, 'browser_test_done'), 'ok');
} catch (e) {
  failures.push(String(e.stack || e));
  console.log(`FAIL ${e.stack || e}`);
} finally {
  if (browser) await browser.close();
  if (server) server.kill('SIGTERM');
  if (failures.length === 0) rmSync(served, { recursive: true, force: true });
}
console.log(`${failures.length ? `${failures.length} failure(s)` : 'all browser checks passed'} in ` +
            `${((Date.now() - started) / 1000).toFixed(0)} s`);
process.exit(failures.length ? 1 : 0);
