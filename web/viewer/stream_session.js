// One mesh streamed over GET /v1/ws into the WebAssembly decoder: sends
// `start` and `refine` (a refine may name a view or region: the server
// then sends units, whole packets or one precinct's part of a split packet,
// region first), feeds every unit to the decoder as it arrives,
// and reports the decoded mesh at most once per animation frame (the
// decoder copies the whole mesh out, so a burst of small packets is shown
// as one refinement per frame). Any failure — a refused packet, a
// malformed message, a closed socket — stops the session and is reported
// once; the last mesh reported stays the last good one. No DOM here.
import { decodeServerMessage, encodeRefine, encodeStart } from './ws_protocol.js';

export class StreamSession {
  // mw: the decoder module (createMeshwave()). Callbacks:
  //   onMesh({positions, faces, colors, texture, level, levels, psnr})
  //   after new packets (colors: linear RGB per vertex, or null without a
  //   colour channel; texture: {uvs, image} or null, as MeshView.setMesh
  //   takes them),
  //   onProgress(stats) after every message, onDone(stats) when a
  //   selection is complete, onError(message) once, then nothing more.
  // mw may be the promise of the module: the socket opens and the request
  // goes out meanwhile, and the messages wait for it, in order.
  constructor(mw, wsUrl, { onMesh, onProgress, onDone, onError }) {
    this.mw = null;
    this.callbacks = { onMesh, onProgress, onDone, onError };
    this.decoder = null;
    // packets: Packet messages (units: a whole packet or a part); parts:
    // those that were one precinct's part of a split packet.
    this.stats = { bytes: 0, packets: 0, parts: 0, level: null, levels: null, psnr: null,
                   texture: null, complete: false, streaming: false };
    this.textureLevel = null;  // the level being decoded or shown
    this.textureBitmap = null;
    this.failed = false;
    this.dirty = false;
    this.socket = new WebSocket(wsUrl);
    this.socket.binaryType = 'arraybuffer';
    this.opened = new Promise((resolve) => { this.socket.onopen = resolve; });
    this.received = Promise.resolve(mw).then(
      (module) => { this.mw = module; },
      (e) => this.fail(e.message));
    this.socket.onmessage = (e) => this.after(() => this.onMessage(e.data));
    this.socket.onclose = (e) => this.after(() => {
      if (this.closing) return;
      this.fail(`the connection to the server closed (code ${e.code}${e.reason ? ', ' + e.reason : ''})` +
                ` after ${this.stats.packets} packets`);
    });
  }

  // Runs `handle` after the messages before it (and the module).
  after(handle) {
    this.received = this.received.then(handle).catch((e) => this.fail(e.message));
  }

  // budget: container bytes (header included) or null for the whole order;
  // rate: bytes per second, 0 unpaced.
  async start({ meshId, order, budget, rate }) {
    await this.opened;
    this.stats.streaming = true;
    this.send(encodeStart({ meshId, order, budget, rate }));
  }

  // extraBytes more payload bytes; options {view} or {region} (ws_protocol.js)
  // to refine that first from now on; none: as the last request did.
  refine(extraBytes, options = {}) {
    if (this.failed || !this.decoder) return;
    this.stats.streaming = true;
    this.send(encodeRefine(extraBytes, options));
  }

  close() {
    this.closing = true;
    this.socket.close(1000);
    if (this.decoder) this.decoder.delete();
    this.decoder = null;
  }

  send(bytes) {
    if (this.socket.readyState !== WebSocket.OPEN) {
      this.fail('the connection to the server is closed');
      return;
    }
    this.socket.send(bytes);
  }

