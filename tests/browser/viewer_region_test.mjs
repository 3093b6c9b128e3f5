// "refine where I look" end to end: meshwave-server on 127.0.0.1 serving a
// shipped sample ingested with small precincts, the viewer with the real
// WebAssembly decoder in headless Chromium, and a test proxy (Playwright's
// WebSocket routing) recording every message both ways. The mesh is
// streamed at a small budget, then the camera is turned, panned and zoomed
// close to one corner with the mouse, as a user would, and left to rest:
//  1. the page sends a refine with a view (the slider's bytes, the pixel
//     tolerance left empty: viewer_view_test.mjs has the tolerance; the
//     camera in the mesh's coordinates, seeing a part of it, not all), and
//     units that are parts of split packets arrive;
//  2. no unit arrives twice in the session (nor a part of a packet that came
//     whole, nor the packet after a part);
//  3. the units received, decoded here with the same module: the vertices
//     the view sees moved more than those out of it, and came closer to the
//     complete stream's mesh, by a larger fraction than the others;
//  4. the readouts count the units, parts and bytes the page received;
//  5. "refine +N KiB" afterwards sends a refine without a view (continuing
//     the region) and only new units; with "refine where I look" unticked a
//     camera move sends nothing.
// Screenshots are kept in the artefacts directory.
//
// The mesh: data/holes.off, an open patch already semi-regular (2 levels
// over a base of 518 faces, 4,291 vertices), ingested with --precinct-size
// 64 --split-bytes 4: 50 precincts in its finest subband, 13 in the other,
// the low bitplanes of both split. With the server's default (4096
// coefficients) it has one precinct per subband and nothing split. The
// elephant, remeshed over a base of a few large faces, has precincts whose
// balls span half the mesh: any close view takes in nearly all of them.
//
// node viewer_region_test.mjs --server BIN --cli BIN --decoder meshwave_decoder.js
//   --viewer web/viewer --mesh data/holes.off --node-modules DIR --artefacts DIR
// Exit 0 passed, 1 failed, 77 skipped (no Chromium, no decoder module, or
// the test-only fake decoder, which decodes nothing to compare).
import assert from 'node:assert/strict';
import { execFileSync } from 'node:child_process';
import { mkdirSync, rmSync } from 'node:fs';
import path from 'node:path';
import { setTimeout as sleep } from 'node:timers/promises';
import { fileURLToPath } from 'node:url';
import { Server, checkEachUnitOnce, realDecoderTestOptions, ingest, launchChromium, loadDecoderModule, tempDir, viewerDir,
  checks } from './harness.mjs';
import { decodeServerMessage } from '../../web/viewer/ws_protocol.js';

const opt = realDecoderTestOptions('viewer_region_test', 'decodes nothing');

const PRECINCTS = ['--precinct-size', '64', '--split-bytes', '4'];
// Of a container of 8.3 KB (1.2 KB of header): a coarse start, refines of
// a seventh of the rest.
const BUDGET_KIB = 3, REFINE_KIB = 1, ORDER = 'quality';
const protoDir = fileURLToPath(new URL('../../proto/', import.meta.url));
const mw = await loadDecoderModule(opt.decoder);

mkdirSync(opt.artefacts, { recursive: true });
const work = tempDir('meshwave-viewer-region-test-');
const catalog = path.join(work, 'catalog');
const id = ingest(opt.server, catalog, opt.mesh, PRECINCTS);
// Both stopped in the `finally` below, also when the other failed to start.
let server = null, browser = null;

// A ClientMessage as protoc's text format (what the page sent, read by an
// independent parser).
function clientText(bytes) {
  return execFileSync('protoc', [`--proto_path=${protoDir}`, '--decode=meshwave.proto.ClientMessage',
    'websocket.proto'], { input: bytes, encoding: 'utf8' });
}

// The viewer behind a recording proxy: `log.client` holds what the page sent
// ({text, at: server messages before it}), `log.server` what it received.
async function openViewer(consoleErrors) {
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
  await page.goto(`${server.url}/viewer/`);
  await page.waitForSelector('body[data-state="ready"], body[data-state="error"]');
  await page.selectOption('#mesh', id);
  await page.selectOption('#order', ORDER);
  await page.fill('#budget', String(BUDGET_KIB));
  await page.fill('#rate', '0');
  await page.fill('#refine-kib', String(REFINE_KIB));
  await page.fill('#screen-error', '');  // view refines of N KiB
  return { page, log };
}

