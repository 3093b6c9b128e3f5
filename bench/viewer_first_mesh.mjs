// Time to the first drawn mesh in the browser viewer on loopback: headless
// Chromium (as tests/browser) opens /viewer/?mesh=ID from a meshwave-server
// serving MESH with the real WebAssembly decoder; the address names the
// mesh, so the page streams it on opening. The page's own readout gives two
// times to the frame after the first decoded mesh went to three.js: from
// navigation (performance.now(): the page, its modules, the decoder module,
// the WebSocket, the packets, the decode, the geometry upload and one
// SwiftShader frame) and from the stream's start.
//   warm: a fresh page in one browser profile, after one first visit of 3 s
//     (the files from the HTTP cache, revalidated; compiled code from the
//     caches that visit filled);
//   cold: a fresh browser profile each run (nothing cached).
// A textured mesh gets a second table from the same runs: the time to the
// first frame drawn with a texture level applied (the page's readout of the
// frame after it, as the first mesh's). The page's defaults hold: once the
// budget's stream is done, a view refine to 1 px follows, which may bring a
// level the budget did not; the table says which level the budget's own
// selection holds (the CLI's decode of GET /stream at that budget, the same
// selection as the page's start).
//
// node viewer_first_mesh.mjs SERVER CLI DECODER_JS MESH NODE_MODULES RUNS BUDGETS...
import { execFileSync } from 'node:child_process';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { Server, ingest, launchChromium, tempDir, viewerDir } from '../tests/browser/harness.mjs';
import { readFileSync, rmSync, writeFileSync } from 'node:fs';

const [serverBin, cli, decoder, mesh, modules, runsText, ...budgets] = process.argv.slice(2);
const runs = Number(runsText);
if (readFileSync(decoder, 'utf8').includes('isFakeTestOnly')) {
  console.error('viewer_first_mesh: that is the test-only fake decoder; give the real module');
  process.exit(2);
}
const root = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '..');
const work = tempDir('meshwave-viewer-bench-');
const catalog = path.join(work, 'catalog');
const id = ingest(serverBin, catalog, mesh);
const server = await Server.start(serverBin, catalog,
  viewerDir(path.join(root, 'web/viewer'), decoder, path.join(work, 'viewer')), work);
const median = (xs) => [...xs].sort((a, b) => a - b)[Math.floor(xs.length / 2)];

// The base colour level a budget's stream holds ("W x H"), or null: the
// CLI's decode of what GET /stream selects for it, which a start with that
// budget selects too.
async function textureLevelAt(budget) {
  const reply = await fetch(`${server.url}/v1/meshes/${id}/stream?order=quality` +
                            (budget === 'all' ? '' : `&budget=${Math.round(Number(budget) * 1024)}`));
  if (!reply.ok) throw new Error(`GET /stream: HTTP ${reply.status}: ${await reply.text()}`);
  const file = path.join(work, 'budget.mwv');
  writeFileSync(file, Buffer.from(await reply.arrayBuffer()));
  const out = execFileSync(cli, ['decode', file, path.join(work, 'budget.glb')], { encoding: 'utf8' });
  return out.match(/textured: base colour (\d+ x \d+)/)?.[1] ?? null;
}
let hasTexture = false;
const TEXTURE_WAIT_MS = 15000;
const textured = {};  // budget -> its base colour level, or null

