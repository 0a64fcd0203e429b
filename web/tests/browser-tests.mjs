// obscura's web page in a real browser (issue 60), run by scripts/web-tests.sh:
//   node browser-tests.mjs --site DIR --cli OBSCURA --corpus DIR --out DIR
// Serves DIR on 127.0.0.1, drives the system's Chromium (WebGPU on SwiftShader) and checks:
// - the AO the page reads back equals `obscura render` (native, lavapipe) of the same view and
//   settings: MAE at most 2e-3 per row and scene, compared by `obscura diff` on EXRs;
// - which rows run within WebGPU's default limits (recorded, with each failure's message);
// - the error paths: no WebGPU, a broken glTF, a row the device cannot run: one clear message;
// - a screenshot of the split-screen page (OUT/page.png), and the time to the first AO.
// Everything measured goes to OUT/results.json.
import { chromium } from 'playwright-core';
import { execFileSync } from 'node:child_process';
import fs from 'node:fs';
import http from 'node:http';
import path from 'node:path';
import { tableScene } from './scene.mjs';

const args = Object.fromEntries(process.argv.slice(2).reduce((pairs, a, i, all) => (a.startsWith('--') ? [...pairs, [a.slice(2), all[i + 1]]] : pairs), []));
for (const key of ['site', 'cli', 'corpus', 'out']) {
  if (!args[key]) throw new Error(`browser-tests: --${key} is required`);
}
const MAE_BOUND = 2e-3;
const COMPARED_ROWS = ['vao', 'gtao', 'hbao+', 'sd-vao', 'rt-vao'];
const COMPARE_SIZE = [320, 180];
const results = { comparisons: [], rows: {}, errors: {} };
const failures = [];
const started = Date.now();
const step = (name) => { (results.stepSeconds ||= {})[name] = (Date.now() - started) / 1000; };
const check = (ok, message) => { if (!ok) { failures.push(message); console.error(`FAIL: ${message}`); } };

// ---- a static server: the built folder as any host would serve it ----
const types = { '.html': 'text/html', '.js': 'text/javascript', '.css': 'text/css', '.wasm': 'application/wasm', '.json': 'application/json', '.ts': 'text/plain' };
const server = http.createServer((req, res) => {
  const url = new URL(req.url, 'http://127.0.0.1');
  const file = path.join(args.site, path.normalize(decodeURIComponent(url.pathname)).replace(/^(\.\.[/\\])+/, ''), url.pathname.endsWith('/') ? 'index.html' : '');
  fs.readFile(file, (err, data) => {
    if (err) { res.writeHead(404); res.end('not found'); return; }
    res.writeHead(200, { 'content-type': types[path.extname(file)] || 'application/octet-stream' });
    res.end(data);
  });
});
await new Promise((resolve) => server.listen(0, '127.0.0.1', resolve));
const base = `http://127.0.0.1:${server.address().port}/`;

const browser = await chromium.launch({
  executablePath: process.env.CHROMIUM || '/usr/bin/chromium',
  headless: true,
  // WebGPU on the CPU (SwiftShader), and no background traffic on a closed network.
  args: ['--enable-unsafe-webgpu', '--enable-unsafe-swiftshader', '--no-sandbox', '--disable-gpu-sandbox',
    '--no-first-run', '--disable-background-networking', '--disable-component-update', '--disable-sync'],
});
const context = await browser.newContext({ viewport: { width: 1100, height: 1000 } });

async function open(query, ctx = context) {
  const page = await ctx.newPage();
  page.on('console', (m) => { if (m.type() === 'error') console.error(`page console: ${m.text()}`); });
  await page.goto(`${base}?${query}`);
  await page.waitForFunction(() => window.obscuraPage?.ready, null, { timeout: 180_000 });
  return page;
}
const pageErrors = (page) => page.evaluate(() => window.obscuraPage.errors.slice());
// One frame from the page's viewer, its AO as EXR bytes (the library's encoder).
async function renderExr(page, request) {
  const bytes = await page.evaluate(async (req) => {
    const frame = await window.obscuraPage.state.viewer.render(JSON.stringify(req));
    return Array.from(frame.exr());
  }, request);
  return Buffer.from(bytes);
}
async function tryRow(page, technique) {
  return page.evaluate(async (req) => {
    try { await window.obscuraPage.state.viewer.render(JSON.stringify(req)); return null; } catch (e) { return e.message || String(e); }
  }, { technique, width: 96, height: 54 });
}
const cli = (...a) => execFileSync(args.cli, a, { encoding: 'utf8', stdio: ['ignore', 'pipe', 'pipe'] });

