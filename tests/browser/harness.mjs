// What the browser test and bench/viewer_first_mesh.sh share: a catalog
// ingested from a shipped sample, a meshwave-server on 127.0.0.1 serving
// it with a given viewer directory, and Debian's Chromium driven by
// playwright-core (pinned by web/package-lock.json) with the flags this
// machine's closed network needs.
import assert from 'node:assert/strict';
import { execFileSync, spawn } from 'node:child_process';
import { cpSync, existsSync, mkdtempSync, readFileSync, rmSync } from 'node:fs';
import { createRequire } from 'node:module';
import { tmpdir } from 'node:os';
import path from 'node:path';
import { setTimeout as sleep } from 'node:timers/promises';
import { pathToFileURL } from 'node:url';
import { parseArgs } from 'node:util';

export const CHROMIUM = '/usr/bin/chromium';
export const SKIP = 77;  // ctest's SKIP_RETURN_CODE for these tests

export function skip(message) {
  console.log(`SKIP: ${message}`);
  process.exit(SKIP);
}

// The options every browser test against the real decoder takes (--server,
// --cli, --decoder, --viewer, --mesh, --node-modules, --artefacts): exits 2
// on a missing one, skips without the decoder module or with the test-only
// fake (`why` says what the test needs it for).
export function realDecoderTestOptions(test, why) {
  const { values: opt } = parseArgs({ options: {
    server: { type: 'string' }, cli: { type: 'string' }, decoder: { type: 'string' },
    viewer: { type: 'string' }, mesh: { type: 'string' }, 'node-modules': { type: 'string' },
    artefacts: { type: 'string' },
  } });
  for (const k of ['server', 'viewer', 'mesh', 'node-modules', 'artefacts']) {
    if (!opt[k]) { console.error(`${test}: --${k} is required`); process.exit(2); }
  }
  if (!opt.decoder || !existsSync(opt.decoder)) {
    skip(`the WebAssembly decoder module is not built (${opt.decoder || 'no path given'}): ` +
         'configure with -DMESHWAVE_DECODER_JS=PATH/meshwave_decoder.js');
  }
  if (readFileSync(opt.decoder, 'utf8').includes('isFakeTestOnly')) {
    skip(`the test-only fake decoder ${why}: this test needs the real module`);
  }
  return opt;
}

// Named checks, one line each ("ok: NAME" or "FAIL: NAME: why"); a failure
// does not stop the ones after it, and `failed()` tells the exit code.
export function checks() {
  let anyFailed = false;
  return {
    async test(name, body) {
      try {
        await body();
        console.log(`ok: ${name}`);
      } catch (e) {
        anyFailed = true;
        console.log(`FAIL: ${name}: ${e.stack || e}`);
      }
    },
    failed: () => anyFailed,
  };
}

// Packet messages ({id, part}: part null for a whole packet) of one
// session: throws when a unit arrives twice, a part of a packet that came
// whole, or a packet after a part of it.
export function checkEachUnitOnce(packets) {
  const whole = new Set(), part = new Set();
  for (const p of packets) {
    const key = `${p.id}.${p.part}`;
    if (part.has(key) || whole.has(p.id)) throw new Error(`unit ${key} arrived twice (or after its packet)`);
    if (p.part === null) {
      if ([...part].some((k) => k.startsWith(`${p.id}.`))) throw new Error(`packet ${p.id} after a part of it`);
      whole.add(p.id);
    } else {
      part.add(key);
    }
  }
}

export function tempDir(prefix) { return mkdtempSync(path.join(tmpdir(), prefix)); }

// `meshwave-server ingest` of one mesh file (more ingest options in
// `options`); its catalog id.
export function ingest(serverBinary, catalog, meshFile, options = []) {
  const out = execFileSync(serverBinary, ['ingest', '--catalog', catalog, ...options, meshFile],
    { encoding: 'utf8' });
  // The id opens the line naming the file (a log line, e.g. a fidelity
  // warning, may come first).
  const found = out.match(/^([0-9a-f]{12}) /m);
  if (!found) throw new Error(`ingest printed no id: ${out}`);
  return found[1];
}

// web/viewer with `decoderModule` as its meshwave_decoder.js (and the
// .wasm beside it, which the test-only fake has not), in `dir`.
export function viewerDir(sourceViewer, decoderModule, dir) {
  cpSync(sourceViewer, dir, { recursive: true });
  cpSync(decoderModule, path.join(dir, 'meshwave_decoder.js'));
  const wasm = decoderModule.replace(/\.js$/, '.wasm');
  if (existsSync(wasm)) cpSync(wasm, path.join(dir, 'meshwave_decoder.wasm'));
  return dir;
}

// The decoder module under Node: its wasm read from beside it (the
// module's loader fetches it only in a browser).
export async function loadDecoderModule(modulePath) {
  const { default: createMeshwave } = await import(pathToFileURL(path.resolve(modulePath)).href);
  const wasm = path.resolve(modulePath).replace(/\.js$/, '.wasm');
  return createMeshwave(existsSync(wasm) ? { wasmBinary: readFileSync(wasm) } : {});
}

