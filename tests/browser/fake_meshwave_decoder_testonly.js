// TEST ONLY — NOT THE DECODER. A stand-in for meshwave_decoder.js (the
// WebAssembly decoder, built from the decoder-only library) with its API,
// which decodes nothing: it counts the packets and bytes it is given and
// shows a tetrahedron whose apex moves with them. It exists only to exercise the
// page's wiring (socket, readouts, redraws, error display) where the real
// module has not been built; the browser test refuses it (see
// viewer_test.mjs) and never counts as a pass with it.
export const isFakeTestOnly = true;

class Decoder {
  constructor(header) {
    if (!(header instanceof Uint8Array) || header.length === 0) throw new Error('empty header');
    this.ids = new Set();
    this.bytes = 0;
  }
  packetCount() { return 1 << 20; }
  dependenciesMet() { return true; }
  hasPacket(id) { return this.ids.has(id); }
  addPacket(id, payload) {
    if (this.ids.has(id)) throw new Error(`packet ${id} is already decoded`);
    this.ids.add(id);
    this.bytes += payload.length;
  }
  // Parts count as units of their own here (key `id.part`).
  partCount() { return 1 << 10; }
  hasPart(id, part) { return this.ids.has(id) || this.ids.has(`${id}.${part}`); }
  partDependenciesMet() { return true; }
  addPacketPart(id, part, payload) {
    if (this.hasPart(id, part)) throw new Error(`part ${part} of packet ${id} is already decoded`);
    this.ids.add(`${id}.${part}`);
    this.bytes += payload.length;
  }
  positions() {
    // The apex leans over as packets arrive: a visible change, same size.
    const t = 0.3 * Math.min(1, this.ids.size / 25);
    return Float32Array.from([0, 0, 0, 1, 0, 0, 0, 1, 0, t, t, 1]);
  }
  faces() { return Uint32Array.from([0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3]); }
  hasColors() { return false; }
  colors() { return new Float32Array(0); }
  hasTexture() { return false; }
  originalReady() { return false; }
  level() { return 0; }
  detailLevels() { return 0; }
  levels() { return 0; }
  estimatedPsnr() { return 0; }
  packetsDecoded() { return this.ids.size; }
  payloadBytesDecoded() { return this.bytes; }
  delete() {}
}

export default async function createMeshwave() { return { Decoder }; }
