// Measures (does not assert) the frame rate of the wound timeline while it is scrubbed, at a given map
// resolution (the figure is for 2048^2 maps): makes a wound run with `forensim wound`, serves it,
// opens it in headless chromium, moves the time slider every frame for a few seconds and prints the frames
// per second the page drew. Headless chromium draws with software WebGL (SwiftShader), so the figure is a
// floor; a browser on a GPU draws the same page far faster.
//   node tests/web/measure_scrub_fps.mjs --forensim build/release/bin/forensim --web web [--resolution 2048]

import { spawn, spawnSync } from 'node:child_process';
import { existsSync, mkdtempSync, rmSync } from 'node:fs';
import { createRequire } from 'node:module';
import { tmpdir } from 'node:os';
import { join, resolve } from 'node:path';

const args = Object.fromEntries(process.argv.slice(2).reduce((p, a, i, all) => {
  if (a.startsWith('--')) p.push([a.slice(2), all[i + 1]]);
  return p;
}, []));
const forensim = resolve(args.forensim || 'build/release/bin/forensim');
const web = resolve(args.web || 'web');
const resolution = args.resolution || '2048';
const chromiumPath = args.chromium || '/usr/bin/chromium';
if (!existsSync(chromiumPath)) { console.log('SKIP: no chromium'); process.exit(77); }
const { chromium } = createRequire(join(web, 'package.json'))('playwright-core');

const served = mkdtempSync(join(tmpdir(), 'forensim-fps-'));
const t0 = Date.now();
const made = spawnSync(forensim, ['wound', '--builtin', 'forearm-uv', '--resolution', resolution, '--times', '36h',
                                  '--picture-size', '0', '-o', join(served, 'w')], { encoding: 'utf8' });
if (made.status !== 0) throw new Error(made.stderr);
console.log(`wound run at ${resolution}^2 made in ${((Date.now() - t0) / 1000).toFixed(1)} s`);
const server = spawn(forensim, ['serve', '--port', '0', '--web', web, served], { stdio: ['ignore', 'pipe', 'inherit'] });
const base = await new Promise((ok) => server.stdout.on('data', (d) => {
  const m = /http:\/\/127\.0\.0\.1:(\d+)\//.exec(String(d));
  if (m) ok(`http://127.0.0.1:${m[1]}/`);
}));
const browser = await chromium.launch({
  executablePath: chromiumPath,
  args: ['--headless', '--no-sandbox', '--disable-gpu', '--disable-background-networking', '--disable-component-update',
         '--disable-sync', '--no-first-run', '--enable-unsafe-swiftshader', '--use-angle=swiftshader'],
});
try {
  const page = await browser.newPage({ viewport: { width: 1280, height: 720 } });
  await page.goto(base + '#/run?path=w');
  await page.waitForFunction(() => document.body.dataset.ready === '1', null, { timeout: 300000 });
  const fps = await page.evaluate(() => new Promise((done) => {
    const { timeline, timelineControl, stage } = window.forensim;
    const t1 = timeline.endTime, start = performance.now();
    let frames = 0;
    const step = (now) => {
      const x = (now - start) / 5000;
      timelineControl.setTime(t1 * x * x);  // sweeps every key position
      ++frames;
      if (now - start < 5000) requestAnimationFrame(step);
      else done({ frames, seconds: (now - start) / 1000, stageFps: stage.fps() });
    };
    requestAnimationFrame(step);
  }));
  console.log(`measured: ${(fps.frames / fps.seconds).toFixed(1)} frames/s scrubbing ${resolution}^2 maps ` +
              `(${fps.frames} frames in ${fps.seconds.toFixed(1)} s, 1280x720, software WebGL)`);
} finally {
  await browser.close();
  server.kill('SIGTERM');
  rmSync(served, { recursive: true, force: true });
}
