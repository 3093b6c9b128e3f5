// The page's side of decoder_worker.js: the WebAssembly decoder of one
// stream on a worker thread. Requests go out in order and are answered in
// order; `open` and `add` need no waiting (each calls its `accepted` once
// taken, then onState; a refusal goes to onRefused, and the decoder takes
// nothing more), `sync` and `mesh` return promises. A worker that cannot load the decoder module fails every
// request with a message that says so.
const MODULE_ERROR = 'the WebAssembly decoder (meshwave_decoder.js and meshwave_decoder.wasm) ' +
                     "could not be loaded; the server's viewer directory must hold it: ";

export class DecoderClient {
  constructor() {
    this.worker = new Worker(new URL('./decoder_worker.js', import.meta.url), { type: 'module' });
    this.seq = 0;
    this.pending = new Map();  // seq -> {resolve, reject} or {what} of a request not awaited
    this.onState = () => {};
    this.onRefused = () => {};  // (what, message): a packet or header refused
    this.onFailed = () => {};   // (message): the decoder is gone, once
    this.worker.onmessage = (e) => this.onReply(e.data);
    this.worker.onerror = (e) => {
      e.preventDefault();
      this.failAll(MODULE_ERROR + (e.message || 'the worker did not start'));
    };
    // Resolves once the module is instantiated; rejects with a readable Error.
    this.ready = this.request({ ping: true });
  }

  // The stream header (Uint8Array): a new stream in this decoder.
  open(header, accepted) {
    this.post({ open: true, header }, 'the stream header', header, accepted);
  }

  // A packet (part: null) or a precinct's part of one; `what` names it in a
  // refusal.
  add(id, part, payload, what, accepted) {
    this.post({ add: true, id, part, payload }, what, payload, accepted);
  }

  // The state once everything posted before is decoded.
  sync() { return this.request({ sync: true }); }

  // The mesh at `level` (undefined: the level the page draws, or the
  // original once it is held), with its arrays.
  mesh(level) { return this.request({ mesh: true, level }); }

  terminate() {
    this.worker.terminate();
    this.failAll('the decoder was closed');
  }

  post(request, what, bytes, accepted) {
    const seq = ++this.seq;
    this.pending.set(seq, { what, accepted });
    // The bytes' buffer goes over (the page keeps no reference to it).
    this.worker.postMessage({ seq, ...request }, [bytes.buffer]);
  }

  request(request) {
    const seq = ++this.seq;
    const reply = new Promise((resolve, reject) => this.pending.set(seq, { resolve, reject }));
    if (this.failure) this.onReply({ seq, failed: this.failure });
    else this.worker.postMessage({ seq, ...request });
    return reply;
  }

  onReply(reply) {
    const waiting = this.pending.get(reply.seq);
    this.pending.delete(reply.seq);
    if (reply.failed !== undefined) {
      this.failAll(MODULE_ERROR + reply.failed, waiting);
      return;
    }
    if (reply.state) {
      waiting?.accepted?.();
      this.onState(reply.state);
    }
    if (reply.refused !== undefined) {
      if (waiting?.reject) waiting.reject(new Error(reply.refused));
      else this.onRefused(waiting?.what ?? 'a request', reply.refused);
      return;
    }
    waiting?.resolve?.(reply.state ?? reply.mesh ?? {});
  }

  failAll(message, first = null) {
    const news = this.failure === undefined;
    this.failure ??= message;
    const error = new Error(this.failure);
    for (const w of [first, ...this.pending.values()]) w?.reject?.(error);
    this.pending.clear();
    if (news) this.onFailed(this.failure);
  }
}
