// Time to first mesh in the browser viewer on loopback: headless Chromium
// (as tests/browser) opens /viewer/ from a meshwave-server serving MESH with
// the real WebAssembly decoder, clicks Stream, and reads the page's own
// "first mesh after" readout: from the click to the frame after the first
// decoded mesh was handed to three.js (WebSocket connect, StreamStart,
// packets, decode, geometry upload, one SwiftShader frame). Each run is a
// fresh page (module and wasm from the HTTP cache, as a reload would be).
//
// node viewer_first_mesh.mjs SERVER CLI DECODER_JS MESH NODE_MODULES RUNS BUDGETS...
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { Server, ingest, launchChromium, tempDir, viewerDir } from '../tests/browser/harness.mjs';
import { readFileSync, rmSync } from 'node:fs';

const [serverBin, , decoder, mesh, modules, runsText, ...budgets] = process.argv.slice(2);
const runs = Number(runsText);
if (readFileSync(decoder, 'utf8').includes('isFakeTestOnly')) {
  console.error('viewer_first_mesh: that is the test-only fake decoder; give the real module');
  process.exit(2);
}
const root = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '..');
const work = tempDir('meshwave-viewer-bench-');
const catalog = path.join(work, 'catalog');
const id = ingest(serverBin, catalog, mesh);
const server = await Server.start(serverBin, catalog,
  viewerDir(path.join(root, 'web/viewer'), decoder, path.join(work, 'viewer')), work);
const browser = await launchChromium(modules);
const median = (xs) => [...xs].sort((a, b) => a - b)[Math.floor(xs.length / 2)];
try {
  console.log(`mesh ${path.basename(mesh)} (${id}), ${runs} runs per budget, loopback, unpaced`);
  console.log('| budget | first mesh (median) | min | max | bytes | packets |');
  console.log('|---|---|---|---|---|---|');
  for (const budget of budgets) {
    const times = [];
    let bytes = 0, packets = 0;
    for (let i = 0; i < runs + 1; ++i) {  // the first run warms the cache
      const page = await browser.context.newPage();
      await page.goto(`${server.url}/viewer/?mesh=${id}&order=quality&rate=0&budget=${budget === 'all' ? '' : budget}`);
      await page.waitForSelector('body[data-state="ready"]');
      await page.click('#stream');
      await page.waitForSelector('body[data-state="done"]');
      await page.waitForFunction(() => document.getElementById('r-first').dataset.value);
      const r = await page.evaluate(() => ({
        ms: Number(document.getElementById('r-first').dataset.value),
        bytes: Number(document.getElementById('r-bytes').dataset.value),
        packets: Number(document.getElementById('r-packets').textContent) }));
      if (i > 0) times.push(r.ms);
      ({ bytes, packets } = r);
      await page.close();
    }
    console.log(`| ${budget === 'all' ? 'whole stream' : budget + ' KiB'} | ${median(times).toFixed(1)} ms | ` +
                `${Math.min(...times).toFixed(1)} | ${Math.max(...times).toFixed(1)} | ${bytes} | ${packets} |`);
  }
} finally {
  await browser.close();
  await server.stop();
  rmSync(work, { recursive: true, force: true });
}
