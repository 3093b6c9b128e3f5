// One mesh streamed over GET /v1/ws into the WebAssembly decoder, which
// runs on a worker (decoder_client.js): sends `start` and `refine` (a
// refine may name a view or region: the server then sends units, whole
// packets or one precinct's part of a split packet, region first), hands
// every unit to the decoder as it arrives, and reports the decoded mesh at
// most once per animation frame (a burst of small packets is shown as one
// refinement per frame). Any failure — a refused packet, a malformed
// message, a closed socket — stops the session and is reported once; the
// last mesh reported stays the last good one. No DOM here.
import { DecoderClient } from './decoder_client.js';
import { decodeServerMessage, encodeRefine, encodeStart } from './ws_protocol.js';

export class StreamSession {
  // decoder: a DecoderClient of its own (a fresh one when not given).
  // Callbacks:
  //   onMesh({positions, faces, colors, texture, level, levels, psnr,
  //   original}) after new packets (colors: linear RGB per vertex, or null
  //   without a colour channel; texture: {uvs, image} or null, as
  //   MeshView.setMesh takes them; original: the input's own mesh),
  //   onProgress(stats) after every message, onDone(stats) when a
  //   selection is complete, onError(message) once, then nothing more.
  constructor(decoder, wsUrl, { onMesh, onProgress, onDone, onError }) {
    this.callbacks = { onMesh, onProgress, onDone, onError };
    this.decoder = decoder ?? new DecoderClient();
    this.decoder.onState = (state) => this.onState(state);
    this.decoder.onRefused = (what, message) => this.fail(`${what} was refused: ${message}`);
    this.decoder.onFailed = (message) => this.fail(message);
    this.hasHeader = false;
    // packets: Packet messages (units: a whole packet or a part); parts:
    // those that were one precinct's part of a split packet.
    this.stats = { bytes: 0, packets: 0, parts: 0, level: null, levels: null, psnr: null,
                   texture: null, complete: false, streaming: false };
    this.textureLevel = null;  // the level being decoded or shown
    this.textureBitmap = null;
    this.failed = false;
    // Per request awaiting its `done`: whether its `complete` speaks of the
    // whole stream. A refine with a tolerance may end `complete` when its
    // view is within it (nothing more for that request), which says nothing
    // of the rest.
    this.completeMeansStream = [];
    this.dirty = false;       // a mesh is to be reported
    this.meshing = false;     // a mesh request is out
    this.socket = new WebSocket(wsUrl);
    this.socket.binaryType = 'arraybuffer';
    this.opened = new Promise((resolve) => { this.socket.onopen = resolve; });
    this.socket.onmessage = (e) => this.onMessage(e.data);
    this.socket.onclose = (e) => {
      if (this.closing) return;
      this.fail(`the connection to the server closed (code ${e.code}${e.reason ? ', ' + e.reason : ''})` +
                ` after ${this.stats.packets} packets`);
    };
  }

  // budget: container bytes (header included) or null for the whole order;
  // rate: bytes per second, 0 unpaced.
  async start({ meshId, order, budget, rate }) {
    await this.opened;
    this.stats.streaming = true;
    this.completeMeansStream.push(true);
    this.send(encodeStart({ meshId, order, budget, rate }));
  }

  // extraBytes more payload bytes; options {view} (with screenError, pixels:
  // only what the view needs to be within it) or {region} (ws_protocol.js)
  // to refine that first from now on; none: as the last request did.
  refine(extraBytes, options = {}) {
    if (this.failed || !this.hasHeader) return;
    this.stats.streaming = true;
    this.completeMeansStream.push(options.screenError === undefined || options.screenError === null);
    this.send(encodeRefine(extraBytes, options));
  }

