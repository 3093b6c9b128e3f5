// "refine where I look" by screen-space error, end to end: meshwave-server
// on 127.0.0.1 serving a shipped sample ingested with small precincts, the
// viewer with the real WebAssembly decoder in headless Chromium, opened by
// address, and a test proxy (Playwright's WebSocket routing) recording every
// message both ways: every unit (packet id and part) the page receives, and
// so hands to its decoder, which the readouts then count.
//  1. The defaults (/viewer/?mesh=ID&budget=…): "refine where I look" on,
//     a tolerance of 1 px; once the stream is done, one refine with the
//     camera as its view, screen_error 1 and extra_bytes 4 MiB.
//  2. An address with ?screen_error=0.25&view_budget=2: that refine first,
//     then the camera turned, panned and zoomed onto one corner with the
//     mouse and left to rest: a refine with the new view and the same
//     tolerance and budget, bringing units; then "refine +N KiB", which
//     names that view again without the tolerance.
// In both, every refine's units are exactly those GET /stream answers for
// the same view, screen_error, budget and the units held when it was sent
// (the held bitmap computed here from the header), in the same order and
// with the same bytes; no unit arrives twice in a session; the readouts
// count every unit and the tolerance of the last view refine.
// The small view_budget of 2 keeps something to refine after the move also
// from a server that sends the whole view up to the budget; the checks are
// the same whether the server stops at the tolerance or not.
//
// node viewer_view_test.mjs --server BIN --cli BIN --decoder meshwave_decoder.js
//   --viewer web/viewer --mesh data/holes.off --node-modules DIR --artefacts DIR
// Exit 0 passed, 1 failed, 77 skipped (no Chromium, no decoder module, or
// the test-only fake decoder, which cannot read a header here).
import assert from 'node:assert/strict';
import { execFileSync } from 'node:child_process';
import { mkdirSync, rmSync } from 'node:fs';
import path from 'node:path';
import { setTimeout as sleep } from 'node:timers/promises';
import { fileURLToPath } from 'node:url';
import { Server, checkEachUnitOnce, realDecoderTestOptions, ingest, launchChromium, loadDecoderModule, tempDir, viewerDir,
  checks } from './harness.mjs';
import { decodeServerMessage } from '../../web/viewer/ws_protocol.js';

const opt = realDecoderTestOptions('viewer_view_test', 'reads no header');

// As viewer_region_test.mjs: data/holes.off with 50 precincts in its finest
// subband, the low bitplanes split. A first stream of 2 KiB (1.2 KB of it
// the header) leaves the first view refine something to bring.
const PRECINCTS = ['--precinct-size', '64', '--split-bytes', '4'];
const BUDGET_KIB = 2;
const DEFAULT_SCREEN_ERROR = 1, DEFAULT_VIEW_BUDGET = 4 * 1024 * 1024;
// A tolerance the 2-KiB stream does not meet where the camera goes (at 1
// or 2 px the first units already bring that view within it).
const SCREEN_ERROR = 0.25, VIEW_BUDGET_KIB = 2;
const protoDir = fileURLToPath(new URL('../../proto/', import.meta.url));
const mw = await loadDecoderModule(opt.decoder);

mkdirSync(opt.artefacts, { recursive: true });
const work = tempDir('meshwave-viewer-view-test-');
const catalog = path.join(work, 'catalog');
const id = ingest(opt.server, catalog, opt.mesh, PRECINCTS);
let server = null, browser = null;

// A ClientMessage as protoc's text format (what the page sent, read by an
// independent parser).
function clientText(bytes) {
  return execFileSync('protoc', [`--proto_path=${protoDir}`, '--decode=meshwave.proto.ClientMessage',
    'websocket.proto'], { input: bytes, encoding: 'utf8' }).replace(/\s+/g, ' ').trim();
}

