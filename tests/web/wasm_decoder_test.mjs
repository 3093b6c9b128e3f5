// node wasm_decoder_test.mjs MODULE.js CASE_DIR...: the WebAssembly decoder
// against the native one. Each CASE_DIR is wasm_reference's output for one
// container; every case (order x budget) is decoded by the module through
// its JS API and must give the native positions bit for bit (float64, and
// float32 as the float32 of the native doubles), the same faces, level,
// packet and byte counts, and the estimated PSNR to 1e-9 dB. Then the API's refusals: a
// bad header, an unknown id, a packet twice, a missing dependency, a
// corrupt payload each throw an Error carrying the decoder's message.
import { readFileSync } from 'node:fs';
import { join, resolve } from 'node:path';
import { pathToFileURL } from 'node:url';

const [modulePath, ...dirs] = process.argv.slice(2);
if (!modulePath || dirs.length === 0) {
  console.error('usage: node wasm_decoder_test.mjs MODULE.js CASE_DIR...');
  process.exit(2);
}
const { default: createMeshwave } = await import(pathToFileURL(resolve(modulePath)).href);
const mw = await createMeshwave();

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
      const native = view(join(dir, c.name + '.pos64'), Float64Array);
      const p64 = dec.positions64();
      expect(sameBits(p64, native), what + ': float64 positions bit for bit');
      expect(sameBits(dec.positions(), Float32Array.from(native)), what + ': float32 positions');
      expect(sameBits(dec.positions64(1), view(join(dir, c.name + '.l1.pos64'), Float64Array)),
             what + ': level-1 positions');
      expect(sameBits(dec.faces(), view(join(dir, c.name + '.faces'), Uint32Array)),
             what + ': faces');
      expect(dec.faces(0).length < dec.faces().length, what + ': fewer faces at level 0');
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
      checked += 1;
    } finally {
      dec.delete();
    }
  }
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

console.log(`${checked} cases of ${dirs.length} containers compared, ${failures} failures`);
process.exit(failures === 0 && checked > 0 ? 0 : 1);
