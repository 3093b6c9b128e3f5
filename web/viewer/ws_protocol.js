// The few protobuf messages of the WebSocket endpoint GET /v1/ws
// (proto/websocket.proto, docs/API.md), written and read by hand: the page
// sends one ClientMessage kind per action and reads six ServerMessage
// kinds, which takes a varint reader and a length-delimited field walker —
// smaller to ship and to read than a protobuf library (protobufjs is some
// 80 KB plus its own pinning), and checked byte for byte against protoc in
// tests/browser/ws_protocol_test.mjs. Field numbers are the .proto's.

// --- writing ----------------------------------------------------------

class Writer {
  constructor() { this.bytes = []; }
  varint(n) {
    // Numbers up to 2^53: plenty for budgets and rates.
    let v = BigInt(n);
    do {
      let b = Number(v & 0x7fn);
      v >>= 7n;
      if (v > 0n) b |= 0x80;
      this.bytes.push(b);
    } while (v > 0n);
    return this;
  }
  tag(field, wire) { return this.varint(field * 8 + wire); }
  uint(field, n) { return this.tag(field, 0).varint(n); }
  bool(field, b) { return b ? this.uint(field, 1) : this; }
  double(field, x) {
    const b = new Uint8Array(8);
    new DataView(b.buffer).setFloat64(0, x, true);
    this.tag(field, 1);
    for (const byte of b) this.bytes.push(byte);
    return this;
  }
  bytesField(field, u8) {
    this.tag(field, 2).varint(u8.length);
    for (const b of u8) this.bytes.push(b);
    return this;
  }
  string(field, s) { return this.bytesField(field, new TextEncoder().encode(s)); }
  message(field, w) { return this.bytesField(field, Uint8Array.from(w.bytes)); }
  finish() { return Uint8Array.from(this.bytes); }
}

// The text forms of a region request (docs/API.md, "Region requests"):
// a sphere {centre: [x, y, z], radius} as "x,y,z,r"; a view {eye: [x, y, z],
// direction: [x, y, z], fov (vertical, degrees), width, height (pixels)} as
// "ex,ey,ez,dx,dy,dz,fov,width,height". Numbers as JS prints them (the
// shortest that reads back, which the server's from_chars reads); a
// non-finite one, a radius <= 0, a fov outside (0, 180) or a screen size
// that is no whole number in [1, 16384] is a RangeError here rather than
// a BAD_REQUEST later.
function finite(x, what) {
  if (typeof x !== 'number' || !Number.isFinite(x)) {
    throw new RangeError(`${what} ${x} is not a finite number`);
  }
  return String(x);
}
function pixels(n, what) {
  if (!Number.isInteger(n) || n < 1 || n > 16384) {
    throw new RangeError(`${what} ${n} is not a whole number of pixels in [1, 16384]`);
  }
  return String(n);
}
export function sphereText({ centre, radius }) {
  if (!(radius > 0)) throw new RangeError(`region radius ${radius} is not > 0`);
  return [...centre.map((x) => finite(x, 'region centre')), finite(radius, 'region radius')].join(',');
}
export function viewText({ eye, direction, fov, width, height }) {
  if (direction.every((x) => x === 0)) throw new RangeError('view direction is zero');
  if (!(fov > 0 && fov < 180)) throw new RangeError(`view fov ${fov} is not in (0, 180) degrees`);
  return [...eye.map((x) => finite(x, 'view eye')), ...direction.map((x) => finite(x, 'view direction')),
    finite(fov, 'view fov'), pixels(width, 'view width'), pixels(height, 'view height')].join(',');
}
function regionFields(w, { region, view, screenError }, [regionField, viewField, errorField]) {
  if (region) w.string(regionField, sphereText(region));
  if (view) w.string(viewField, viewText(view));
  if (screenError !== null && screenError !== undefined) w.double(errorField, screenError);
}
function atMostOne(what, values) {
  if (values.filter(Boolean).length > 1) throw new TypeError(`at most one of ${what}`);
}

// ClientMessage{start: StreamRequest}. budget and maxLevel: null for absent
// (proto3 `optional`); rate 0 for unpaced. region or view (objects as
// above; then no order) make the session count units, region first;
// screenError (pixels) goes with a view.
export function encodeStart({ meshId, order = '', maxLevel = null, budget = null, rate = 0,
                              headerOnly = false, region = null, view = null, screenError = null }) {
  atMostOne('order, region and view', [order, region, view]);
  const req = new Writer();
  req.string(1, meshId);
  if (order) req.string(2, order);
  if (maxLevel !== null) req.uint(3, maxLevel);
  if (budget !== null) req.uint(4, budget);
  if (rate) req.uint(5, rate);
  req.bool(6, headerOnly);
  regionFields(req, { region, view, screenError }, [7, 8, 9]);
  return new Writer().message(1, req).finish();
}

