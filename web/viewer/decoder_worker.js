// The WebAssembly decoder on a thread of its own (a module worker), so that
// the page never stalls on a decode and the module compiles and
// instantiates beside three.js: decoder_client.js is the page's side.
// Requests are handled one at a time, in the order they were posted, and
// each is answered with its `seq`:
//   {ping}                       -> {}             (the module is ready)
//   {open, header}               -> state          (the stream header)
//   {add, id, part, payload}     -> state          (a packet, or a part of one)
//   {sync}                       -> state          (after all the above)
//   {mesh, level}                -> mesh           (level: undefined for the
//                                                   level the page draws)
// state: {levels, level, psnr, texture} (texture: a map level newly held,
// as decoder.textureImage gives it, else null); mesh: {positions, faces,
// colors, uvs, level, levels, psnr, original}, its arrays transferred. A
// refused request is answered {refused: message}; after a refused header or
// packet no other is taken (the mesh stays what was accepted before it).
// When the module cannot load, every request is answered {failed: message}.
let decoder = null;
let textureLevel = null;
let refusal = null;  // why a header or packet was refused

// The module, or null when it could not load (`failure` says why).
let failure = null;
const module = import('./meshwave_decoder.js')
  .then(({ default: createMeshwave }) => createMeshwave())
  .catch((error) => {
    failure = error.message || String(error);
    return null;
  });

// The level the page draws: one past the finest that received detail (its
// subdivision smooths the surface; more would add faces, not detail), as
// `meshwave decode` writes it.
function drawnLevel() {
  return Math.min(decoder.levels(), decoder.detailLevels() + 1);
}

function state() {
  const out = { levels: decoder.levels(), level: drawnLevel(), psnr: decoder.estimatedPsnr(),
                texture: null };
  // The base colour map's finest level held, once per level.
  const image = decoder.hasTexture() ? decoder.textureImage(0) : null;
  if (image && image.level !== textureLevel) {
    textureLevel = image.level;
    out.texture = image;
  }
  return out;
}

function mesh(level) {
  const drawn = level ?? drawnLevel();
  const reply = { level: drawn, levels: decoder.levels(), psnr: decoder.estimatedPsnr(),
                  original: false, colors: null, uvs: null };
  if (level === undefined && decoder.originalReady() && !decoder.hasColors() &&
      !decoder.hasTexture()) {
    // The stream's last layer: the user's own mesh (docs/FORMAT.md 2.5).
    const original = decoder.originalMesh();
    return { ...reply, positions: original.positions, faces: original.faces, original: true };
  }
  return {
    ...reply,
    positions: decoder.positions(drawn), faces: decoder.faces(drawn),
    colors: decoder.hasColors() ? decoder.colors(drawn) : null,
    uvs: decoder.hasTexture() ? decoder.textureCoordinates(drawn) : null,
  };
}

function handle(mw, request) {
  if (request.ping) return {};
  if ((request.open || request.add) && refusal) {
    throw new Error(`not decoded after an earlier refusal (${refusal})`);
  }
  try {
    return take(mw, request);
  } catch (error) {
    if (request.open || request.add) refusal = error.message || String(error);
    throw error;
  }
}

function take(mw, request) {
  if (request.open) {
    decoder?.delete();
    decoder = new mw.Decoder(request.header);
    textureLevel = null;
    return { state: state() };
  }
  if (!decoder) throw new Error('no stream header yet');
  if (request.add) {
    if (request.part === null) decoder.addPacket(request.id, request.payload);
    else decoder.addPacketPart(request.id, request.part, request.payload);
    return { state: state() };
  }
  if (request.sync) return { state: state() };
  if (request.mesh) return { mesh: mesh(request.level) };
  throw new Error('unknown request');
}

function transfers(reply) {
  const out = [];
  const m = reply.mesh;
  if (m) for (const a of [m.positions, m.faces, m.colors, m.uvs]) if (a) out.push(a.buffer);
  if (reply.state?.texture) out.push(reply.state.texture.bytes.buffer);
  return out;
}

let queue = module;
self.onmessage = (e) => {
  const request = e.data;
  queue = queue.then((mw) => {
    if (!mw) {
      self.postMessage({ seq: request.seq, failed: failure });
      return mw;
    }
    let reply;
    try {
      reply = handle(mw, request);
    } catch (error) {
      reply = { refused: error.message || String(error) };
    }
    self.postMessage({ seq: request.seq, ...reply }, transfers(reply));
    return mw;
  });
};
