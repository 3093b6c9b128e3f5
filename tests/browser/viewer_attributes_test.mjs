// The viewer in colour and texture, in headless Chromium against the real
// server and WebAssembly decoder (run_viewer_test.sh starts it):
//  1. The coloured sample (--mesh, a PLY with vertex colours) streamed at a
//     budget: the mesh is drawn in colour — chromatic pixels where the grey
//     render (the "colours and texture" box off) has none.
//  2. The textured sample (--textured, an OBJ + MTL + PNG) streamed at a
//     budget: the texture readout names the level held, the screenshot
//     differs from the grey render; refined to the whole stream, the finest
//     level arrives and the picture changes.
//  3. A budget that holds the header only: the base mesh is drawn.
// No console error in any.
//
// Usage: node viewer_attributes_test.mjs --server BIN --cli BIN --decoder meshwave_decoder.js
//   --viewer web/viewer --mesh data/textured/hue_ball.ply --textured data/textured/die.obj
//   --node-modules DIR --artefacts DIR
import assert from 'node:assert/strict';
import { existsSync, mkdirSync, readFileSync, rmSync } from 'node:fs';
import path from 'node:path';
import { parseArgs } from 'node:util';
import {
  Server, checks, comparePictures, ingest, launchChromium, openQualityViewer, skip, tempDir, viewerDir,
  waitStreamDone,
} from './harness.mjs';

const { values: opt } = parseArgs({ options: {
  server: { type: 'string' }, cli: { type: 'string' }, decoder: { type: 'string' },
  viewer: { type: 'string' }, mesh: { type: 'string' }, textured: { type: 'string' },
  'node-modules': { type: 'string' }, artefacts: { type: 'string' },
} });
for (const k of ['server', 'viewer', 'mesh', 'textured', 'node-modules', 'artefacts']) {
  if (!opt[k]) { console.error(`viewer_attributes_test: --${k} is required`); process.exit(2); }
}
if (!opt.decoder || !existsSync(opt.decoder)) {
  skip(`the WebAssembly decoder module is not built (${opt.decoder || 'no path given'})`);
}
if (readFileSync(opt.decoder, 'utf8').includes('isFakeTestOnly')) {
  skip('the test-only fake decoder has no colours or textures');
}

mkdirSync(opt.artefacts, { recursive: true });
const work = tempDir('meshwave-viewer-attributes-');
const catalog = path.join(work, 'catalog');
const coloured = ingest(opt.server, catalog, opt.mesh);
const textured = ingest(opt.server, catalog, opt.textured);
const server = await Server.start(opt.server, catalog,
  viewerDir(opt.viewer, opt.decoder, path.join(work, 'viewer')), work);
const browser = await launchChromium(opt['node-modules']);

const openViewer = (meshId, budgetKiB, errors) =>
  openQualityViewer(browser, server.url, meshId, budgetKiB, errors);
const waitDone = waitStreamDone;

async function shot(page, name) {
  await page.evaluate(() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r))));
  const file = path.join(opt.artefacts, name);
  await page.locator('#view').screenshot({ path: file });
  return readFileSync(file);
}

// Of two screenshots: pixels drawn, chromatic ones and those that differ.
const measure = (a, b) => comparePictures(browser, a, b);

// The attributes shown, then the grey render of the same mesh.
async function withAndWithout(page, name) {
  const shown = await shot(page, `${name}.png`);
  await page.uncheck('#attributes');
  const grey = await shot(page, `${name}_grey.png`);
  await page.check('#attributes');
  return { shown, grey };
}

const { test, failed } = checks();
try {
  await test('vertex colours on screen', async () => {
    const errors = [];
    const page = await openViewer(coloured, 4, errors);
    await page.click('#stream');
    await waitDone(page);
    const { shown, grey } = await withAndWithout(page, 'viewer_colours_4KiB');
    const m = await measure(shown, grey);
    console.log(`  ${m.drawn} pixels drawn, ${m.chromaticA} chromatic in colour, ` +
                `${m.chromaticB} in grey`);
    assert.ok(m.drawn > 0.02 * 960 * 640, 'the mesh is drawn');
    assert.equal(m.chromaticB, 0, 'the grey render has no colour');
    assert.ok(m.chromaticA > 0.3 * m.drawn, 'most of the mesh is in colour');
    assert.deepEqual(errors, [], 'console errors');
    await page.close();
  });

  await test('a budget below the first packet shows the base mesh', async () => {
    const errors = [];
    // The header's size, as the server states it when refusing a smaller budget.
    const refusal = await (await fetch(
      `${server.url}/v1/meshes/${textured}/stream?order=quality&budget=1`)).text();
    const header = refusal.match(/\((\d+) bytes\)/);
    assert.ok(header, `the server's refusal names the header's size: ${refusal}`);
    const page = await openViewer(textured, parseInt(header[1], 10) / 1024, errors);
    await page.click('#stream');
    await waitDone(page);
    const packets = await page.evaluate(() => document.getElementById('r-packets').textContent);
    const png = await shot(page, 'viewer_texture_header_only.png');
    const m = await measure(png, png);
    console.log(`  ${packets} packets, ${m.drawn} pixels drawn`);
    assert.equal(packets, '0', 'the budget holds the header only');
    assert.ok(m.drawn > 0.02 * 960 * 640, 'the base mesh is drawn');
    assert.deepEqual(errors, [], 'console errors');
    await page.close();
  });

  await test('the texture on screen, then refined', async () => {
    const errors = [];
    const page = await openViewer(textured, 6, errors);
    await page.click('#stream');
    await waitDone(page);
    await page.waitForFunction(() => document.getElementById('r-texture').dataset.value !== '');
    const first = await page.evaluate(() => document.getElementById('r-texture').textContent);
    const { shown, grey } = await withAndWithout(page, 'viewer_texture_6KiB');
    const m = await measure(shown, grey);
    console.log(`  texture ${first}; ${m.drawn} pixels drawn, ${m.chromaticA} chromatic, ` +
                `${m.differ} differ from the grey render`);
    assert.ok(m.drawn > 0.02 * 960 * 640, 'the mesh is drawn');
    assert.ok(m.differ > 0.3 * m.drawn, 'the textured render differs from the grey one');
    assert.ok(m.chromaticA > m.chromaticB + 0.1 * m.drawn, 'the texture brings colour');

    // The rest of the stream: the finest texture level arrives.
    await page.fill('#refine-kib', '100000');
    await page.click('#refine');
    await waitDone(page);
    await page.waitForFunction(() => /level (\d+) of \1\)/.test(document.getElementById('r-texture').textContent));
    const last = await page.evaluate(() => document.getElementById('r-texture').textContent);
    const refined = await shot(page, 'viewer_texture_complete.png');
    const r = await measure(shown, refined);
    console.log(`  refined: texture ${last}; ${r.differ} pixels changed`);
    assert.notEqual(last, first, 'a finer texture level arrived');
    assert.ok(r.differ > 0.01 * m.drawn, 'the refined picture changed');
    assert.deepEqual(errors, [], 'console errors');
    await page.close();
  });
} finally {
  await browser.close();
  await server.stop();
  rmSync(work, { recursive: true, force: true });
}
console.log(`screenshots in ${opt.artefacts}`);
if (failed()) process.exit(1);
console.log('viewer_attributes_test: all passed');