// The viewer at `address` behind a recording proxy: `log.client` holds what
// the page sent ({text, at: server messages before it}), `log.server` what
// it received.
async function openViewer(address, consoleErrors) {
  const page = await browser.context.newPage();
  page.on('console', (m) => { if (m.type() === 'error') consoleErrors.push(m.text()); });
  page.on('pageerror', (e) => consoleErrors.push(`uncaught: ${e.message}`));
  const log = { client: [], server: [] };
  await page.routeWebSocket(/\/v1\/ws$/, (ws) => {
    const upstream = ws.connectToServer();
    ws.onMessage((m) => {
      log.client.push({ text: clientText(Buffer.from(m)), at: log.server.length });
      upstream.send(m);
    });
    upstream.onMessage((m) => {
      const bytes = new Uint8Array(m);  // a copy: the payload views stay valid
      log.server.push(decodeServerMessage(bytes));
      ws.send(Buffer.from(bytes));
    });
  });
  await page.goto(`${server.url}${address}`);
  return { page, log };
}

// The stream and `refines` view refines are done.
async function waitViewRefines(page, refines) {
  await page.waitForSelector(`body[data-view-refines="${refines}"][data-state="done"], ` +
                             'body[data-state="error"]');
  const error = await page.evaluate(() => document.getElementById('error').textContent);
  assert.equal(error, '', 'the page shows an error');
}

async function shot(page, name) {
  await page.evaluate(() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r))));
  await page.locator('#view').screenshot({ path: path.join(opt.artefacts, name) });
}

const packetsOf = (messages) => messages.filter((m) => m.kind === 'packet');

// Unit numbers (docs/API.md, "Units and the held bitmap"): packets in id
// order, a split packet one unit per part. first[id] is its packet's first.
function unitNumbers(header) {
  const dec = new mw.Decoder(header);
  try {
    const first = [], count = [];
    let total = 0;
    for (let packet = 0; packet < dec.packetCount(); ++packet) {
      first.push(total);
      count.push(Math.max(1, dec.partCount(packet)));
      total += count.at(-1);
    }
    return { first, count, total };
  } finally {
    dec.delete();
  }
}

// `held` of the units in `packets` (Packet messages): base64url, no
// padding, of a bitmap with unit n at bit n % 8 of byte n / 8, trailing
// zero bytes left out.
function heldText(units, packets) {
  const bits = new Uint8Array(Math.ceil(units.total / 8));
  const set = (n) => { bits[n >> 3] |= 1 << (n & 7); };
  for (const p of packets) {
    if (p.part !== null) set(units.first[p.id] + p.part);
    else for (let k = 0; k < units.count[p.id]; ++k) set(units.first[p.id] + k);
  }
  let end = bits.length;
  while (end > 0 && bits[end - 1] === 0) --end;
  return Buffer.from(bits.subarray(0, end)).toString('base64url');
}

// A body of units (application/vnd.meshwave.units): per unit the packet
// id, 0 or 1 + part, the payload's length (varints), the payload.
function readUnits(body) {
  const out = [];
  let pos = 0;
  const varint = () => {
    let n = 0, scale = 1, b;
    do {
      assert.ok(pos < body.length, 'a truncated record in the body of units');
      b = body[pos++];
      n += (b & 0x7f) * scale;
      scale *= 128;
    } while (b & 0x80);
    return n;
  };
  while (pos < body.length) {
    const packet = varint(), part = varint(), length = varint();
    assert.ok(pos + length <= body.length, 'a truncated payload in the body of units');
    out.push({ id: packet, part: part === 0 ? null : part - 1, payload: body.subarray(pos, pos + length) });
    pos += length;
  }
  return out;
}

// The fields of a refine as protoc printed them.
function refineFields(text) {
  const extra = text.match(/extra_bytes: (\d+)/);
  const view = text.match(/view: "([^"]+)"/);
  const px = text.match(/screen_error: ([0-9.e+-]+)/);
  return { extraBytes: extra && Number(extra[1]), view: view?.[1] ?? null, screenError: px && Number(px[1]) };
}

// GET /stream's units for a view, its screen_error (null: none), the units
// held and a budget.
async function unitsOverHttp(view, screenError, held, budget) {
  const query = new URLSearchParams({ view, held, budget: String(budget) });
  if (screenError !== null) query.set('screen_error', String(screenError));
  const reply = await fetch(`${server.url}/v1/meshes/${id}/stream?${query}`);
  const body = new Uint8Array(await reply.arrayBuffer());
  assert.equal(reply.status, 200, `GET /stream?${query}: ${new TextDecoder().decode(body)}`);
  const units = readUnits(body);
  assert.equal(Number(reply.headers.get('x-meshwave-units')), units.length, 'X-Meshwave-Units');
  return units;
}

