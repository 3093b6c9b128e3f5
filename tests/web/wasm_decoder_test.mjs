// node wasm_decoder_test.mjs MODULE.js CASE_DIR...: the WebAssembly decoder
// against the native one. Each CASE_DIR is wasm_reference's output for one
// container; every case (order x budget) is decoded by the module through
// its JS API and must give the native positions bit for bit (float64, and
// float32 as the float32 of the native doubles), the same faces, level,
// packet and byte counts, and the estimated PSNR to 1e-9 dB. A container
// with split packets (docs/FORMAT.md 2.2) also has part cases: units fed
// one by one (addPacketPart for a part), compared the same way; and its
// split packets cut into parts here, in JS, give the native cut and, fed
// part by part, the complete mesh. Then the API's refusals: a bad header,
// an unknown id, a packet twice, a missing dependency, a corrupt payload,
// and for parts an unsplit packet, a part out of range, a part twice, a
// part before its dependency, each throw an Error carrying the decoder's
// message.
import { existsSync, readFileSync } from 'node:fs';
import { join } from 'node:path';
import { loadDecoderModule } from '../browser/harness.mjs';

const [modulePath, ...dirs] = process.argv.slice(2);
if (!modulePath || dirs.length === 0) {
  console.error('usage: node wasm_decoder_test.mjs MODULE.js CASE_DIR...');
  process.exit(2);
}
const mw = await loadDecoderModule(modulePath);

