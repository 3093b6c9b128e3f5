// The viewer page: the catalog (GET /v1/meshes), a mesh streamed over
// GET /v1/ws with the order, budget and pace chosen, every refinement drawn
// as it arrives, readouts, "refine +N KiB", "refine where I look" (once the
// stream is done and whenever the camera stops, a refine with the camera as
// its view and a pixel tolerance: the server sends what that view needs to
// be within it on screen, and stops; with no tolerance, N KiB of what the
// view sees first), optional error colours against the complete stream.
// Errors are shown in words; the last good mesh stays.
// An address that names a mesh (/viewer/?mesh=ID, with ?order=, ?budget=
// in KiB, ?rate=, ?screen_error= in pixels (empty: none) and ?view_budget=
// in KiB if wanted) streams it on opening, while the page's other parts
// load.
import { DecoderClient } from './decoder_client.js';
import { StreamSession, fetchComplete } from './stream_session.js';
import { errorColours } from './error_colours.js';

const $ = (id) => document.getElementById(id);
const KiB = 1024;
// How long the camera must rest before the page asks for what it sees: a
// drag ends with a release, but a wheel zoom is a train of steps, each with
// its own 'end' (about 100 ms apart when scrolled by hand).
const SETTLE_MS = 400;
// The most one view refine with a tolerance may bring: the tolerance is
// what ends it; this only bounds a tolerance too fine for the link.
const VIEW_BUDGET_KIB = 4096;
// The server's largest screen (and so largest useful tolerance), in pixels.
const MAX_SCREEN_PIXELS = 16384;
const wsUrl = `${location.protocol === 'https:' ? 'wss' : 'ws'}://${location.host}/v1/ws`;

let spare = null;     // a decoder worker started ahead of the next stream
let view = null;      // MeshView, null without WebGL
let session = null;   // the current StreamSession
let lastMesh = null;  // what is drawn: {positions, faces, level}
let reference = null; // {meshId, order, decoder, positions: level -> Float32Array} of the complete stream
let streamStarted = 0, firstMeshShown = false, firstTextureShown = false;
let settleTimer = 0;      // the pending "refine where I look"
let viewWanted = false;   // a view refine is owed: after the running request, or the first mesh
let viewRefines = 0;      // refines with a view sent (body[data-view-refines])
let viewBudget = VIEW_BUDGET_KIB * KiB;  // ?view_budget= changes it
let toleranceView = null; // the view of the last request, when it had a tolerance

function setState(state) { document.body.dataset.state = state; }

function showError(message) {
  $('error').textContent = message + (lastMesh ? '\nShowing the last good mesh.' : '');
  $('error').hidden = false;
}

function clearError() { $('error').hidden = true; $('error').textContent = ''; }

function status(text) { $('status').textContent = text; }

function kib(bytes) { return `${(bytes / KiB).toFixed(1)} KiB`; }

function showStats(s) {
  $('r-bytes').textContent = `${s.bytes} B (${kib(s.bytes)})`;
  $('r-bytes').dataset.value = s.bytes;
  $('r-packets').textContent = s.packets;
  $('r-parts').textContent = s.parts;
  $('r-level').textContent = s.level === null ? '–' : `${s.level} of ${s.levels}`;
  $('r-level').dataset.value = s.level ?? '';
  $('r-psnr').textContent = s.psnr === null ? '–' : s.psnr >= 999 ? 'lossless' : `${s.psnr.toFixed(2)} dB`;
  $('r-psnr').dataset.value = s.psnr ?? '';
  const t = s.texture;
  $('r-texture').textContent = t ? `${t.width} × ${t.height} (level ${t.level + 1} of ${t.levels})` : '–';
  $('r-texture').dataset.value = t ? t.width : '';
}

function draw(fitCamera) {
  if (!lastMesh) return;
  const { positions, faces } = lastMesh;
  $('r-size').textContent = `${positions.length / 3} / ${faces.length / 3}`;
  if (!view) return;
  // The mesh's own colours and texture (unless turned off), or the error
  // colours when asked for.
  const attributes = $('attributes').checked;
  let colours = attributes ? lastMesh.colors : null;
  let texture = attributes ? lastMesh.texture : null;
  if ($('errors').checked && reference?.decoder) {
    const level = lastMesh.level;
    const complete = reference.positions.get(level);
    if (complete) {
      colours = errorColours(positions, complete);
      texture = null;
    } else {
      // The complete stream's positions at this level, from its decoder's
      // worker: drawn again when they are here.
      const wanted = reference;
      wanted.decoder.mesh(level).then((mesh) => {
        wanted.positions.set(level, mesh.positions);
        if (reference === wanted) draw(false);
      }, (e) => showError(`error colours unavailable: ${e.message}`));
    }
  }
  view.setMesh(positions, faces, colours, fitCamera || !firstMeshShown, texture);
  // A view refine waited for a mesh to look at.
  if (viewWanted && session && !session.stats.streaming) refineWhereLooking();
  if (!firstMeshShown) {
    firstMeshShown = true;
    stampFrame($('r-first'));
  }
  // The first frame drawn with a texture level applied (the same as the
  // first mesh's when its texture was decoded in time).
  if (!firstTextureShown && texture?.image) {
    firstTextureShown = true;
    stampFrame($('r-first-texture'));
  }
}

