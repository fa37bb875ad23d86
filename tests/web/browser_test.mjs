// Browser tests of forensim serve's front end: starts `forensim serve` on a free loopback port over a
// scratch folder holding a small wound run and a small desiccation run (made by the forensim executable),
// drives Debian's chromium headless through playwright-core, and checks each view: the runs list, a wound
// run's timeline scrubbed (the wound's colour changes with time), the wound editor (a stroke painted by ray
// cast, the timeline generated on the server and scrubbed), and a desiccation run stepped frame by frame.
// No console errors or page errors are allowed. Measured and printed, not asserted: frames per second while
// scrubbing. Screenshots go to --shots DIR when given.
//
//   node tests/web/browser_test.mjs --forensim build/release/bin/forensim --web web [--shots DIR]
// Exit codes: 0 pass, 1 fail, 77 skipped (no chromium or no playwright-core).

import { spawn, spawnSync } from 'node:child_process';
import { existsSync, mkdtempSync, mkdirSync, rmSync, writeFileSync } from 'node:fs';
import { createRequire } from 'node:module';
import { tmpdir } from 'node:os';
import { join, resolve } from 'node:path';

const args = Object.fromEntries(process.argv.slice(2).reduce((pairs, a, i, all) => {
  if (a.startsWith('--')) pairs.push([a.slice(2), all[i + 1]]);
  return pairs;
}, []));
const forensim = resolve(args.forensim || 'build/release/bin/forensim');
const web = resolve(args.web || 'web');
const chromiumPath = args.chromium || '/usr/bin/chromium';
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

const served = mkdtempSync(join(tmpdir(), 'forensim-web-'));
let server, browser;
try {
  const t0 = Date.now();
  run(['wound', '--builtin', 'cylinder', '--resolution', '256', '--times', '36h', '--picture-size', '0',
       '-o', join(served, 'wound-run')]);
  run(['mummify', '--phantom', 'arm', '--size', 'small', '--days', '2', '--frames', '2', '--no-pictures',
       '-o', join(served, 'dry-run')]);
  console.log(`runs made in ${((Date.now() - t0) / 1000).toFixed(1)} s`);

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

  // 1. The runs list.
  await open('#/runs');
  const runs = await page.$$eval('#runs a', (as) => as.map((a) => a.dataset.run));
  check(runs.includes('wound-run') && runs.includes('dry-run'), `runs listed: ${runs.join(', ')}`);
  await shot('runs.png');

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
  // Scrubbing by the slider itself; frame rate measured while it moves.
  const fpsBefore = Date.now();
  for (let v = 0; v <= 1000; v += 100) {
    await page.locator('#time-slider').fill(String(v));
  }
  const scrubSeconds = (Date.now() - fpsBefore) / 1000;
  const fps = await page.evaluate(() => window.forensim.stage.fps());
  console.log(`measured: ${fps.toFixed(1)} frames/s while scrubbing (11 slider moves in ${scrubSeconds.toFixed(2)} s,` +
              ' software WebGL)');
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
  await page.click('#cut-on');
  await page.locator('#cut-at').fill('300');
  await settle();
  const cutOpen = await canvasColour(0.5, 0.5, 20);
  check(distance(cutOpen, dry) > 0.005, `the cutting plane changes the view (${distance(cutOpen, dry).toFixed(3)})`);

  // 5. The desiccation start form and the editor's default mesh load without errors.
  await open('#/desiccation');
  await open('#/wound', 180000);
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
console.log(failures.length ? `${failures.length} failure(s)` : 'all browser checks passed');
process.exit(failures.length ? 1 : 0);