  onMessage(data) {
    if (this.failed) return;
    if (!(data instanceof ArrayBuffer)) return this.fail('the server sent a text frame');
    let m;
    try {
      m = decodeServerMessage(new Uint8Array(data));
    } catch (e) {
      return this.fail(`the server sent a malformed message: ${e.message}`);
    }
    switch (m.kind) {
      case 'start':
        try {
          this.decoder = new this.mw.Decoder(m.header);
        } catch (e) {
          return this.fail(`the stream header was refused: ${e.message}`);
        }
        this.stats.bytes += m.header.length;
        this.updateLevel();
        this.scheduleMesh();  // the base mesh, drawn even when no packet fits the budget
        break;
      case 'selection':
        break;
      case 'packet':
        if (!this.decoder) return this.fail('a packet before the stream header');
        try {
          if (m.part === null) this.decoder.addPacket(m.id, m.payload);
          else this.decoder.addPacketPart(m.id, m.part, m.payload);
        } catch (e) {
          const what = m.part === null ? `packet ${m.id}` : `part ${m.part} of packet ${m.id}`;
          return this.fail(`${what} (cursor ${m.cursor}) was refused: ${e.message}`);
        }
        this.stats.bytes += m.payload.length;
        this.stats.packets += 1;
        if (m.part !== null) this.stats.parts += 1;
        this.updateLevel();
        this.loadTexture();
        this.scheduleMesh();
        break;
      case 'done':
        this.stats.streaming = false;
        this.stats.complete = m.complete;
        this.emitMesh();  // the final state now, not a frame later
        this.callbacks.onDone(this.stats);
        break;
      case 'error':
        this.stats.streaming = false;
        return this.fail(`the server refused the request (${m.codeName}): ${m.message}`);
    }
    this.callbacks.onProgress(this.stats);
  }

  updateLevel() {
    // The level drawn: one past the finest that received detail (its
    // subdivision smooths the surface; more levels would add faces, not
    // detail), as `meshwave decode` writes it.
    this.stats.levels = this.decoder.levels();
    this.stats.level = Math.min(this.stats.levels, this.decoder.detailLevels() + 1);
    this.stats.psnr = this.decoder.estimatedPsnr();
  }

  // The base colour map's best level held, decoded by the browser
  // (createImageBitmap, off the main thread); it replaces the one shown
  // when decoded, unless a finer level arrived meanwhile.
  loadTexture() {
    if (!this.decoder.hasTexture()) return;
    const image = this.decoder.textureImage(0);
    if (!image || image.level === this.textureLevel) return;
    this.textureLevel = image.level;
    createImageBitmap(new Blob([image.bytes], { type: image.mimeType }),
      { imageOrientation: 'none', premultiplyAlpha: 'none' })
      .then((bitmap) => {
        if (this.failed || this.textureLevel !== image.level) return;
        this.textureBitmap = bitmap;
        this.stats.texture = { width: image.width, height: image.height, level: image.level,
                               levels: image.levels };
        this.callbacks.onProgress(this.stats);
        this.scheduleMesh();
      })
      .catch((e) => this.fail(`texture level ${image.level} (${image.mimeType}) could not be ` +
                              `decoded: ${e.message}`));
  }

  scheduleMesh() {
    if (this.dirty) return;
    this.dirty = true;
    requestAnimationFrame(() => this.emitMesh());
  }

  emitMesh() {
    if (!this.dirty || !this.decoder) return;
    this.dirty = false;
    const level = this.stats.level;
    if (this.decoder.originalReady() && !this.decoder.hasColors() && !this.decoder.hasTexture()) {
      // The stream's last layer: the user's own mesh (docs/FORMAT.md 2.5).
      const original = this.decoder.originalMesh();
      this.callbacks.onMesh({
        positions: original.positions, faces: original.faces, colors: null, texture: null,
        level, levels: this.stats.levels, psnr: this.stats.psnr, original: true,
      });
      return;
    }
    this.callbacks.onMesh({
      positions: this.decoder.positions(level), faces: this.decoder.faces(level),
      colors: this.decoder.hasColors() ? this.decoder.colors(level) : null,
      texture: this.decoder.hasTexture()
        ? { uvs: this.decoder.textureCoordinates(level), image: this.textureBitmap ?? null } : null,
      level,
      levels: this.stats.levels, psnr: this.stats.psnr,
    });
  }

  fail(message) {
    if (this.failed) return;
    // Packets accepted before the failure are part of the last good mesh.
    this.emitMesh();
    this.failed = true;
    this.stats.streaming = false;
    this.closing = true;
    if (this.socket.readyState <= WebSocket.OPEN) this.socket.close(1000);
    this.callbacks.onError(message);
  }
}

// The complete stream of a mesh in a decoder of its own (for the error
// colours): resolves to the decoder, rejects with a readable Error.
export function fetchComplete(mw, wsUrl, meshId, order) {
  return new Promise((resolve, reject) => {
    const s = new StreamSession(mw, wsUrl, {
      onMesh() {}, onProgress() {},
      onDone: () => { s.closing = true; s.socket.close(1000); resolve(s.decoder); },
      onError: (message) => reject(new Error(message)),
    });
    s.start({ meshId, order, budget: null, rate: 0 });
  });
}