let failures = 0;
let checked = 0;
function fail(what) {
  failures += 1;
  console.error('FAIL ' + what);
}
function expect(ok, what) {
  if (!ok) fail(what);
}
function view(file, Type) {
  const b = readFileSync(file);
  return new Type(b.buffer, b.byteOffset, b.byteLength / Type.BYTES_PER_ELEMENT);
}
function sameBits(a, b) {
  if (a.length !== b.length) return false;
  const x = new Uint8Array(a.buffer, a.byteOffset, a.byteLength);
  const y = new Uint8Array(b.buffer, b.byteOffset, b.byteLength);
  return x.every((v, i) => v === y[i]);
}
function* packets(file) {
  const b = readFileSync(file);
  const d = new DataView(b.buffer, b.byteOffset, b.byteLength);
  for (let at = 0; at < b.length;) {
    const id = d.getUint32(at, true);
    const length = d.getUint32(at + 4, true);
    yield [id, new Uint8Array(b.buffer, b.byteOffset + at + 8, length)];
    at += 8 + length;
  }
}
// PARTS.units (wasm_reference): [id, part (-1: the whole packet), payload].
function* units(file) {
  const b = readFileSync(file);
  const d = new DataView(b.buffer, b.byteOffset, b.byteLength);
  for (let at = 0; at < b.length;) {
    const id = d.getUint32(at, true);
    const tag = d.getUint32(at + 4, true);
    const length = d.getUint32(at + 8, true);
    yield [id, tag - 1, new Uint8Array(b.buffer, b.byteOffset + at + 12, length)];
    at += 12 + length;
  }
}
// The `count` parts of a split packet's payload (FORMAT.md 2.2): the
// lengths of the first count - 1 as varints (LEB128, at most 5 bytes),
// then the codewords; the last one's length is what remains.
function splitParts(payload, count) {
  let at = 0;
  const lengths = [];
  for (let p = 0; p + 1 < count; ++p) {
    let v = 0;
    for (let shift = 0; ; shift += 7) {
      if (at >= payload.length || shift > 28) throw new Error('a truncated part table');
      const byte = payload[at++];
      v += (byte & 0x7f) * 2 ** shift;
      if (!(byte & 0x80)) break;
    }
    lengths.push(v);
  }
  const parts = [];
  for (const length of lengths) {
    if (length > payload.length - at) throw new Error('part lengths overrun the payload');
    parts.push(payload.subarray(at, at + length));
    at += length;
  }
  parts.push(payload.subarray(at));
  return parts;
}
// What the decoder says of a case, against the native manifest entry.
function compareCase(dec, dir, c, what) {
  const native = view(join(dir, c.name + '.pos64'), Float64Array);
  expect(sameBits(dec.positions64(), native), what + ': float64 positions bit for bit');
  expect(sameBits(dec.positions(), Float32Array.from(native)), what + ': float32 positions');
  expect(sameBits(dec.positions64(1), view(join(dir, c.name + '.l1.pos64'), Float64Array)),
         what + ': level-1 positions');
  expect(sameBits(dec.faces(), view(join(dir, c.name + '.faces'), Uint32Array)),
         what + ': faces');
  expect(dec.faces(0).length < dec.faces().length, what + ': fewer faces at level 0');
  const colours = join(dir, c.name + '.col64');
  expect(dec.hasColors() === existsSync(colours), what + ': hasColors');
  if (existsSync(colours)) {
    const native64 = view(colours, Float64Array);
    expect(sameBits(dec.colors64(), native64), what + ': float64 colours bit for bit');
    expect(sameBits(dec.colors(), Float32Array.from(native64)), what + ': float32 colours');
  } else {
    expect(dec.colors().length === 0, what + ': no colours without a colour channel');
  }
  const uvs = join(dir, c.name + '.uv32');
  expect(dec.hasTexture() === existsSync(uvs), what + ': hasTexture');
  if (existsSync(uvs)) {
    expect(sameBits(dec.textureCoordinates(), view(uvs, Float32Array)),
           what + ': texture coordinates bit for bit');
  } else {
    expect(dec.textureCoordinates().length === 0, what + ': no UVs without a texture');
  }
  const map = join(dir, c.name + '.map0');
  const image = dec.textureImage(0);
  expect((image !== null) === existsSync(map), what + ': a base colour level held');
  if (image !== null && existsSync(map)) {
    expect(sameBits(image.bytes, view(map, Uint8Array)), what + ': the base colour level\'s bytes');
  }
  expect(dec.level() === c.level, what + ': level ' + dec.level() + ' vs ' + c.level);
  expect(dec.detailLevels() === c.detailLevels,
         what + ': detailLevels ' + dec.detailLevels() + ' vs ' + c.detailLevels);
  expect(dec.levels() === c.levels, what + ': levels');
  expect(dec.packetsDecoded() === c.packets, what + ': packetsDecoded');
  expect(dec.payloadBytesDecoded() === c.payloadBytes, what + ': payloadBytesDecoded');
  // The estimate goes through exp2 and log10, whose last bit differs
  // between glibc and musl: equal to 1e-9 dB (the mesh is exact).
  const psnr = c.psnr === 'Infinity' ? Infinity : c.psnr;
  const got = dec.estimatedPsnr();
  expect(got === psnr || Math.abs(got - psnr) <= 1e-9,
         what + ': estimatedPsnr ' + got + ' vs ' + psnr);
}
function throwsWith(f, text, what) {
  try {
    f();
  } catch (e) {
    expect(e instanceof Error, what + ': throws an Error');
    expect(text === '' || String(e.message).includes(text),
           what + ': message "' + e.message + '" lacks "' + text + '"');
    return;
  }
  fail(what + ': did not throw');
}

for (const dir of dirs) {
  const header = readFileSync(join(dir, 'header.bin'));
  const manifest = JSON.parse(readFileSync(join(dir, 'manifest.json'), 'utf8'));
  for (const c of manifest.cases) {
    const what = dir + ' ' + c.name + ' (budget ' + c.budget + ')';
    const dec = new mw.Decoder(header);
    try {
      expect(dec.packetCount() === c.packetCount, what + ': packetCount');
      for (const [id, payload] of packets(join(dir, c.name + '.packets'))) {
        expect(dec.dependenciesMet(id) && !dec.hasPacket(id), what + ': packet ' + id + ' ready');
        dec.addPacket(id, payload);
        expect(dec.hasPacket(id), what + ': hasPacket after addPacket');
      }
      compareCase(dec, dir, c, what);
      checked += 1;
    } finally {
      dec.delete();
    }
  }
}