export class Server {
  // Starts `serverBinary` on 127.0.0.1 with a free port.
  static async start(serverBinary, catalog, viewer, work) {
    const portFile = path.join(work, 'port');
    rmSync(portFile, { force: true });
    const child = spawn(serverBinary, ['--catalog', catalog, '--listen', '127.0.0.1:0',
      '--port-file', portFile, '--viewer-dir', viewer, '--log-level', 'warn'],
    { stdio: ['ignore', 'inherit', 'inherit'] });
    let exited = false;
    child.on('exit', () => { exited = true; });
    for (let i = 0; i < 200 && !exited; ++i) {
      if (existsSync(portFile)) {
        const port = parseInt(readFileSync(portFile, 'utf8'), 10);
        if (port > 0) return new Server(child, `http://127.0.0.1:${port}`);
      }
      await sleep(50);
    }
    child.kill('SIGKILL');
    throw new Error('meshwave-server did not start');
  }

  constructor(child, url) { this.child = child; this.url = url; }

  async stop() {
    if (this.child.exitCode !== null) return;
    const exited = new Promise((resolve) => this.child.on('exit', resolve));
    this.child.kill('SIGTERM');
    await Promise.race([exited, sleep(15000)]);
    if (this.child.exitCode === null) this.child.kill('SIGKILL');
  }
}

// A Chromium context with a fresh profile (removed by close()).
export async function launchChromium(nodeModules) {
  if (!existsSync(CHROMIUM)) skip(`${CHROMIUM} not found: apt-get install chromium (deploy/install-deps.sh)`);
  const require = createRequire(path.join(nodeModules, 'noop.js'));
  const { chromium } = require('playwright-core');
  const profile = tempDir('meshwave-chromium-');
  const context = await chromium.launchPersistentContext(profile, {
    executablePath: CHROMIUM,
    headless: true,
    viewport: { width: 960, height: 640 },
    args: ['--headless', '--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run',
      '--disable-background-networking', '--disable-component-update', '--disable-sync',
      // WebGL without a GPU: ANGLE on SwiftShader, which newer Chromium
      // only offers when asked.
      '--use-angle=swiftshader', '--enable-unsafe-swiftshader'],
  });
  return {
    context,
    async close() {
      await context.close();
      rmSync(profile, { recursive: true, force: true });
    },
  };
}

// A viewer page on `meshId` set to stream `budgetKiB` in the quality order,
// unpaced, with no pixel tolerance (nothing but the budget and the refines
// asked for is streamed), its console errors and uncaught exceptions
// collected into `errors`. The Stream button is left to the caller.
export async function openQualityViewer(browser, serverUrl, meshId, budgetKiB, errors) {
  const page = await browser.context.newPage();
  page.on('console', (m) => { if (m.type() === 'error') errors.push(m.text()); });
  page.on('pageerror', (e) => errors.push(`uncaught: ${e.message}`));
  await page.goto(`${serverUrl}/viewer/`);
  await page.waitForSelector('body[data-state="ready"], body[data-state="error"]');
  await page.selectOption('#mesh', meshId);
  await page.selectOption('#order', 'quality');
  await page.fill('#budget', String(budgetKiB));
  await page.fill('#rate', '0');
  await page.fill('#screen-error', '');
  return page;
}

// Waits until the page's stream (or refine) is done, and fails on the error
// it shows if it ended in one.
export async function waitStreamDone(page) {
  await page.waitForSelector('body[data-state="done"], body[data-state="error"]');
  const error = await page.evaluate(() => {
    const e = document.getElementById('error');
    return e.hidden ? '' : e.textContent;
  });
  assert.equal(error, '', 'the viewer reported an error');
}

// Of two screenshots (PNG buffers of the same size), decoded by the
// browser's own image decoder: pixels drawn in each (not the white
// background: channels summing under 3 x 240), chromatic ones in each (max
// - min channel over 40: a grey render has none), warm ones in each (red
// over blue by more than 60: the error colours' yellow to red) and pixels
// that differ (channel differences summing over 24).
export async function comparePictures(browser, a, b) {
  const page = await browser.context.newPage();
  const result = await page.evaluate(async ([a64, b64]) => {
    const pixels = async (data) => {
      const img = new Image();
      img.src = `data:image/png;base64,${data}`;
      await img.decode();
      const c = new OffscreenCanvas(img.width, img.height);
      const g = c.getContext('2d');
      g.drawImage(img, 0, 0);
      return g.getImageData(0, 0, img.width, img.height).data;
    };
    const [pa, pb] = [await pixels(a64), await pixels(b64)];
    const r = { drawn: 0, drawnB: 0, chromaticA: 0, chromaticB: 0, warmA: 0, warmB: 0, differ: 0,
                total: pa.length / 4 };
    const spread = (p, i) => Math.max(p[i], p[i + 1], p[i + 2]) - Math.min(p[i], p[i + 1], p[i + 2]);
    for (let i = 0; i < pa.length; i += 4) {
      if (pa[i] + pa[i + 1] + pa[i + 2] < 3 * 240) ++r.drawn;
      if (pb[i] + pb[i + 1] + pb[i + 2] < 3 * 240) ++r.drawnB;
      if (spread(pa, i) > 40) ++r.chromaticA;
      if (spread(pb, i) > 40) ++r.chromaticB;
      if (pa[i] > pa[i + 2] + 60) ++r.warmA;
      if (pb[i] > pb[i + 2] + 60) ++r.warmB;
      const d = Math.abs(pa[i] - pb[i]) + Math.abs(pa[i + 1] - pb[i + 1]) + Math.abs(pa[i + 2] - pb[i + 2]);
      if (d > 24) ++r.differ;
    }
    return r;
  }, [a.toString('base64'), b.toString('base64')]);
  await page.close();
  return result;
}