try {
  // 1. The first AO: stairs, one row, 640x360, from navigation to the image drawn.
  const page = await open('scene=stairs&left=vao&split=0');
  check((await pageErrors(page)).length === 0, `the page showed errors: ${await pageErrors(page)}`);
  results.adapter = await page.evaluate(async () => {
    const info = (await navigator.gpu.requestAdapter()).info;
    return { ...window.obscuraPage.adapter, vendor: info.vendor, architecture: info.architecture, description: info.description };
  });
  results.firstAoMs = await page.evaluate(() => window.obscuraPage.state.firstAoMs);
  console.log(`adapter: ${JSON.stringify(results.adapter)}; first AO (stairs, vao, 640x360) after ${Math.round(results.firstAoMs)} ms`);
  check(results.firstAoMs > 0 && results.firstAoMs < 60_000, `first AO after ${results.firstAoMs} ms`);

  step('first AO');
  // 2. The page's AO against the CLI's, stairs and a generated glTF scene.
  const gltfPath = path.join(args.out, 'table.gltf');
  fs.writeFileSync(gltfPath, tableScene());
  for (const scene of ['stairs', 'table.gltf']) {
    if (scene === 'table.gltf') {
      // Through the page's own file input, as a user's file.
      await page.setInputFiles('#file', gltfPath);
      await page.waitForFunction(() => window.obscuraPage.state.scene?.name === 'table.gltf' && !window.obscuraPage.state.busy, null, { timeout: 120_000 });
    }
    for (const row of COMPARED_ROWS) {
      const [width, height] = COMPARE_SIZE;
      const stem = path.join(args.out, `${scene.replace('.gltf', '')}-${row}`);
      fs.writeFileSync(`${stem}.web.exr`, await renderExr(page, { technique: row, width, height }));
      cli('render', '--scene', scene === 'stairs' ? scene : gltfPath, '--technique', row, '--size', `${width}x${height}`, '--out', `${stem}.cli.exr`);
      const diff = cli('diff', `${stem}.cli.exr`, `${stem}.web.exr`);
      const max = Number(/max \|a-b\| ([^,\s]+)/.exec(diff)[1]);
      const mae = Number(/mean \|a-b\| ([^,\s]+)/.exec(diff)[1]);
      const differing = Number(/(\d+) of \d+ pixels differ/.exec(diff)[1]);
      results.comparisons.push({ scene, row, mae, max, differing, pixels: width * height });
      console.log(`${scene} ${row}: MAE ${mae.toExponential(2)}, max ${max.toExponential(2)}, ${differing} of ${width * height} pixels differ at all`);
      check(mae <= MAE_BOUND, `${scene} ${row}: MAE ${mae} over ${MAE_BOUND}`);
    }
  }

  step('comparisons');
  // 3. A broken glTF: one message, the library's, and the scene before stays.
  await page.setInputFiles('#file', path.join(args.corpus, 'glb-bad-json-length.glb'));
  await page.waitForFunction(() => window.obscuraPage.errors.length > 0, null, { timeout: 30_000 });
  results.errors.brokenGltf = (await pageErrors(page)).join('\n');
  check(/glb-bad-json-length\.glb.*not a usable glTF 2\.0 file/.test(results.errors.brokenGltf), `broken glTF message: ${results.errors.brokenGltf}`);
  check(await page.evaluate(() => window.obscuraPage.state.scene.name) === 'table.gltf', 'the scene before a broken file stays');
  await page.close();

  // 4. Every row within WebGPU's default limits (and, for one that fails there, with the
  // adapter's limits, to tell a limit from anything else).
  const limited = await open('scene=stairs&left=vao&split=0&limits=default');
  const full = await open('scene=stairs&left=vao&split=0');
  const rows = await limited.evaluate(() => window.obscuraPage.state.rows.map((r) => r.name));
  for (const row of rows) {
    const error = await tryRow(limited, row);
    results.rows[row] = { defaultLimits: error ?? 'ok' };
    if (error) results.rows[row].adapterLimits = (await tryRow(full, row)) ?? 'ok';
    console.log(`row ${row}: ${JSON.stringify(results.rows[row])}`);
  }
  await full.close();
  step('row sweep');
  const unsupported = rows.find((r) => results.rows[r].defaultLimits !== 'ok');
  check(rows.includes('vao') && results.rows.vao.defaultLimits === 'ok', 'vao runs within the default limits');

  // 5. A row the device cannot run, as a user picks it: one message naming it. Where a row
  // fails within the default limits, that row; where none does (SwiftShader runs them all), a
  // device that refuses the new row's compute pipelines (an invalid entry point: a real WebGPU
  // validation error) stands in for one that lacks what the row needs.
  const refusing = await browser.newContext();
  await refusing.addInitScript(() => {
    const create = GPUDevice.prototype.createComputePipeline;
    GPUDevice.prototype.createComputePipeline = function (desc) {
      const refused = window.refusePipelines ? { ...desc, compute: { ...desc.compute, entryPoint: 'refused_by_the_test' } } : desc;
      return create.call(this, refused);
    };
  });
  const picked = unsupported || 'rtao';
  const refused = await open('scene=stairs&left=vao&split=0&limits=default', refusing);
  check((await pageErrors(refused)).length === 0, `errors before the refused row: ${await pageErrors(refused)}`);
  await refused.evaluate((simulate) => { window.refusePipelines = simulate; }, !unsupported);
  await refused.selectOption('#rowA', picked);
  await refused.waitForFunction(() => window.obscuraPage.errors.length > 0 && !window.obscuraPage.state.busy, null, { timeout: 60_000 });
  results.errors.unsupportedRow = { row: picked, simulated: !unsupported, message: (await pageErrors(refused)).join('\n') };
  check((await pageErrors(refused)).length === 1 && results.errors.unsupportedRow.message.startsWith(`${picked}: technique '${picked}' cannot run on this WebGPU device`), `unsupported row message: ${results.errors.unsupportedRow.message}`);
  check(await refused.evaluate(() => document.getElementById('error').hidden === false), 'the error box is shown');
  await refusing.close();
  await limited.close();

  // 6. No WebGPU: the page says so, once.
  const bare = await browser.newContext();
  await bare.addInitScript(() => { Object.defineProperty(Navigator.prototype, 'gpu', { get: () => undefined }); });
  const noGpu = await open('scene=stairs', bare);
  results.errors.noWebgpu = (await pageErrors(noGpu)).join('\n');
  check(/no WebGPU/.test(results.errors.noWebgpu) && (await pageErrors(noGpu)).length === 1, `no-WebGPU message: ${results.errors.noWebgpu}`);
  await bare.close();

  step('error paths');
  // 7. The page as a user first sees it (split screen), kept for a look.
  const shown = await open('scene=stairs');
  await shown.waitForFunction(() => window.obscuraPage.state.frames[1] && !window.obscuraPage.state.busy, null, { timeout: 120_000 });
  check((await pageErrors(shown)).length === 0, `the split page showed errors: ${await pageErrors(shown)}`);
  await shown.screenshot({ path: path.join(args.out, 'page.png'), fullPage: true });
  // The controls and the image only (docs/web-page.png is one of these).
  await shown.screenshot({ path: path.join(args.out, 'page-top.png'), clip: { x: 0, y: 0, width: 1100, height: 600 } });
  step('screenshot');
} finally {
  fs.writeFileSync(path.join(args.out, 'results.json'), JSON.stringify(results, null, 2));
  await browser.close();
  server.close();
}
if (failures.length) {
  console.error(`browser-tests: ${failures.length} failed:\n${failures.join('\n')}`);
  process.exit(1);
}
console.log('browser-tests: all passed');