// One page load; the page's readouts once its stream is done.
// linger: milliseconds the page stays open after its stream (a visit's
// length, in which the browser caches what it compiled).
async function load(context, budget, linger = 0) {
    const page = await context.newPage();
  try {
    await page.goto(`${server.url}/viewer/?mesh=${id}&order=quality&rate=0&budget=` +
                    (budget === 'all' ? '' : budget));
    await page.waitForSelector('body[data-state="done"], body[data-state="error"]');
    await page.waitForTimeout(linger);
    await page.waitForFunction(() => document.getElementById('r-first').dataset.value ||
                                     document.body.dataset.state === 'error');
    // A textured frame, unless none comes (no level within the budget
    // and none brought by the view refine): TEXTURE_WAIT_MS after the rest.
    if (hasTexture) {
      await page.waitForFunction(() => document.getElementById('r-first-texture').dataset.value ||
                                       document.body.dataset.state === 'error',
      null, { timeout: TEXTURE_WAIT_MS }).catch(() => {});
    }
    return await page.evaluate(() => {
      const first = document.getElementById('r-first').dataset;
      if (document.body.dataset.state === 'error') {
        throw new Error(document.getElementById('error').textContent);
      }
      const texture = document.getElementById('r-first-texture').dataset;
      return {
        navigation: Number(first.fromNavigation), stream: Number(first.value),
        textureNavigation: Number(texture.fromNavigation), textureStream: Number(texture.value),
        bytes: Number(document.getElementById('r-bytes').dataset.value),
        packets: Number(document.getElementById('r-packets').textContent),
      };
    });
  } finally {
    await page.close();
  }
}

const texturedRows = [];
function row(cache, budget, results) {
  texturedRows.push(texturedRow(cache, budget, results));
  const nav = results.map((r) => r.navigation), stream = results.map((r) => r.stream);
  const { bytes, packets } = results.at(-1);
  console.log(`| ${cache} | ${budget === 'all' ? 'whole stream' : budget + ' KiB'} | ` +
              `${median(nav).toFixed(1)} ms | ${Math.min(...nav).toFixed(1)} | ` +
              `${Math.max(...nav).toFixed(1)} | ${median(stream).toFixed(1)} ms | ${bytes} | ${packets} |`);
}

// The same runs' first textured frame, beside their first mesh.
function texturedRow(cache, budget, results) {
  const label = budget === 'all' ? 'whole stream' : budget + ' KiB';
  const nav = results.map((r) => r.navigation);
  const drawn = results.filter((r) => Number.isFinite(r.textureNavigation));
  const inBudget = textured[budget] ?? 'none';
  if (drawn.length < results.length) {
    return `| ${cache} | ${label} | ${median(nav).toFixed(1)} ms | none drawn in ${results.length - drawn.length} ` +
           `of ${results.length} runs | | | | ${inBudget} |`;
  }
  const tex = drawn.map((r) => r.textureNavigation), stream = drawn.map((r) => r.textureStream);
  return `| ${cache} | ${label} | ${median(nav).toFixed(1)} ms | ${median(tex).toFixed(1)} ms | ` +
         `${Math.min(...tex).toFixed(1)} | ${Math.max(...tex).toFixed(1)} | ${median(stream).toFixed(1)} ms | ` +
         `${inBudget} |`;
}

try {
  hasTexture = (await textureLevelAt('all')) !== null;
  for (const budget of budgets) textured[budget] = hasTexture ? await textureLevelAt(budget) : null;
  console.log(`mesh ${path.basename(mesh)} (${id}), ${runs} runs each, loopback, unpaced`);
  console.log('| cache | budget | first mesh from navigation (median) | min | max | ' +
              'from the stream\'s start (median) | bytes | packets |');
  console.log('|---|---|---|---|---|---|---|---|');
  for (const budget of budgets) {
    const warm = await launchChromium(modules);
    try {
      await load(warm.context, budget, 3000);  // a first visit of 3 s fills the caches
      const results = [];
      for (let i = 0; i < runs; ++i) results.push(await load(warm.context, budget));
      row('warm', budget, results);
    } finally {
      await warm.close();
    }
    const results = [];
    for (let i = 0; i < runs; ++i) {
      const cold = await launchChromium(modules);
      try {
        results.push(await load(cold.context, budget));
      } finally {
        await cold.close();
      }
    }
    row('cold', budget, results);
  }
  if (hasTexture) {
    console.log('');
    console.log('first textured frame (a base colour level drawn), the same runs:');
    console.log('| cache | budget | first mesh from navigation (median) | first textured frame from navigation ' +
                '(median) | min | max | from the stream\'s start (median) | base colour level within the budget |');
    console.log('|---|---|---|---|---|---|---|---|');
    for (const r of texturedRows) console.log(r);
  }
} finally {
  await server.stop();
  rmSync(work, { recursive: true, force: true });
}
