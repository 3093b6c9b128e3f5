// node bench/wasm_decode_rate.mjs MODULE.js FILE.mwv [--runs 9]: the
// WebAssembly decoder's cost per payload byte under Node, measured as
// bench/decode_rate measures the native one (docs/BENCHMARKS.md): per run a
// fresh Decoder from the header (not timed), every packet of the container
// in its order through addPacket (timed: process CPU and wall), then one
// positions() + faces() (timed apart: the mesh a page would upload).
import { readFileSync } from 'node:fs';
import { performance } from 'node:perf_hooks';
import { loadDecoderModule } from '../tests/browser/harness.mjs';

const args = process.argv.slice(2);
if (args.length < 2 || args.includes('--help')) {
  console.error('usage: node bench/wasm_decode_rate.mjs MODULE.js FILE.mwv [--runs N]');
  process.exit(args.includes('--help') ? 0 : 2);
}
const runsAt = args.indexOf('--runs');
const runs = runsAt >= 0 ? Number(args[runsAt + 1]) : 9;
const mw = await loadDecoderModule(args[0]);
const { header, packets } = mw.parseContainer(readFileSync(args[1]));
const payload = packets.reduce((n, p) => n + p.payload.length, 0);

const median = (xs) => [...xs].sort((a, b) => a - b)[Math.floor(xs.length / 2)];
const cpuMs = () => {
  const u = process.cpuUsage();
  return (u.user + u.system) / 1e3;
};
const nsPerByte = [], wallNsPerByte = [], meshMs = [];
for (let run = 0; run < runs; ++run) {
  const dec = new mw.Decoder(header);
  const cpu0 = cpuMs(), wall0 = performance.now();
  for (const { id, payload: p } of packets) dec.addPacket(id, p);
  const cpu1 = cpuMs(), wall1 = performance.now();
  const positions = dec.positions();
  dec.faces();
  const wall2 = performance.now();
  dec.delete();
  const ns = (cpu1 - cpu0) * 1e6 / payload;
  nsPerByte.push(ns);
  wallNsPerByte.push((wall1 - wall0) * 1e6 / payload);
  meshMs.push(wall2 - wall1);
  console.log(`run ${run}: ${packets.length} packets, ${payload} payload bytes: decode ` +
              `${(cpu1 - cpu0).toFixed(2)} ms CPU (${ns.toFixed(1)} ns/byte = ` +
              `${(8e3 / ns).toFixed(1)} Mbit/s), ${(wall1 - wall0).toFixed(2)} ms wall; ` +
              `positions()+faces() ${(wall2 - wall1).toFixed(2)} ms wall ` +
              `(${positions.length / 3} vertices)`);
}
const ns = median(nsPerByte);
console.log(`median: ${ns.toFixed(1)} ns CPU per payload byte = ${(8e3 / ns).toFixed(1)} ` +
            `Mbit/s on one core (best ${Math.min(...nsPerByte).toFixed(1)} ns/byte; wall ` +
            `${median(wallNsPerByte).toFixed(1)} ns/byte); positions()+faces() ` +
            `${median(meshMs).toFixed(2)} ms wall`);
