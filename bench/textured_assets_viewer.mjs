// The viewer's side of bench/textured_assets.sh: each catalog item streamed
// by the browser viewer (headless Chromium, the real WebAssembly decoder)
// at the same five budgets as the C++ client, a screenshot of each, and one
// TSV line: bytes received, vertices and faces, the texture readout, the
// pixels drawn, the chromatic ones, those that differ from the grey render
// (the "colours and texture" box off: colour or texture on screen) and the
// console errors.
//
// Usage: node bench/textured_assets_viewer.mjs --url http://127.0.0.1:PORT
//   --catalog OUT/catalog.txt --node-modules DIR --out DIR
// (the server must serve the viewer: meshwave-server --viewer-dir DIR)
import { mkdirSync, readFileSync, writeFileSync } from 'node:fs';
import path from 'node:path';
import { parseArgs } from 'node:util';
import { comparePictures, launchChromium } from '../tests/browser/harness.mjs';

const { values: opt } = parseArgs({ options: {
  url: { type: 'string' }, catalog: { type: 'string' },
  'node-modules': { type: 'string' }, out: { type: 'string' },
  help: { type: 'boolean', short: 'h' },
} });
if (opt.help || !opt.url || !opt.catalog || !opt['node-modules'] || !opt.out) {
  console.log(readFileSync(new URL(import.meta.url), 'utf8').split('\n').slice(0, 10)
    .map((l) => l.replace(/^\/\/ ?/, '')).join('\n'));
  process.exit(opt.help ? 0 : 2);
}
mkdirSync(opt.out, { recursive: true });

// `meshwave catalog` lines: ID NAME VERTICES FACES LEVELS PACKETS BYTES.
const items = readFileSync(opt.catalog, 'utf8').split('\n')
  .map((l) => l.trim().split(/\s+/))
  .filter((f) => /^[0-9a-f]{12}$/.test(f[0]))
  .map((f) => ({ id: f[0], name: f[1], bytes: parseInt(f[6], 10) }));
const shares = [5, 15, 35, 65, 100];

const browser = await launchChromium(opt['node-modules']);

// Of a screenshot and the grey render of the same view: pixels drawn,
// chromatic ones and those that differ (harness.mjs).
async function measure(png, grey) {
  const r = await comparePictures(browser, png, grey);
  return { drawn: r.drawn, chromatic: r.chromaticA, differ: r.differ };
}

async function stream(item, share) {
  const errors = [];
  const page = await browser.context.newPage();
  page.on('console', (m) => { if (m.type() === 'error') errors.push(m.text()); });
  page.on('pageerror', (e) => errors.push(`uncaught: ${e.message}`));
  await page.goto(`${opt.url}/viewer/`);
  await page.waitForSelector('body[data-state="ready"], body[data-state="error"]');
  await page.selectOption('#mesh', item.id);
  await page.selectOption('#order', 'quality');
  await page.fill('#budget', String(item.bytes * share / 100 / 1024));
  await page.fill('#rate', '0');
  const t0 = Date.now();
  await page.click('#stream');
  await page.waitForSelector('body[data-state="done"], body[data-state="error"]', { timeout: 300000 });
  const seconds = (Date.now() - t0) / 1000;
  // The texture levels held are decoded by the browser, the last one after
  // the stream's end: wait until the readout has not changed for a second
  // (at most 15 s; it stays '–' when no level fits the budget).
  let last = null;
  for (let quiet = 0, i = 0; quiet < 4 && i < 60; ++i) {
    const now = await page.evaluate(() => document.getElementById('r-texture').textContent);
    quiet = now === last ? quiet + 1 : 0;
    last = now;
    await page.waitForTimeout(250);
  }
  await page.evaluate(() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r))));
  const read = await page.evaluate(() => {
    const t = (id) => document.getElementById(id).textContent.trim();
    const e = document.getElementById('error');
    return { bytes: t('r-bytes'), size: t('r-size'), texture: t('r-texture'),
             error: e.hidden ? '' : e.textContent.trim() };
  });
  const file = path.join(opt.out, `viewer_${item.name}_${share}.png`);
  await page.locator('#view').screenshot({ path: file });
  await page.uncheck('#attributes');
  await page.evaluate(() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r))));
  const grey = await page.locator('#view').screenshot();
  await page.close();
  const m = await measure(readFileSync(file), grey);
  if (read.error) errors.push(read.error);
  return { ...read, ...m, seconds, errors };
}

const lines = ['asset\tbudget\tbytes received\tvertices / faces\ttexture\tdrawn px\tchromatic px\tunlike grey px\tseconds\terrors'];
let failed = false;
try {
  for (const item of items) {
    for (const share of shares) {
      const r = await stream(item, share);
      failed ||= r.errors.length > 0 || r.drawn === 0;
      const line = [item.name, `${share}%`, r.bytes, r.size, r.texture, r.drawn, r.chromatic, r.differ,
        r.seconds.toFixed(1), r.errors.join(' | ') || '-'].join('\t');
      console.log(line);
      lines.push(line);
    }
  }
} finally {
  await browser.close();
}
const tsv = path.join(opt.out, 'textured_assets_viewer.tsv');
writeFileSync(tsv, `${lines.join('\n')}\n`);
console.log(`textured_assets_viewer: ${tsv}`);
process.exit(failed ? 1 : 0);