  close() {
    this.closing = true;
    this.socket.close(1000);
    this.decoder.onFailed = () => {};
    this.decoder.terminate();
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
      case 'start': {
        const bytes = m.header.length;  // the header's buffer goes to the worker
        this.decoder.open(m.header, () => { this.stats.bytes += bytes; });
        this.hasHeader = true;
        this.scheduleMesh();  // the base mesh, drawn even when no packet fits the budget
        break;
      }
      case 'selection':
        break;
      case 'packet': {
        if (!this.hasHeader) return this.fail('a packet before the stream header');
        const what = m.part === null ? `packet ${m.id}` : `part ${m.part} of packet ${m.id}`;
        const bytes = m.payload.length;  // its buffer goes to the worker
        this.decoder.add(m.id, m.part, m.payload, `${what} (cursor ${m.cursor})`, () => {
          this.stats.bytes += bytes;
          this.stats.packets += 1;
          if (m.part !== null) this.stats.parts += 1;
        });
        this.scheduleMesh();
        break;
      }
      case 'done': {
        const meansStream = this.completeMeansStream.shift() ?? true;
        // Reported once the decoder has taken every packet before it.
        this.decoder.sync().then(() => {
          if (this.failed) return;
          this.stats.streaming = false;
          if (meansStream) this.stats.complete = m.complete;
          this.emitMesh();  // the final state now, not a frame later
          this.callbacks.onDone(this.stats);
          this.callbacks.onProgress(this.stats);
        }, (e) => this.fail(e.message));
        return;
      }
      case 'error':
        this.stats.streaming = false;
        return this.fail(`the server refused the request (${m.codeName}): ${m.message}`);
    }
    this.callbacks.onProgress(this.stats);
  }

  // The decoder's state after a header or packet: level, PSNR, and a
  // texture level newly held.
  onState(state) {
    if (this.failed) return;
    this.stats.levels = state.levels;
    this.stats.level = state.level;
    this.stats.psnr = state.psnr;
    if (state.texture) this.loadTexture(state.texture);
    this.callbacks.onProgress(this.stats);
  }

  // The base colour map's best level held, decoded by the browser
  // (createImageBitmap, off the main thread); it replaces the one shown
  // when decoded, unless a finer level arrived meanwhile.
  loadTexture(image) {
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

  // Asks the decoder for the mesh it holds now (one request at a time: a
  // change meanwhile asks again when it is answered) and reports it, also
  // after a failure (what was accepted before it is the last good mesh).
  emitMesh() {
    if (!this.dirty || !this.hasHeader) return;
    if (this.meshing) return;
    this.dirty = false;
    this.meshing = true;
    this.decoder.mesh().then((mesh) => {
      this.meshing = false;
      this.callbacks.onMesh({
        positions: mesh.positions, faces: mesh.faces, colors: mesh.colors,
        texture: mesh.uvs ? { uvs: mesh.uvs, image: this.textureBitmap ?? null } : null,
        level: mesh.level, levels: mesh.levels, psnr: mesh.psnr, original: mesh.original,
      });
      if (this.dirty) this.emitMesh();
    }, () => { this.meshing = false; });
  }

  fail(message) {
    if (this.failed) return;
    // Packets accepted before the failure are part of the last good mesh.
    this.dirty = true;
    this.emitMesh();
    this.failed = true;
    this.stats.streaming = false;
    this.closing = true;
    if (this.socket.readyState <= WebSocket.OPEN) this.socket.close(1000);
    this.callbacks.onError(message);
  }
}

// The complete stream of a mesh in a decoder of its own (for the error
// colours): resolves to its DecoderClient (mesh(level) gives its positions
// at a level), rejects with a readable Error.
export function fetchComplete(wsUrl, meshId, order) {
  return new Promise((resolve, reject) => {
    const s = new StreamSession(null, wsUrl, {
      onMesh() {}, onProgress() {},
      onDone: () => { s.closing = true; s.socket.close(1000); resolve(s.decoder); },
      onError: (message) => reject(new Error(message)),
    });
    s.start({ meshId, order, budget: null, rate: 0 });
  });
}
