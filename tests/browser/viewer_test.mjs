// The browser viewer end to end: meshwave-server on 127.0.0.1 serving a
// catalog ingested from a shipped sample and the viewer with the real
// WebAssembly decoder, opened in headless Chromium.
//  1. A mesh streamed at a budget, then refined: the readouts (bytes,
//     packets, level, estimated PSNR) equal what the server's GET /stream
//     and `meshwave decode` of the same prefix say, the mesh is drawn, the
//     two screenshots differ where it refined, no console error.
//  2. A corrupt packet (a test proxy inside the browser flips payload bytes):
//     a readable error, the last good mesh still drawn, the page answering.
//  3. The socket closed by the server mid-stream: the same.
//  4. Error colours against the complete stream: a 6 KiB prefix shows them.
//  5. The whole stream ends in the input's own mesh (the original layer):
//     the viewer draws the input's vertex and face counts.
//  6. An address naming a mesh (/viewer/?mesh=ID&budget=…) streams it on
//     opening, without a click: the same readouts as 1.
//  7. A decoder module that cannot load (its wasm missing): the page says
//     so in words.
// Screenshots are kept in the artefacts directory.
//
// node viewer_test.mjs --server BIN --cli BIN --decoder meshwave_decoder.js
//   --viewer web/viewer --mesh data/elephant.off --node-modules DIR --artefacts DIR
// Exit 0 passed, 1 failed, 77 skipped (no Chromium, no decoder module) —
// and 77 after a run with the test-only fake decoder, which checks the
// page's wiring but can never pass.
import assert from 'node:assert/strict';
import { execFileSync } from 'node:child_process';
import { existsSync, mkdirSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import path from 'node:path';
import { parseArgs } from 'node:util';
import { Server, SKIP, ingest, launchChromium, skip, tempDir, viewerDir, checks, comparePictures } from './harness.mjs';
import { decodeServerMessage } from '../../web/viewer/ws_protocol.js';

const { values: opt } = parseArgs({ options: {
  server: { type: 'string' }, cli: { type: 'string' }, decoder: { type: 'string' },
  viewer: { type: 'string' }, mesh: { type: 'string' }, 'node-modules': { type: 'string' },
  artefacts: { type: 'string' },
} });
for (const k of ['server', 'cli', 'viewer', 'mesh', 'node-modules', 'artefacts']) {
  if (!opt[k]) { console.error(`viewer_test: --${k} is required`); process.exit(2); }
}
if (!opt.decoder || !existsSync(opt.decoder)) {
  skip(`the WebAssembly decoder module is not built (${opt.decoder || 'no path given'}): ` +
       'configure with -DMESHWAVE_DECODER_JS=PATH/meshwave_decoder.js');
}
const fake = readFileSync(opt.decoder, 'utf8').includes('isFakeTestOnly');
if (fake) console.log('WIRING ONLY: the test-only fake decoder; level and PSNR are not checked');

const BUDGET = 6 * 1024, REFINE_KIB = 8, ORDER = 'quality';
mkdirSync(opt.artefacts, { recursive: true });
const work = tempDir('meshwave-viewer-test-');
const catalog = path.join(work, 'catalog');
const id = ingest(opt.server, catalog, opt.mesh);
const server = await Server.start(opt.server, catalog,
  viewerDir(opt.viewer, opt.decoder, path.join(work, 'viewer')), work);
const browser = await launchChromium(opt['node-modules']);

// What the server and the CLI say about the prefix order[0 .. packets) that
// fits `budget` container bytes: the bytes the page receives for it,
// packets, level, estimated PSNR.
let wsHeaderLength = null;
async function serverNumbers(budget) {
  if (wsHeaderLength === null) {
    const header = await fetch(`${server.url}/v1/meshes/${id}/header`);
    wsHeaderLength = (await header.arrayBuffer()).byteLength;
  }
  const reply = await fetch(`${server.url}/v1/meshes/${id}/stream?order=${ORDER}&budget=${budget}`);
  assert.equal(reply.status, 200);
  const body = Buffer.from(await reply.arrayBuffer());
  const file = path.join(work, `prefix_${budget}.mwv`);
  writeFileSync(file, body);
  const out = execFileSync(opt.cli, ['decode', file, path.join(work, 'prefix.ply')], { encoding: 'utf8' });
  const level = out.match(/\(level (\d+) of (\d+)\)/);
  const psnr = out.match(/estimated PSNR ([0-9.]+) dB/);
  assert.ok(level && psnr, `unexpected meshwave decode output: ${out}`);
  // The page receives the header as GET /header serves it (`present`
  // empty) and the payloads: the container less its 8-byte preamble and
  // its header (which lists the packets present).
  const headerLength = body.readUInt32LE(4);
  const bytes = wsHeaderLength + body.length - 8 - headerLength;
  return { containerBytes: body.length, bytes, packets: Number(reply.headers.get('x-meshwave-packets')),
           nextCursor: Number(reply.headers.get('x-meshwave-next-cursor')),
           level: Number(level[1]), psnr: Number(psnr[1]) };
}

async function readouts(page) {
  return page.evaluate(() => ({
    bytes: Number(document.getElementById('r-bytes').dataset.value),
    packets: Number(document.getElementById('r-packets').textContent),
    level: Number(document.getElementById('r-level').dataset.value),
    psnr: Number(document.getElementById('r-psnr').dataset.value),
    error: document.getElementById('error').hidden ? '' : document.getElementById('error').textContent,
    state: document.body.dataset.state,
  }));
}

function checkReadouts(got, want, what) {
  assert.equal(got.bytes, want.bytes, `${what}: bytes received`);
  assert.equal(got.packets, want.packets, `${what}: packets`);
  if (fake) return;
  assert.equal(got.level, want.level, `${what}: level`);
  assert.ok(Math.abs(got.psnr - want.psnr) <= 0.006, `${what}: PSNR ${got.psnr} vs ${want.psnr}`);
}

async function shot(page, name) {
  // Two frames: whatever was scheduled is drawn.
  await page.evaluate(() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r))));
  const file = path.join(opt.artefacts, name);
  await page.locator('#view').screenshot({ path: file });
  return readFileSync(file);
}

