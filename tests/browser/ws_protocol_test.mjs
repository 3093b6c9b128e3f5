// web/viewer/ws_protocol.js against protoc: what the page sends is byte for
// byte protoc's encoding of the same ClientMessage (region requests too:
// view, region, screen_error, a refine's order), and what protoc encodes
// as a ServerMessage the page reads back field for field, a Packet's part
// also when written before the payload as the server does; malformed
// bytes are a ProtocolError, never a wrong message.
//
// node ws_protocol_test.mjs PROTO_DIR
import assert from 'node:assert/strict';
import { execFileSync } from 'node:child_process';
import test from 'node:test';
import { ProtocolError, decodeServerMessage, encodeRefine, encodeStart, viewText } from
  '../../web/viewer/ws_protocol.js';

const protoDir = process.argv[2];
const encode = (type, text) => new Uint8Array(execFileSync('protoc', [`--proto_path=${protoDir}`,
  `--encode=meshwave.proto.${type}`, 'websocket.proto'], { input: text }));

test('start messages equal protoc\'s', () => {
  assert.deepEqual(encodeStart({ meshId: '0123456789ab', order: 'rd', budget: 6144, rate: 0 }),
    encode('ClientMessage', 'start { mesh_id: "0123456789ab" order: "rd" budget: 6144 }'));
  assert.deepEqual(encodeStart({ meshId: 'abcdefabcdef', order: 'quality', maxLevel: 0,
    budget: 2 ** 50, rate: 1048576, headerOnly: false }),
  encode('ClientMessage', 'start { mesh_id: "abcdefabcdef" order: "quality" max_level: 0 ' +
    'budget: 1125899906842624 rate: 1048576 }'));
  // An absent budget (the whole order) is not budget 0.
  assert.deepEqual(encodeStart({ meshId: 'abcdefabcdef', budget: null }),
    encode('ClientMessage', 'start { mesh_id: "abcdefabcdef" }'));
  assert.deepEqual(encodeStart({ meshId: 'abcdefabcdef', headerOnly: true }),
    encode('ClientMessage', 'start { mesh_id: "abcdefabcdef" header_only: true }'));
});

test('refine messages equal protoc\'s', () => {
  for (const n of [1, 127, 128, 4096, 300000, 2 ** 40]) {
    assert.deepEqual(encodeRefine(n), encode('ClientMessage', `refine { extra_bytes: ${n} }`));
  }
});

// A camera as the viewer sends it: fractional, negative, tiny numbers.
const camera = { eye: [0.125, -2.5, 1e-7], direction: [-0.6, 0, -0.8], fov: 40, width: 960,
                 height: 640 };
const cameraText = '0.125,-2.5,1e-7,-0.6,0,-0.8,40,960,640';

test('region requests equal protoc\'s', () => {
  assert.equal(viewText(camera), cameraText);
  assert.deepEqual(encodeStart({ meshId: '0123456789ab', budget: 6144, view: camera }),
    encode('ClientMessage', `start { mesh_id: "0123456789ab" budget: 6144 view: "${cameraText}" }`));
  assert.deepEqual(encodeStart({ meshId: '0123456789ab', view: camera, screenError: 1.5 }),
    encode('ClientMessage', `start { mesh_id: "0123456789ab" view: "${cameraText}" screen_error: 1.5 }`));
  assert.deepEqual(encodeStart({ meshId: '0123456789ab', region: { centre: [0.1, 0.2, -3], radius: 0.25 } }),
    encode('ClientMessage', 'start { mesh_id: "0123456789ab" region: "0.1,0.2,-3,0.25" }'));
  assert.deepEqual(encodeRefine(8192, { view: camera }),
    encode('ClientMessage', `refine { extra_bytes: 8192 view: "${cameraText}" }`));
  assert.deepEqual(encodeRefine(8192, { view: camera, screenError: 0.5 }),
    encode('ClientMessage', `refine { extra_bytes: 8192 view: "${cameraText}" screen_error: 0.5 }`));
  assert.deepEqual(encodeRefine(100, { region: { centre: [1, 2, 3], radius: 4 } }),
    encode('ClientMessage', 'refine { extra_bytes: 100 region: "1,2,3,4" }'));
  assert.deepEqual(encodeRefine(100, { order: 'rd' }),
    encode('ClientMessage', 'refine { extra_bytes: 100 order: "rd" }'));
  // No options: the plain refine (continues the last region or order).
  assert.deepEqual(encodeRefine(100, {}), encode('ClientMessage', 'refine { extra_bytes: 100 }'));
});