// After the frame that shows what was just drawn: its time from the
// stream's start, and from the page's navigation (performance.now()'s
// origin), which counts loading the page, its modules and the decoder too.
function stampFrame(cell) {
  const stream = streamStarted;
  requestAnimationFrame(() => {
    if (stream !== streamStarted) return;  // a new stream began meanwhile
    const now = performance.now();
    cell.textContent = `${(now - stream).toFixed(0)} ms (${now.toFixed(0)} ms after the page opened)`;
    cell.dataset.fromNavigation = now;
    cell.dataset.value = now - stream;
  });
}

function clearFrameStamp(cell) {
  cell.textContent = '–';
  delete cell.dataset.fromNavigation;
  delete cell.dataset.value;
}

function onMesh(mesh) {
  if (!mesh.faces.length) return;
  lastMesh = mesh;
  draw(false);
}

// meshId: the picked mesh, or the one the address names (?mesh=ID), which
// streams while the catalog and the decoder still load (decoder: the
// module, or the promise of it).
function startStream(meshId = $('mesh').value) {
  if (!meshId) return showError('Pick a mesh first (the catalog is empty?).');
  if (session) session.close();
  clearError();
  lastMesh = null;
  firstMeshShown = false;
  firstTextureShown = false;
  clearTimeout(settleTimer);
  // With a tolerance, the view is refined to it as soon as the stream is done.
  viewWanted = $('follow-view').checked && screenError() !== null;
  toleranceView = null;
  clearFrameStamp($('r-first'));
  clearFrameStamp($('r-first-texture'));
  const budgetKiB = parseFloat($('budget').value);
  const rateKiB = parseFloat($('rate').value);
  const request = {
    meshId, order: $('order').value,
    budget: Number.isFinite(budgetKiB) && budgetKiB > 0 ? Math.round(budgetKiB * KiB) : null,
    rate: Number.isFinite(rateKiB) && rateKiB > 0 ? Math.round(rateKiB * KiB) : 0,
  };
  streamStarted = performance.now();
  setState('streaming');
  status(`streaming ${$('mesh').selectedOptions[0]?.textContent ?? meshId} …`);
  $('refine').disabled = true;
  const s = new StreamSession(takeDecoder(), wsUrl, {
    onMesh,
    onProgress: showStats,
    onDone(stats) {
      if (s !== session) return;
      spare ??= new DecoderClient();  // ready for the next stream
      status(stats.complete ? 'complete: the whole stream is here' : 'done; refine for more');
      $('refine').disabled = stats.complete;
      setState('done');
      if ($('errors').checked) ensureReference();
      if (viewWanted) refineWhereLooking();
    },
    onError(message) {
      if (s !== session) return;
      $('refine').disabled = true;
      status('');
      showError(message);
      setState('error');
    },
  });
  session = s;
  s.start(request);
}

function refineBytes() { return Math.round(parseFloat($('refine-kib').value) * KiB); }

// The pixel tolerance of view refines, or null (empty): they bring
// +N KiB instead.
function screenError() {
  const px = parseFloat($('screen-error').value);
  return px > 0 ? Math.min(px, MAX_SCREEN_PIXELS) : null;
}

// Without a view: the server continues the last region asked for, or the
// order. After a view refine with a tolerance, continuing it would bring
// nothing once the view is within it: the view is named again without one,
// N KiB more of what it sees first.
function refine() {
  const extra = refineBytes();
  if (!session || !(extra > 0)) return;
  clearTimeout(settleTimer);
  viewWanted = false;
  $('refine').disabled = true;
  setState('streaming');
  status(`refining by ${kib(extra)} …`);
  session.refine(extra, toleranceView ? { view: toleranceView } : {});
  toleranceView = null;
}

// "refine where I look": the camera has rested SETTLE_MS, or the stream
// is done with a tolerance set. A request still running (the stream, a
// refine) is left to finish, and the camera as it then is asked for after
// its `done`, as it is once a first mesh is in the view; nothing once the
// stream is complete. With a tolerance the server sends what the view needs
// to be within it (up to viewBudget), else N KiB of what it sees first.
function refineWhereLooking() {
  viewWanted = false;
  if (!$('follow-view').checked || !session?.decoder || session.failed) return;
  if (session.stats.streaming) {
    viewWanted = true;
    return;
  }
  if (session.stats.complete) return;
  const camera = view?.viewRegion();
  if (!camera) {
    viewWanted = true;  // draw() asks again with the first mesh in the view
    return;
  }
  const px = screenError();
  const extra = px === null ? refineBytes() : viewBudget;
  if (!(extra > 0)) return;
  $('refine').disabled = true;
  setState('streaming');
  status(px === null ? `refining where you look by ${kib(extra)} …`
                     : `refining where you look to within ${px} px …`);
  showViewRefine(px, extra);
  session.refine(extra, px === null ? { view: camera } : { view: camera, screenError: px });
  toleranceView = px === null ? null : camera;
}