async function waitDone(page) {
  await page.waitForSelector('body[data-state="done"], body[data-state="error"]');
  const error = await page.evaluate(() => document.getElementById('error').textContent);
  assert.equal(error, '', 'the page shows an error');
}

async function shot(page, name) {
  await page.evaluate(() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r))));
  await page.locator('#view').screenshot({ path: path.join(opt.artefacts, name) });
}

const packetsOf = (messages) => messages.filter((m) => m.kind === 'packet');

// Float64 positions of the finest level from a header and Packet messages.
function decode(header, packets) {
  const dec = new mw.Decoder(header);
  try {
    for (const p of packets) {
      if (p.part === null) dec.addPacket(p.id, p.payload);
      else dec.addPacketPart(p.id, p.part, p.payload);
    }
    return dec.positions64();
  } finally {
    dec.delete();
  }
}

// Vertices the view sees (inside the cone of the screen's half height) and
// those it does not (behind the eye or outside the cone through the
// screen's corners), as index lists.
function seenAndUnseen(view, positions) {
  const [ex, ey, ez, dx, dy, dz, fov, width, height] = view;
  const length = Math.hypot(dx, dy, dz);
  const inner = (fov / 2) * Math.PI / 180;
  const outer = Math.atan(Math.tan(inner) * Math.hypot(1, width / height));
  const seen = [], unseen = [];
  for (let v = 0; v < positions.length / 3; ++v) {
    const x = positions[3 * v] - ex, y = positions[3 * v + 1] - ey, z = positions[3 * v + 2] - ez;
    const along = (x * dx + y * dy + z * dz) / length;
    const angle = Math.acos(Math.min(1, along / Math.hypot(x, y, z)));
    if (along > 0 && angle < inner) seen.push(v);
    else if (along <= 0 || angle > outer) unseen.push(v);
  }
  return { seen, unseen };
}

// Mean distance between the same vertices of two meshes, over `vertices`.
function meanDistance(a, b, vertices) {
  let sum = 0;
  for (const v of vertices) {
    sum += Math.hypot(a[3 * v] - b[3 * v], a[3 * v + 1] - b[3 * v + 1], a[3 * v + 2] - b[3 * v + 2]);
  }
  return sum / vertices.length;
}

async function readouts(page) {
  return page.evaluate(() => ({
    bytes: Number(document.getElementById('r-bytes').dataset.value),
    packets: Number(document.getElementById('r-packets').textContent),
    parts: Number(document.getElementById('r-parts').textContent),
  }));
}

const { test, failed } = checks();