// Part cases: units as a region stream sends them, fed one by one.
let splitContainers = 0;
for (const dir of dirs) {
  const header = readFileSync(join(dir, 'header.bin'));
  const manifest = JSON.parse(readFileSync(join(dir, 'manifest.json'), 'utf8'));
  const split = new Map(manifest.split);
  if (split.size > 0) splitContainers += 1;
  // The JS cut of every split packet, from the complete stream.
  const cut = new Map();
  for (const [id, payload] of packets(join(dir, 'quality_4.packets'))) {
    if (split.has(id)) cut.set(id, splitParts(payload, split.get(id)));
  }
  for (const c of manifest.partCases) {
    const what = dir + ' ' + c.name;
    const dec = new mw.Decoder(header);
    try {
      for (const [id, count] of split) {
        expect(dec.partCount(id) === count, what + ': partCount(' + id + ')');
      }
      for (const [id, part, payload] of units(join(dir, c.name + '.units'))) {
        if (part < 0) {
          expect(dec.partCount(id) === 0 || !dec.hasPacket(id), what + ': packet ' + id + ' new');
          dec.addPacket(id, payload);
          expect(dec.hasPacket(id), what + ': hasPacket after addPacket');
          continue;
        }
        expect(sameBits(payload, cut.get(id)[part]),
               what + ': the JS cut of part ' + part + ' of packet ' + id + ' is the native one');
        expect(!dec.hasPart(id, part) && dec.partDependenciesMet(id, part),
               what + ': part ' + part + ' of packet ' + id + ' ready');
        dec.addPacketPart(id, part, payload);
        expect(dec.hasPart(id, part), what + ': hasPart after addPacketPart');
      }
      compareCase(dec, dir, c, what);
      checked += 1;
    } finally {
      dec.delete();
    }
  }
  if (split.size === 0) continue;
  // Every split packet part by part, the parts in reverse: the complete mesh.
  const dec = new mw.Decoder(header);
  const what = dir + ' every packet, split ones part by part';
  for (const [id, payload] of packets(join(dir, 'quality_4.packets'))) {
    if (!split.has(id)) {
      dec.addPacket(id, payload);
      continue;
    }
    const parts = cut.get(id);
    for (let p = parts.length - 1; p >= 0; --p) dec.addPacketPart(id, p, parts[p]);
    expect(dec.hasPacket(id), what + ': all parts of ' + id + ' make the packet');
  }
  expect(sameBits(dec.positions64(), view(join(dir, 'quality_4.pos64'), Float64Array)),
         what + ': the complete mesh');
  dec.delete();
}

// parseContainer: the whole container gives the header and every packet,
// which decode to the complete case's mesh; a cut one gives a prefix.
for (const dir of dirs) {
  const manifest = JSON.parse(readFileSync(join(dir, 'manifest.json'), 'utf8'));
  const bytes = readFileSync(manifest.container);
  const parsed = mw.parseContainer(bytes);
  const what = dir + ' parseContainer';
  expect(sameBits(parsed.header, readFileSync(join(dir, 'header.bin'))), what + ': header');
  expect(parsed.missingBytes === 0, what + ': nothing missing');
  const dec = new mw.Decoder(parsed.header);
  expect(parsed.packets.length === dec.packetCount(), what + ': every packet');
  for (const { id, payload } of parsed.packets) dec.addPacket(id, payload);
  expect(sameBits(dec.positions64(), view(join(dir, 'quality_4.pos64'), Float64Array)),
         what + ': all packets decode to the complete mesh');
  dec.delete();
  const cut = mw.parseContainer(bytes.subarray(0, bytes.length - 1));
  expect(cut.missingBytes > 0 && cut.packets.length < parsed.packets.length,
         what + ': a cut container gives the whole packets before the cut');
  throwsWith(() => mw.parseContainer(new Uint8Array([1, 2, 3, 4, 5, 6, 7, 8, 9])), 'magic',
             what + ': not a container');
}

