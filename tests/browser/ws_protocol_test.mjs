// web/viewer/ws_protocol.js against protoc: what the page sends is byte for
// byte protoc's encoding of the same ClientMessage, and what protoc encodes
// as a ServerMessage the page reads back field for field; malformed bytes
// are a ProtocolError, never a wrong message.
//
// node ws_protocol_test.mjs PROTO_DIR
import assert from 'node:assert/strict';
import { execFileSync } from 'node:child_process';
import test from 'node:test';
import { ProtocolError, decodeServerMessage, encodeRefine, encodeStart } from
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
  assert.throws(() => decodeServerMessage(new Uint8Array([0x0b])), ProtocolError);  // wire type 3
  assert.throws(() => decodeServerMessage(new Uint8Array(11).fill(0xff)), ProtocolError);
  assert.throws(() => decodeServerMessage(new Uint8Array(0)), ProtocolError);  // no kind
  // A varint where a message belongs.
  assert.throws(() => decodeServerMessage(new Uint8Array([0x18, 0x01])), ProtocolError);
});