try {
  server = await Server.start(opt.server, catalog,
    viewerDir(opt.viewer, opt.decoder, path.join(work, 'viewer')), work);
  browser = await launchChromium(opt['node-modules']);
  await test('refine where I look: a view refine, parts of it, each unit once, the view refined', async () => {
    const errors = [];
    const { page, log } = await openViewer(errors);
    assert.equal(await page.isChecked('#follow-view'), true, '"refine where I look" is on by default');
    await page.click('#stream');
    await waitDone(page);
    assert.equal(log.client.length, 1, 'the stream alone sends one start');
    await shot(page, 'viewer_region_before.png');
    const before = packetsOf(log.server);

    // Look down on the patch (left drag down: the camera orbits up over
    // it), pan a corner towards the centre (right drag), zoom in (wheel),
    // then leave the camera alone. The gestures take far less than the
    // page's 400 ms settle: one rest, one refine.
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
    await page.waitForFunction(() => document.body.dataset.viewRefines);
    await waitDone(page);
    await sleep(1000);  // nothing more is sent while the camera rests
    await waitDone(page);
    await shot(page, 'viewer_region_after.png');

    // 1. The refine with a view, in the mesh's coordinates. One, unless the
    // machine was so loaded that the camera rested between two gestures;
    // then the last view is the one looked through.
    const refines = log.client.slice(1);
    console.log(`  sent after the stream: ${refines.map((r) => r.text.replace(/\s+/g, ' ')).join(' | ')}`);
    assert.ok(refines.length >= 1, 'a refine when the camera rests');
    assert.equal(await page.evaluate(() => document.body.dataset.viewRefines), String(refines.length));
    for (const { text } of refines) {
      assert.match(text, new RegExp(`^refine \\{\\s+extra_bytes: ${REFINE_KIB * 1024}\\s+view: "`));
    }
    const view = refines.at(-1).text.match(/view: "([^"]+)"/)[1].split(',').map(Number);
    assert.equal(view.length, 9);
    const canvas = await page.evaluate(() => {
      const c = document.querySelector('#view canvas');
      return [c.width, c.height];
    });
    assert.deepEqual(view.slice(6), [40, ...canvas], 'fov and the canvas size in pixels');
    const after = packetsOf(log.server.slice(refines[0].at));
    const parts = after.filter((p) => p.part !== null);
    console.log(`  the view refine: ${after.length} units, ${parts.length} parts, ` +
                `${after.reduce((n, p) => n + p.payload.length, 0)} bytes`);
    assert.ok(parts.length > 0, 'units that are parts of split packets arrived');

    // 2. Each unit once.
    checkEachUnitOnce(packetsOf(log.server));

    // 3. What the view sees was refined, the rest much less.
    const header = log.server[0].header;
    const complete = mw.parseContainer(new Uint8Array(
      await (await fetch(`${server.url}/v1/meshes/${id}/container`)).arrayBuffer()));
    const done = decode(complete.header, complete.packets.map((p) => ({ ...p, part: null })));
    const p0 = decode(header, before), p1 = decode(header, [...before, ...after]);
    const { seen, unseen } = seenAndUnseen(view, done);
    const vertices = done.length / 3;
    console.log(`  the view sees ${seen.length} of ${vertices} vertices, misses ${unseen.length}`);
    assert.ok(seen.length > vertices * 0.02, 'the view sees some of the mesh');
    assert.ok(unseen.length > vertices * 0.25, 'the view is close to one side, not the whole mesh');
    const moved = [meanDistance(p0, p1, seen), meanDistance(p0, p1, unseen)];
    const errorBefore = [meanDistance(p0, done, seen), meanDistance(p0, done, unseen)];
    const errorAfter = [meanDistance(p1, done, seen), meanDistance(p1, done, unseen)];
    console.log(`  mean vertex move seen ${moved[0].toExponential(3)}, unseen ${moved[1].toExponential(3)}; ` +
                `error to the complete mesh seen ${errorBefore[0].toExponential(3)} -> ` +
                `${errorAfter[0].toExponential(3)}, unseen ${errorBefore[1].toExponential(3)} -> ` +
                `${errorAfter[1].toExponential(3)}`);
    // Measured: 2.3 times the move, error to 0.29 against 0.77 of itself.
    assert.ok(moved[0] > 1.5 * moved[1], 'the vertices seen moved over 1.5 times more than the others');
    assert.ok(errorAfter[0] < 0.5 * errorBefore[0], 'the vertices seen came closer to the complete mesh');
    assert.ok(errorAfter[0] / errorBefore[0] < 0.6 * (errorAfter[1] / errorBefore[1]),
      'by a larger fraction than the others');

    // 4. The readouts count what came.
    const all = packetsOf(log.server);
    assert.deepEqual(await readouts(page), {
      bytes: header.length + all.reduce((n, p) => n + p.payload.length, 0),
      packets: all.length, parts: all.filter((p) => p.part !== null).length,
    });

    // 5. The manual refine continues the region, sending only new units.
    const sentBefore = log.client.length;
    await page.click('#refine');
    await waitDone(page);
    assert.equal(log.client.length, sentBefore + 1);
    const manual = log.client.at(-1);
    assert.match(manual.text, new RegExp(`^refine \\{\\s+extra_bytes: ${REFINE_KIB * 1024}\\s+\\}`),
      'refine +N KiB sends no view');
    const more = packetsOf(log.server.slice(manual.at));
    assert.ok(more.length > 0, 'the manual refine brings units');
    checkEachUnitOnce(packetsOf(log.server));
    // Unticked, a camera move asks for nothing.
    await page.uncheck('#follow-view');
    await page.mouse.move(cx, cy);
    await page.mouse.wheel(0, 200);
    await sleep(1000);
    assert.equal(log.client.length, sentBefore + 1, 'nothing sent with "refine where I look" off');
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
console.log('viewer_region_test: all passed');