const unitName = (u) => (u.part === null ? `${u.id}` : `${u.id}.${u.part}`);

// Each refine the page sent after the stream: a view, screen_error and
// extra_bytes as wanted, and its units (those up to the next request)
// exactly GET /stream's for the same numbers and what was held before it.
async function checkViewRefines(log, want) {
  const header = log.server[0].header;
  const units = unitNumbers(header);
  const refines = log.client.slice(1);
  const answers = [];
  for (const [i, refine] of refines.entries()) {
    const fields = refineFields(refine.text);
    console.log(`  refine ${i + 1}: ${refine.text}`);
    assert.match(refine.text, /^refine \{/, 'a refine');
    assert.ok(fields.view, 'the refine names a view');
    assert.equal(fields.screenError, want.screenError, 'screen_error');
    assert.equal(fields.extraBytes, want.extraBytes, 'extra_bytes');
    const held = packetsOf(log.server.slice(0, refine.at));
    const got = packetsOf(log.server.slice(refine.at, refines[i + 1]?.at ?? log.server.length));
    const http = await unitsOverHttp(fields.view, fields.screenError, heldText(units, held),
                                     fields.extraBytes);
    console.log(`    ${got.length} units (${got.filter((u) => u.part !== null).length} parts, ` +
                `${got.reduce((n, u) => n + u.payload.length, 0)} bytes) over the WebSocket, ` +
                `${http.length} from GET /stream with held = the ${held.length} units before it`);
    assert.deepEqual(got.map(unitName), http.map(unitName), 'the units of GET /stream, in its order');
    for (const [k, u] of got.entries()) {
      assert.ok(Buffer.from(u.payload).equals(Buffer.from(http[k].payload)), `unit ${unitName(u)}'s bytes`);
    }
    answers.push({ fields, held, got, units });
  }
  return answers;
}

// The readouts count every unit received and name the last view refine's
// tolerance.
async function checkReadouts(page, log, screenError) {
  const all = packetsOf(log.server);
  const shown = await page.evaluate(() => ({
    bytes: Number(document.getElementById('r-bytes').dataset.value),
    packets: Number(document.getElementById('r-packets').textContent),
    parts: Number(document.getElementById('r-parts').textContent),
    screenError: document.body.dataset.screenError,
    view: document.getElementById('r-view').textContent,
  }));
  console.log(`  readouts: ${shown.packets} units, ${shown.parts} parts, ${shown.bytes} bytes; ` +
              `view refines "${shown.view}"`);
  assert.deepEqual(shown, {
    bytes: log.server[0].header.length + all.reduce((n, p) => n + p.payload.length, 0),
    packets: all.length, parts: all.filter((p) => p.part !== null).length,
    screenError: String(screenError), view: shown.view,
  });
  assert.match(shown.view, new RegExp(`to ${screenError} px$`), 'the view refines readout');
}

const { test, failed } = checks();

try {
  server = await Server.start(opt.server, catalog,
    viewerDir(opt.viewer, opt.decoder, path.join(work, 'viewer')), work);
  browser = await launchChromium(opt['node-modules']);

  await test('by default, the stream then a refine of the view to within 1 px', async () => {
    const errors = [];
    const { page, log } = await openViewer(`/viewer/?mesh=${id}&budget=${BUDGET_KIB}&rate=0`, errors);
    await waitViewRefines(page, 1);
    assert.equal(await page.isChecked('#follow-view'), true, '"refine where I look" is on');
    assert.equal(await page.inputValue('#screen-error'), String(DEFAULT_SCREEN_ERROR), 'the tolerance');
    assert.match(log.client[0].text, /^start \{/, 'the stream first');
    assert.equal(log.client.length, 2, 'the start and one view refine');
    await checkViewRefines(log, { screenError: DEFAULT_SCREEN_ERROR, extraBytes: DEFAULT_VIEW_BUDGET });
    checkEachUnitOnce(packetsOf(log.server));
    await checkReadouts(page, log, DEFAULT_SCREEN_ERROR);
    await shot(page, 'viewer_view_default.png');
    assert.deepEqual(errors, [], 'console errors');
    await page.close();
  });

  await test('?screen_error=: the view refined to it, again after a move, each unit once', async () => {
    const errors = [];
    const { page, log } = await openViewer(`/viewer/?mesh=${id}&budget=${BUDGET_KIB}&rate=0` +
      `&screen_error=${SCREEN_ERROR}&view_budget=${VIEW_BUDGET_KIB}`, errors);
    await waitViewRefines(page, 1);
    assert.equal(await page.inputValue('#screen-error'), String(SCREEN_ERROR), 'the tolerance');
    await shot(page, 'viewer_view_before.png');
    const beforeMove = log.client.length;
    assert.equal(beforeMove, 2, 'the start and one view refine');

    // As viewer_region_test.mjs: look down on the patch, pan a corner
    // towards the centre, zoom in, then leave the camera alone (one rest,
    // one refine, unless the machine was so loaded that the camera rested
    // between two gestures).
    const box = await page.locator('#view canvas').boundingBox();
    const cx = box.x + box.width / 2, cy = box.y + box.height / 2;
    const drag = async (button, dx, dy) => {
      await page.mouse.move(cx, cy);
      await page.mouse.down({ button });
      await page.mouse.move(cx + box.width * dx, cy + box.height * dy, { steps: 4 });
      await page.mouse.up({ button });
    };
    await drag('left', 0, 0.2);
    await drag('right', 0.25, 0.25);
    for (let i = 0; i < 12; ++i) await page.mouse.wheel(0, -200);
    await page.waitForFunction(() => Number(document.body.dataset.viewRefines) > 1);
    await page.waitForSelector('body[data-state="done"], body[data-state="error"]');
    await sleep(1000);  // nothing more is sent while the camera rests
    const refines = Number(await page.evaluate(() => document.body.dataset.viewRefines));
    await waitViewRefines(page, refines);
    await shot(page, 'viewer_view_after.png');

    assert.equal(log.client.length, 1 + refines, 'one message per view refine, after the start');
    const answers = await checkViewRefines(log, { screenError: SCREEN_ERROR,
                                                  extraBytes: VIEW_BUDGET_KIB * 1024 });
    const [first, moved] = [answers[0], answers.at(-1)];
    assert.notEqual(moved.fields.view, first.fields.view, 'the camera moved');
    const afterMove = answers.slice(1).flatMap((a) => a.got);
    assert.ok(afterMove.length > 0, 'the refines after the move bring units');
    checkEachUnitOnce(packetsOf(log.server));  // so those are new
    await checkReadouts(page, log, SCREEN_ERROR);

    // Whether the server's selection uses the tolerance (the same request
    // without screen_error): said, not checked.
    const without = await unitsOverHttp(moved.fields.view, null, heldText(moved.units, moved.held),
                                        moved.fields.extraBytes);
    console.log(`  the last refine's request without screen_error: ${without.length} units ` +
                `(${without.map(unitName).join(',') === moved.got.map(unitName).join(',')
                  ? 'the same: the server does not use the tolerance' : 'not the same'})`);

    // "refine +N KiB" after it: that view again without the tolerance (within
    // it, the view would bring nothing more), N KiB of what it sees first.
    const sent = log.client.length;
    await page.click('#refine');
    await waitViewRefines(page, refines);
    assert.equal(log.client.length, sent + 1);
    const manual = refineFields(log.client.at(-1).text);
    console.log(`  refine +N KiB: ${log.client.at(-1).text}`);
    assert.deepEqual(manual, { extraBytes: 4 * 1024, view: moved.fields.view, screenError: null });
    assert.ok(packetsOf(log.server.slice(log.client.at(-1).at)).length > 0, 'refine +N KiB brings units');
    checkEachUnitOnce(packetsOf(log.server));
    assert.deepEqual(errors, [], 'console errors');
    await page.close();
  });
} finally {
  await browser?.close();
  await server?.stop();
  rmSync(work, { recursive: true, force: true });
}
console.log(`screenshots in ${opt.artefacts}`);
if (failed()) process.exit(1);
console.log('viewer_view_test: all passed');