// body[data-view-refines] counts them, body[data-screen-error] is the last
// one's tolerance ('' for one of N KiB).
function showViewRefine(px, extra) {
  document.body.dataset.viewRefines = ++viewRefines;
  document.body.dataset.screenError = px ?? '';
  $('r-view').textContent = `${viewRefines}, the last ${px === null ? `+${kib(extra)}` : `to ${px} px`}`;
}

function onCameraStart() {
  clearTimeout(settleTimer);
  viewWanted = false;
}

function onCameraEnd() {
  clearTimeout(settleTimer);
  if ($('follow-view').checked) settleTimer = setTimeout(refineWhereLooking, SETTLE_MS);
}

async function ensureReference() {
  const meshId = $('mesh').value, order = $('order').value;
  if (reference && reference.meshId === meshId) return draw(false);
  reference?.decoder?.terminate();
  reference = { meshId, order, decoder: null, positions: new Map() };
  status('fetching the complete stream for the error colours …');
  try {
    const decoder = await fetchComplete(wsUrl, meshId, order);
    if (reference.meshId !== meshId) return decoder.terminate();
    reference.decoder = decoder;
    status('error colours: grey = as the complete stream, red ≥ 0.5 % of the diagonal away');
    draw(false);
  } catch (e) {
    reference = null;
    showError(`error colours unavailable: ${e.message}`);
  }
}

async function loadCatalog() {
  const reply = await fetch('/v1/meshes?limit=1000');
  if (!reply.ok) throw new Error(`the catalog request failed: HTTP ${reply.status}`);
  const list = await reply.json();
  const select = $('mesh');
  for (const m of list.meshes ?? []) {
    const option = new Option(`${m.name} (${m.vertices} vertices, ${kib(Number(m.bytes))})`, m.id);
    select.add(option);
  }
  if (!select.options.length) status('the catalog is empty: `meshwave-server ingest` fills it');
}

// The decoder worker started at page load (its module compiles and
// instantiates while the rest of the page loads), then a fresh one per
// stream.
function takeDecoder() {
  const decoder = spare ?? new DecoderClient();
  spare = null;
  return decoder;
}

// ?order=, ?budget=, ?rate=, ?screen_error= fill the form, ?view_budget=
// (KiB) bounds view refines with a tolerance; ?mesh=ID picks the mesh once
// the catalog is here (and streams it at once: main()).
function prefillFromUrl(query) {
  for (const key of ['order', 'budget', 'rate']) if (query.has(key)) $(key).value = query.get(key);
  if (query.has('screen_error')) $('screen-error').value = query.get('screen_error');
  const budgetKiB = parseFloat(query.get('view_budget'));
  if (budgetKiB > 0) viewBudget = Math.round(budgetKiB * KiB);
}

async function createView() {
  try {
    const { MeshView } = await import('./scene.js');
    view = new MeshView($('view'));
    view.onCameraStart = onCameraStart;
    view.onCameraEnd = onCameraEnd;
    draw(true);  // a mesh that arrived before the view
  } catch (e) {
    showError(`3D view unavailable (WebGL?): ${e.message}`);
  }
}

async function main() {
  $('stream').onclick = () => startStream();
  $('refine').onclick = refine;
  $('refine-kib').oninput = () => { $('refine-label').textContent = $('refine-kib').value; };
  $('errors').onchange = () => ($('errors').checked && lastMesh ? ensureReference() : draw(false));
  $('attributes').onchange = () => draw(false);
  // Ticked, or a new tolerance: the view as it is now, refined to it.
  $('follow-view').onchange = () => {
    if (!$('follow-view').checked) onCameraStart();
    else if (screenError() !== null) refineWhereLooking();
  };
  $('screen-error').onchange = () => { if (screenError() !== null) refineWhereLooking(); };
  $('stream').disabled = true;
  const query = new URLSearchParams(location.search);
  prefillFromUrl(query);
  // Everything the first mesh waits for starts now, side by side: the
  // decoder module, the catalog, three.js and, when the address names a
  // mesh, its stream (whose messages wait for the decoder, not the rest).
  spare = new DecoderClient();
  const decoderReady = spare.ready;
  const catalogReady = loadCatalog();
  const viewReady = createView();
  if (query.has('mesh')) startStream(query.get('mesh'));
  try {
    await Promise.all([decoderReady, catalogReady]);
  } catch (e) {
    showError(e.message);
    setState('error');
    return;
  }
  await viewReady;
  if (query.has('mesh')) $('mesh').value = query.get('mesh');
  $('stream').disabled = false;
  if (!session) setState('ready');
}

main();