// Pixels of two PNGs (same size) that differ, and pixels of each that are
// not background.
const comparePngs = (a, b) => comparePictures(browser, a, b);

async function openViewer(consoleErrors) {
  const page = await browser.context.newPage();
  page.on('console', (m) => { if (m.type() === 'error') consoleErrors.push(m.text()); });
  page.on('pageerror', (e) => consoleErrors.push(`uncaught: ${e.message}`));
  await page.goto(`${server.url}/viewer/`);
  await page.waitForSelector('body[data-state="ready"], body[data-state="error"]');
  const { error } = await readouts(page);
  assert.equal(error, '', 'the page loaded with an error');
  await page.selectOption('#mesh', id);
  await page.selectOption('#order', ORDER);
  await page.fill('#budget', String(BUDGET / 1024));
  await page.fill('#rate', '0');
  await page.fill('#refine-kib', String(REFINE_KIB));
  // No pixel tolerance: no view refine after the stream (the camera does
  // not move here), so the readouts are the budget's and the refines'
  // alone. The view refines are viewer_view_test.mjs's.
  await page.fill('#screen-error', '');
  return page;
}

async function streamAndWait(page) {
  await page.click('#stream');
  await page.waitForSelector('body[data-state="done"], body[data-state="error"]');
}

async function refineAndWait(page) {
  await page.click('#refine');
  await page.waitForSelector('body[data-state="done"], body[data-state="error"]');
}

const { test, failed } = checks();

