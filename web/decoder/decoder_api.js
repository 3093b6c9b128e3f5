// The JavaScript decoder API (docs/API.md, "JavaScript decoder"), appended
// inside the emscripten module with --post-js: Module.Decoder wraps the
// embind class RawDecoder (decoder_bindings.cpp), turning its error
// messages into thrown Errors and its arguments into the types it takes.
//
//   import createMeshwave from './meshwave_decoder.js';
//   const mw = await createMeshwave();
//   const dec = new mw.Decoder(headerBytes);  // Uint8Array | ArrayBuffer
//   dec.addPacket(id, payload);               // throws Error(message)
//   dec.addPacketPart(id, part, payload);     // one precinct's part of a split packet
//   dec.positions(); dec.faces(); dec.colors(); ... dec.delete();
//   const { header, packets } = mw.parseContainer(mwvBytes);  // .mwv files
(function () {
  function bytes(data, what) {
    if (data instanceof Uint8Array) return data;
    if (data instanceof ArrayBuffer) return new Uint8Array(data);
    if (ArrayBuffer.isView(data)) {
      return new Uint8Array(data.buffer, data.byteOffset, data.byteLength);
    }
    throw new TypeError(what + ' must be a Uint8Array or an ArrayBuffer');
  }
  function uint32(value, what) {
    if (!Number.isInteger(value) || value < 0 || value > 0xffffffff) {
      throw new Error(what + ' ' + value + ' is not an integer in [0, 2^32)');
    }
    return value;
  }
  function id(value) { return uint32(value, 'packet id'); }
  function part(value) { return uint32(value, 'part'); }
  function level(value) {
    return value === undefined ? -1 : Math.trunc(value);
  }

  class Decoder {
    constructor(headerBytes) {
      const raw = new Module['RawDecoder']();
      const error = raw['open'](bytes(headerBytes, 'the header'));
      if (error) {
        raw['delete']();
        throw new Error(error);
      }
      this.raw_ = raw;
    }
    packetCount() { return this.live_()['packetCount'](); }
    dependenciesMet(packet) { return this.live_()['dependenciesMet'](id(packet)); }
    hasPacket(packet) { return this.live_()['hasPacket'](id(packet)); }
    addPacket(packet, payload) {
      const error = this.live_()['addPacket'](id(packet), bytes(payload, 'the payload'));
      if (error) throw new Error(error);
    }
    // Split packets (docs/FORMAT.md 2.2), precinct by precinct: 0 for a
    // packet that is not split.
    partCount(packet) { return this.live_()['partCount'](id(packet)); }
    hasPart(packet, p) { return this.live_()['hasPart'](id(packet), part(p)); }
    partDependenciesMet(packet, p) {
      return this.live_()['partDependenciesMet'](id(packet), part(p));
    }
    addPacketPart(packet, p, payload) {
      const error = this.live_()['addPacketPart'](id(packet), part(p), bytes(payload, 'the payload'));
      if (error) throw new Error(error);
    }
    positions(maxLevel) { return this.live_()['positions'](level(maxLevel)); }
    // The decoder's float64 values (tests compare them with the native decoder).
    positions64(maxLevel) { return this.live_()['positions64'](level(maxLevel)); }
    faces(maxLevel) { return this.live_()['faces'](level(maxLevel)); }
    // The original layer (format 10): whether the user's own mesh is held,
    // and that mesh: {positions: Float32Array, faces: Uint32Array}.
    originalReady() { return this.live_()['originalReady'](); }
    originalMesh() { return this.live_()['originalMesh'](); }
    // Vertex colours (format 8's colour channel): linear RGB in [0, 1] per
    // vertex of positions(maxLevel), interleaved; empty without a channel.
    hasColors() { return this.live_()['hasColors'](); }
    colors(maxLevel) { return this.live_()['colors'](level(maxLevel)); }
    colors64(maxLevel) { return this.live_()['colors64'](level(maxLevel)); }
    // The texture (format 9): u, v per face corner of faces(maxLevel)
    // (Float32Array, empty without a texture), and a map's finest level
    // held: {bytes: Uint8Array (JPEG or PNG), mimeType, width, height,
    // level, levels} or null. role: 0 base colour, 1 metallic-roughness,
    // 2 normal, 3 occlusion, 4 emissive.
    hasTexture() { return this.live_()['hasTexture'](); }
    textureCoordinates(maxLevel) { return this.live_()['textureCoordinates'](level(maxLevel)); }
    textureImage(role = 0) { return this.live_()['textureImage'](uint32(role, 'role')); }
    level() { return this.live_()['level'](); }
    // The finest level that received detail: positions(detailLevels() + 1)
    // is the smallest mesh that shows it smoothed (docs/API.md).
    detailLevels() { return this.live_()['detailLevels'](); }
    levels() { return this.live_()['levels'](); }
    estimatedPsnr() { return this.live_()['estimatedPsnr'](); }
    packetsDecoded() { return this.live_()['packetsDecoded'](); }
    payloadBytesDecoded() { return this.live_()['payloadBytesDecoded'](); }
    delete() {
      if (this.raw_) this.raw_['delete']();
      this.raw_ = null;
    }
    live_() {
      if (!this.raw_) throw new Error('the decoder was deleted');
      return this.raw_;
    }
  }
  Module['Decoder'] = Decoder;

  // A .mwv container (whole or cut short, Uint8Array | ArrayBuffer):
  // {header: Uint8Array (StreamHeader bytes, `present` dropped),
  //  packets: [{id, payload: Uint8Array view into `data`}] (whole ones, in
  //  the container's order), missingBytes}. Throws Error(message) on a
  //  container that does not parse.
  Module['parseContainer'] = function (data) {
    const b = bytes(data, 'the container');
    const raw = Module['parseContainerRaw'](b);
    if (raw['error'] !== undefined) throw new Error(raw['error']);
    const packets = [];
    for (let i = 0; i < raw['ids'].length; ++i) {
      const at = raw['offsets'][i];
      packets.push({ id: raw['ids'][i], payload: b.subarray(at, at + raw['lengths'][i]) });
    }
    return { header: raw['header'], packets, missingBytes: raw['missingBytes'] };
  };
})();