test('region requests the server would refuse are refused here', () => {
  const bad = [
    { ...camera, fov: 180 }, { ...camera, fov: 0 }, { ...camera, width: 0 },
    { ...camera, height: 16385 }, { ...camera, width: 10.5 }, { ...camera, direction: [0, 0, 0] },
    { ...camera, eye: [NaN, 0, 0] }, { ...camera, direction: [Infinity, 0, 1] },
  ];
  for (const view of bad) assert.throws(() => encodeRefine(1, { view }), RangeError, JSON.stringify(view));
  assert.throws(() => encodeRefine(1, { region: { centre: [0, 0, 0], radius: 0 } }), RangeError);
  assert.throws(() => encodeRefine(1, { view: camera, order: 'rd' }), TypeError);
  assert.throws(() => encodeStart({ meshId: '0123456789ab', order: 'quality', view: camera }), TypeError);
});

test('server messages read back', () => {
  const start = decodeServerMessage(encode('ServerMessage',
    'start { header: "\\001\\002\\377" selection { from_cursor: 0 next_cursor: 7 order_packets: 40 bytes: 6100 } }'));
  assert.equal(start.kind, 'start');
  assert.deepEqual([...start.header], [1, 2, 255]);
  assert.deepEqual(start.selection, { fromCursor: 0, nextCursor: 7, orderPackets: 40, bytes: 6100 });

  const packet = decodeServerMessage(encode('ServerMessage',
    'packet { cursor: 3 id: 200 payload: "abc" }'));
  assert.equal(packet.kind, 'packet');
  assert.equal(packet.cursor, 3);
  assert.equal(packet.id, 200);
  assert.equal(new TextDecoder().decode(packet.payload), 'abc');
  assert.equal(packet.part, null, 'a whole packet has no part');

  // A part of a split packet: protoc writes part after payload, the server
  // before it (the payload goes last, uncopied); both read the same.
  for (const part of [0, 1, 300]) {
    const protoc = decodeServerMessage(encode('ServerMessage',
      `packet { cursor: 3 id: 200 payload: "abc" part: ${part} }`));
    const partVarint = part < 128 ? [part] : [(part & 0x7f) | 0x80, part >> 7];
    const inner = [0x08, 3, 0x10, 0xc8, 0x01, 0x20, ...partVarint, 0x1a, 3, 0x61, 0x62, 0x63];
    const server = decodeServerMessage(Uint8Array.from([0x1a, inner.length, ...inner]));
    for (const m of [protoc, server]) {
      assert.equal(m.kind, 'packet');
      assert.equal(m.cursor, 3);
      assert.equal(m.id, 200);
      assert.equal(m.part, part);
      assert.equal(new TextDecoder().decode(m.payload), 'abc');
    }
  }

  // Zero-valued fields are absent on the wire: the defaults are filled in.
  const first = decodeServerMessage(encode('ServerMessage', 'packet { payload: "x" }'));
  assert.equal(first.cursor, 0);
  assert.equal(first.id, 0);

  assert.deepEqual(decodeServerMessage(encode('ServerMessage', 'done { next_cursor: 9 complete: true }')),
    { kind: 'done', nextCursor: 9, complete: true });
  assert.deepEqual(decodeServerMessage(encode('ServerMessage', 'done { }')),
    { kind: 'done', nextCursor: 0, complete: false });
  assert.deepEqual(decodeServerMessage(encode('ServerMessage', 'selection { from_cursor: 7 next_cursor: 9 bytes: 300 }')),
    { kind: 'selection', selection: { fromCursor: 7, nextCursor: 9, orderPackets: 0, bytes: 300 } });
  assert.deepEqual(decodeServerMessage(encode('ServerMessage', 'error { code: NOT_FOUND message: "no mesh" }')),
    { kind: 'error', code: 2, codeName: 'NOT_FOUND', message: 'no mesh' });
});

test('malformed bytes are a ProtocolError', () => {
  const good = encode('ServerMessage', 'packet { cursor: 3 id: 200 payload: "abcdef" }');
  for (let cut = 1; cut < good.length; ++cut) {
    assert.throws(() => decodeServerMessage(good.subarray(0, cut)), ProtocolError, `cut at ${cut}`);
  }
  // A part, before the payload as the server writes it.
  const inner = [0x08, 3, 0x10, 0xc8, 0x01, 0x20, 0x85, 0x02, 0x1a, 3, 0x61, 0x62, 0x63];
  const part = Uint8Array.from([0x1a, inner.length, ...inner]);
  assert.equal(decodeServerMessage(part).part, 261);
  for (let cut = 1; cut < part.length; ++cut) {
    assert.throws(() => decodeServerMessage(part.subarray(0, cut)), ProtocolError, `part cut at ${cut}`);
  }
  // part with the wrong wire type.
  assert.throws(() => decodeServerMessage(Uint8Array.from([0x1a, 3, 0x22, 1, 0])), ProtocolError);
  assert.throws(() => decodeServerMessage(new Uint8Array([0x0b])), ProtocolError);  // wire type 3
  assert.throws(() => decodeServerMessage(new Uint8Array(11).fill(0xff)), ProtocolError);
  assert.throws(() => decodeServerMessage(new Uint8Array(0)), ProtocolError);  // no kind
  // A varint where a message belongs.
  assert.throws(() => decodeServerMessage(new Uint8Array([0x18, 0x01])), ProtocolError);
});