try {
  await test('stream, refine: readouts equal the server\'s, the mesh drawn and refined', async () => {
    const errors = [];
    const page = await openViewer(errors);
    await streamAndWait(page);
    const first = await serverNumbers(BUDGET);
    checkReadouts(await readouts(page), first, `budget ${BUDGET}`);
    const coarse = await shot(page, 'viewer_budget_6KiB.png');

    await refineAndWait(page);
    const extra = await fetch(`${server.url}/v1/meshes/${id}/stream?order=${ORDER}` +
                              `&from=${first.nextCursor}&budget=${REFINE_KIB * 1024}`);
    const packets = first.packets + Number(extra.headers.get('x-meshwave-packets'));
    assert.ok(packets > first.packets, 'the refinement brings packets');
    // The container of exactly that prefix: its size from the mesh's
    // rate-distortion table (quality order; the header grows with the
    // packets present, so it is not the two budgets added).
    const details = await (await fetch(`${server.url}/v1/meshes/${id}`)).json();
    const point = details.rate_distortion.find((p) => p.packets === packets);
    assert.ok(point, `no rate-distortion point for ${packets} packets`);
    const refined = await serverNumbers(Number(point.bytes));
    assert.equal(refined.packets, packets);
    checkReadouts(await readouts(page), refined, `after refine +${REFINE_KIB} KiB`);
    const fine = await shot(page, 'viewer_refined_14KiB.png');

    const cmp = await comparePngs(coarse, fine);
    console.log(`  screenshots: ${cmp.drawn} then ${cmp.drawnB} of ${cmp.total} pixels drawn, ` +
                `${cmp.differ} differ`);
    assert.ok(cmp.drawn > cmp.total * 0.02, 'the mesh is drawn (over 2 % of the view)');
    assert.ok(cmp.differ > cmp.drawn * 0.005, 'the refined mesh looks different');
    // The camera stays where the first mesh put it: the refined mesh covers
    // about the same area (a refit or a lost mesh would not).
    assert.ok(Math.abs(cmp.drawnB - cmp.drawn) < cmp.drawn * 0.3, 'the same view, refined');
    const first_ms = await page.evaluate(() => Number(document.getElementById('r-first').dataset.value));
    assert.ok(first_ms > 0, 'time to first mesh shown');
    assert.deepEqual(errors, [], 'console errors');
    await page.close();
  });

  await test('an address naming a mesh streams it on opening', async () => {
    const errors = [];
    const page = await browser.context.newPage();
    page.on('console', (m) => { if (m.type() === 'error') errors.push(m.text()); });
    page.on('pageerror', (e) => errors.push(`uncaught: ${e.message}`));
    // No click: the stream starts while the page's modules still load.
    // No tolerance (screen_error empty): the budget's readouts, with no
    // view refine after them.
    await page.goto(`${server.url}/viewer/?mesh=${id}&order=${ORDER}&budget=${BUDGET / 1024}` +
                    '&rate=0&screen_error=');
    await page.waitForSelector('body[data-state="done"], body[data-state="error"]');
    checkReadouts(await readouts(page), await serverNumbers(BUDGET), 'opened at ?mesh=');
    assert.equal(await page.inputValue('#mesh'), id, 'the mesh is the one picked');
    const first = await page.evaluate(() => document.getElementById('r-first').dataset);
    assert.ok(Number(first.fromNavigation) >= Number(first.value) && Number(first.value) > 0,
              `first mesh times: ${JSON.stringify(first)}`);
    const cmp = await comparePngs(await shot(page, 'viewer_opened_at_mesh.png'),
                                  await shot(page, 'viewer_opened_at_mesh.png'));
    assert.ok(cmp.drawn > cmp.total * 0.02, 'the mesh is drawn (over 2 % of the view)');
    // A mesh the catalog does not hold: the server's refusal, in words.
    await page.goto(`${server.url}/viewer/?mesh=000000000000`);
    await page.waitForSelector('body[data-state="error"]');
    assert.match((await readouts(page)).error, /refused|not found|no mesh/i);
    assert.deepEqual(errors.filter((e) => !/WebSocket|404/.test(e)), [], 'console errors');
    await page.close();
  });

  await test('a decoder that cannot load: the page says so', async () => {
    const page = await browser.context.newPage();
    // The decoder's worker fetches the wasm: it is not found.
    await page.route(/meshwave_decoder\.wasm$/, (route) => route.fulfill({ status: 404, body: 'gone' }));
    await page.goto(`${server.url}/viewer/?mesh=${id}&budget=6`);
    await page.waitForSelector('body[data-state="error"]');
    assert.match((await readouts(page)).error, /WebAssembly decoder .* could not be loaded/);
    assert.ok(await page.isDisabled('#stream'), 'nothing to stream with');
    await page.close();
  });

  await test('the whole stream ends in the input\'s own mesh', async () => {
    const errors = [];
    const page = await openViewer(errors);
    await page.fill('#budget', '100000');
    await streamAndWait(page);
    const info = JSON.parse(execFileSync(opt.cli, ['info', opt.mesh, '--json'], { encoding: 'utf8' }));
    const want = `${info.as_read.vertices} / ${info.as_read.faces}`;
    const size = await page.evaluate(() => document.getElementById('r-size').textContent);
    console.log(`  drawn: ${size} vertices / faces (the input: ${want})`);
    assert.equal(size, want, 'the original mesh drawn');
    const drawn = await shot(page, 'viewer_original.png');
    const cmp = await comparePngs(drawn, drawn);
    assert.ok(cmp.drawn > cmp.total * 0.02, 'the mesh is drawn (over 2 % of the view)');
    assert.deepEqual(errors, [], 'console errors');
    await page.close();
  });

  await test('error colours against the complete stream', async () => {
    const errors = [];
    const page = await openViewer(errors);
    await streamAndWait(page);
    const plain = await shot(page, 'viewer_plain_6KiB.png');
    await page.check('#errors');
    await page.waitForFunction(() => document.getElementById('status').textContent.startsWith('error colours:'));
    const coloured = await shot(page, 'viewer_error_colours_6KiB.png');
    // Yellow to red: red well above blue; the plain grey never is.
    const cmp = await comparePngs(plain, coloured);
    const warm = [cmp.warmA, cmp.warmB];
    console.log(`  warm pixels: ${warm[0]} plain, ${warm[1]} with error colours`);
    assert.equal(warm[0], 0, 'the plain mesh has no error colour');
    assert.ok(warm[1] > 100, 'a 6 KiB prefix differs visibly from the complete stream');
    assert.deepEqual(errors, [], 'console errors');
    await page.close();
  });

  // A proxy between page and server (Playwright's WebSocket routing) that
  // passes everything through except what `tamper` changes.
  async function proxiedViewer(tamper) {
    const errors = [];
    const page = await openViewer(errors);
    let afterDone = false;
    await page.routeWebSocket(/\/v1\/ws$/, (ws) => {
      const upstream = ws.connectToServer();
      ws.onMessage((m) => upstream.send(m));
      upstream.onMessage((m) => {
        const bytes = new Uint8Array(m);
        const msg = decodeServerMessage(bytes);
        if (tamper(msg, bytes, afterDone, ws) !== 'drop') ws.send(Buffer.from(bytes));
        if (msg.kind === 'done') afterDone = true;
      });
    });
    return page;
  }

  async function checkKeptLastGoodMesh(page, good, goodShot, name, errorPattern) {
    const r = await readouts(page);
    assert.equal(r.state, 'error');
    assert.match(r.error, errorPattern);
    assert.match(r.error, /last good mesh/);
    checkReadouts(r, good, 'after the failure');
    const after = await shot(page, name);
    await page.screenshot({ path: path.join(opt.artefacts, name.replace('.png', '_page.png')) });
    const cmp = await comparePngs(goodShot, after);
    console.log(`  ${name}: "${r.error.replace(/\n/g, ' ')}"; ${cmp.differ} pixels differ`);
    assert.ok(cmp.drawn > cmp.total * 0.02, 'the last good mesh is still drawn');
    assert.ok(cmp.differ <= 10, 'the mesh shown did not change');
    // Not frozen: the page answers and can stream again.
    assert.equal(await page.evaluate(() => document.getElementById('stream').disabled), false);
    await page.close();
  }

  await test('a corrupt packet: readable error, last good mesh kept', async () => {
    // Corrupts the first packet of the refinement: the payload is the last
    // field of a Packet message, so its last bytes are payload bytes.
    let seen = 0;
    const page = await proxiedViewer((msg, bytes, afterDone) => {
      if (afterDone && msg.kind === 'packet' && ++seen === 1) {
        for (let i = bytes.length - 4; i < bytes.length; ++i) bytes[i] ^= 0x5a;
      }
    });
    await streamAndWait(page);
    const good = await serverNumbers(BUDGET);
    const goodShot = await shot(page, 'viewer_before_corrupt.png');
    await page.click('#refine');
    await page.waitForSelector('body[data-state="error"]');
    await checkKeptLastGoodMesh(page, good, goodShot, 'viewer_after_corrupt.png',
      /packet \d+ \(cursor \d+\) was refused/);
  });

  await test('the socket closed mid-stream: readable error, last good mesh kept', async () => {
    let seen = 0;
    const page = await proxiedViewer((msg, bytes, afterDone, ws) => {
      if (afterDone && msg.kind === 'packet' && ++seen === 1) {
        ws.close({ code: 1011, reason: 'test proxy closed it' });
        return 'drop';
      }
    });
    await streamAndWait(page);
    const good = await serverNumbers(BUDGET);
    const goodShot = await shot(page, 'viewer_before_close.png');
    await page.click('#refine');
    await page.waitForSelector('body[data-state="error"]');
    await checkKeptLastGoodMesh(page, good, goodShot, 'viewer_after_close.png',
      /connection to the server closed \(code 1011/);
  });
} finally {
  await browser.close();
  await server.stop();
  rmSync(work, { recursive: true, force: true });
}
console.log(`screenshots in ${opt.artefacts}`);
if (failed()) process.exit(1);
if (fake) {
  console.log('SKIP: wiring checked with the test-only fake decoder; the real module is needed to pass');
  process.exit(SKIP);
}
console.log('viewer_test: all passed');