// Refusals, on the first container's header and its complete quality case.
{
  const dir = dirs[0];
  const header = readFileSync(join(dir, 'header.bin'));
  const all = [...packets(join(dir, 'quality_4.packets'))];
  throwsWith(() => new mw.Decoder(header.subarray(0, header.length - 3)), 'header',
             'a cut header');
  throwsWith(() => new mw.Decoder(new Uint8Array([8, 0x80])), 'header', 'malformed bytes');
  const dec = new mw.Decoder(header);
  throwsWith(() => dec.addPacket(dec.packetCount(), new Uint8Array(1)), 'not in the index',
             'an unknown id');
  const [first, payload] = all[0];
  const second = all.find(([id]) => !dec.dependenciesMet(id));
  if (second) {
    throwsWith(() => dec.addPacket(second[0], second[1]), 'first', 'a missing dependency');
  }
  const corrupt = Uint8Array.from(payload);
  corrupt[0] ^= 0x40;
  throwsWith(() => dec.addPacket(first, corrupt), 'CRC', 'a corrupt payload');
  dec.addPacket(first, payload);
  throwsWith(() => dec.addPacket(first, payload), 'already', 'a packet twice');
  dec.delete();
  throwsWith(() => dec.level(), 'deleted', 'a deleted decoder');
}

// Part refusals, on the first container with split packets.
{
  const dir = dirs.find((d) => JSON.parse(readFileSync(join(d, 'manifest.json'), 'utf8')).split.length);
  const manifest = JSON.parse(readFileSync(join(dir, 'manifest.json'), 'utf8'));
  const dec = new mw.Decoder(readFileSync(join(dir, 'header.bin')));
  const all = new Map([...packets(join(dir, 'quality_4.packets'))]);
  const unsplit = [...all.keys()].find((id) => dec.partCount(id) === 0);
  expect(!dec.hasPart(unsplit, 0) && !dec.partDependenciesMet(unsplit, 0),
         'an unsplit packet has no parts');
  throwsWith(() => dec.addPacketPart(unsplit, 0, new Uint8Array(1)), 'not split',
             'a part of an unsplit packet');
  throwsWith(() => dec.addPacketPart(0, -1, new Uint8Array(1)), 'part -1',
             'a negative part');
  // A split packet whose parts need another packet's (one bitplane up).
  const [id, count] = manifest.split.find(([q]) => !dec.partDependenciesMet(q, 0));
  const parts = splitParts(all.get(id), count);
  throwsWith(() => dec.addPacketPart(id, count, parts[0]), 'parts', 'a part out of range');
  throwsWith(() => dec.addPacketPart(id, 0, parts[0]), 'first', 'a part before its dependency');
  // The complete stream in the quality order up to its first split packet,
  // which is then ready: a part twice.
  let ready = null;
  for (const [q, payload] of all) {
    if (dec.partCount(q) > 0) {
      ready = q;
      break;
    }
    dec.addPacket(q, payload);
  }
  const first = splitParts(all.get(ready), dec.partCount(ready));
  expect(dec.partDependenciesMet(ready, 0), 'the first split packet of the order is ready');
  dec.addPacketPart(ready, 0, first[0]);
  expect(dec.hasPart(ready, 0) && !dec.hasPacket(ready), 'one part is not the packet');
  throwsWith(() => dec.addPacketPart(ready, 0, first[0]), 'already', 'a part twice');
  dec.delete();
}

console.log(`${checked} cases of ${dirs.length} containers (${splitContainers} with split packets) ` +
            `compared, ${failures} failures`);
process.exit(failures === 0 && checked > 0 && splitContainers > 0 ? 0 : 1);