// ClientMessage{refine: Refine}: extraBytes more payload bytes; with a
// region, a view or an order, what the rest of the stream refines first
// (at most one of them; none: as before).
export function encodeRefine(extraBytes, { region = null, view = null, screenError = null,
                                           order = '' } = {}) {
  atMostOne('region, view and order', [region, view, order]);
  const refine = new Writer().uint(1, extraBytes);
  regionFields(refine, { region, view, screenError }, [2, 3, 4]);
  if (order) refine.string(5, order);
  return new Writer().message(2, refine).finish();
}

// --- reading ----------------------------------------------------------

export class ProtocolError extends Error {}

class Reader {
  constructor(u8) { this.u8 = u8; this.pos = 0; }
  done() { return this.pos >= this.u8.length; }
  varint() {
    let v = 0n, shift = 0n;
    for (;;) {
      if (this.pos >= this.u8.length) throw new ProtocolError('truncated varint');
      const b = this.u8[this.pos++];
      v |= BigInt(b & 0x7f) << shift;
      if (!(b & 0x80)) break;
      shift += 7n;
      if (shift > 63n) throw new ProtocolError('varint longer than 10 bytes');
    }
    return v;
  }
  // Every field of the message as {field, wire, value}: value is a BigInt
  // for varints, a Uint8Array (a view, no copy) for length-delimited.
  *fields() {
    while (!this.done()) {
      const key = this.varint();
      const field = Number(key >> 3n), wire = Number(key & 7n);
      if (wire === 0) {
        yield { field, wire, value: this.varint() };
      } else if (wire === 2) {
        const len = Number(this.varint());
        if (len > this.u8.length - this.pos) throw new ProtocolError('field longer than the message');
        yield { field, wire, value: this.u8.subarray(this.pos, this.pos + len) };
        this.pos += len;
      } else if (wire === 1) {
        this.skip(8);
      } else if (wire === 5) {
        this.skip(4);
      } else {
        throw new ProtocolError(`unsupported wire type ${wire}`);
      }
    }
  }
  skip(n) {
    if (n > this.u8.length - this.pos) throw new ProtocolError('truncated fixed field');
    this.pos += n;
  }
}

// Reads `u8` into an object: spec maps field number to [name, kind] where
// kind is 'uint' (a Number), 'bool', 'bytes', 'string' or a nested spec.
function readMessage(u8, spec) {
  const out = {};
  for (const { field, wire, value } of new Reader(u8).fields()) {
    const entry = spec[field];
    if (!entry) continue;  // unknown fields are skipped, as protobuf does
    const [name, kind] = entry;
    const want = kind === 'uint' || kind === 'bool' ? 0 : 2;
    if (wire !== want) throw new ProtocolError(`field ${name} has wire type ${wire}`);
    if (kind === 'uint') out[name] = Number(value);
    else if (kind === 'bool') out[name] = value !== 0n;
    else if (kind === 'bytes') out[name] = value;
    else if (kind === 'string') out[name] = new TextDecoder().decode(value);
    else out[name] = readMessage(value, kind);
  }
  return out;
}

const Selection = {
  1: ['fromCursor', 'uint'], 2: ['nextCursor', 'uint'], 3: ['orderPackets', 'uint'],
  4: ['bytes', 'uint'],
};
const ServerMessage = {
  1: ['start', { 1: ['header', 'bytes'], 2: ['selection', Selection] }],
  2: ['selection', Selection],
  // part (proto3 `optional`) comes before payload on the wire: fields are
  // read in any order.
  3: ['packet', { 1: ['cursor', 'uint'], 2: ['id', 'uint'], 3: ['payload', 'bytes'],
                  4: ['part', 'uint'] }],
  4: ['done', { 1: ['nextCursor', 'uint'], 2: ['complete', 'bool'] }],
  5: ['error', { 1: ['code', 'uint'], 2: ['message', 'string'] }],
};
export const ErrorCodes = ['CODE_UNSPECIFIED', 'BAD_REQUEST', 'NOT_FOUND', 'UNAVAILABLE'];

// A ServerMessage as {kind, ...fields of that kind} with proto3 defaults
// filled in; a packet's `part` is null when absent (a whole packet).
// ProtocolError for bytes that are no ServerMessage.
export function decodeServerMessage(u8) {
  const m = readMessage(u8, ServerMessage);
  const kinds = Object.keys(m);
  if (kinds.length !== 1) throw new ProtocolError(`a server message with ${kinds.length} kinds`);
  const kind = kinds[0];
  const body = m[kind];
  const sel = (s = {}) => ({ fromCursor: 0, nextCursor: 0, orderPackets: 0, bytes: 0, ...s });
  switch (kind) {
    case 'start':
      return { kind, header: body.header ?? new Uint8Array(0), selection: sel(body.selection) };
    case 'selection': return { kind, selection: sel(body) };
    case 'packet':
      return { kind, cursor: 0, id: 0, ...body, part: body.part ?? null,
               payload: body.payload ?? new Uint8Array(0) };
    case 'done': return { kind, nextCursor: 0, complete: false, ...body };
    default: {
      const code = body.code ?? 0;
      return { kind, code, codeName: ErrorCodes[code] ?? `code ${code}`, message: body.message ?? '' };
    }
  }
}
