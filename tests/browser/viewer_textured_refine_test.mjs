// A textured mesh refined step by step in the viewer, as a person does it,
// in headless Chromium against the real server and WebAssembly decoder
// (run_viewer_test.sh starts it): the sample (--mesh, data/textured/ring.glb,
// whose first base colour level is within the first 4 KiB) streamed at
// --budget-kib in quality order, then "refine +N KiB" (the panel's button,
// N = --step-kib) until the viewer says the whole stream is here. The
// camera is fitted to the stream's first mesh and never moved after it.
// At every step, once the viewer is done and its picture has settled:
//  (a) the mesh is drawn textured: the texture readout names a level (the
//      base colour map's best level held, decoded and handed to the drawn
//      mesh), never a coarser one than the step before, and the picture is
//      in colour (the untextured material is grey);
//  (b) the rendered error against the complete stream's final frame from
//      the same camera (mean squared BT.709 luma difference over the pixels
//      covered in either frame: not the white background) never increases
//      from one step to the next (float noise allowed: 1e-6 relative), and
//      the last step's is 0 (within the same noise).
// No console error. Screenshots of every step and of the final frame are
// kept in --artefacts.
//
// node viewer_textured_refine_test.mjs --server BIN --cli BIN --decoder meshwave_decoder.js
//   --viewer web/viewer --mesh data/textured/ring.glb --node-modules DIR --artefacts DIR
//   [--budget-kib 4] [--step-kib 2.5]
// Exit 0 passed, 1 failed, 77 skipped (no Chromium, no decoder module, or
// the test-only fake decoder, which has no textures).
import assert from 'node:assert/strict';
import { existsSync, mkdirSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import path from 'node:path';
import { parseArgs } from 'node:util';
import {
  Server, checks, ingest, launchChromium, openQualityViewer, skip, tempDir, viewerDir, waitStreamDone,
} from './harness.mjs';

const { values: opt } = parseArgs({ options: {
  server: { type: 'string' }, cli: { type: 'string' }, decoder: { type: 'string' },
  viewer: { type: 'string' }, mesh: { type: 'string' }, 'node-modules': { type: 'string' },
  artefacts: { type: 'string' },
  // ring.glb: 4 KiB hold the base mesh, the geometry's first bitplanes and
  // the first level of each map (2,699 bytes); a refine brings the longest
  // run of packets that fits its step, and the largest packet (the finer
  // base colour level) is 2,320 bytes, so steps of 2.5 KiB always bring one.
  'budget-kib': { type: 'string', default: '4' },
  'step-kib': { type: 'string', default: '2.5' },
} });
for (const k of ['server', 'viewer', 'mesh', 'node-modules', 'artefacts']) {
  if (!opt[k]) { console.error(`viewer_textured_refine_test: --${k} is required`); process.exit(2); }
}
if (!opt.decoder || !existsSync(opt.decoder)) {
  skip(`the WebAssembly decoder module is not built (${opt.decoder || 'no path given'}): ` +
       'configure with -DMESHWAVE_DECODER_JS=PATH/meshwave_decoder.js');
}
if (readFileSync(opt.decoder, 'utf8').includes('isFakeTestOnly')) {
  skip('the test-only fake decoder has no textures: this test needs the real module');
}
const BUDGET_KIB = parseFloat(opt['budget-kib']), STEP_KIB = parseFloat(opt['step-kib']);
const MAX_STEPS = 64;
const NOISE = 1e-6;  // relative: what float rounding may move an error by

mkdirSync(opt.artefacts, { recursive: true });
const work = tempDir('meshwave-viewer-textured-refine-');
const catalog = path.join(work, 'catalog');
const id = ingest(opt.server, catalog, opt.mesh);
const server = await Server.start(opt.server, catalog,
  viewerDir(opt.viewer, opt.decoder, path.join(work, 'viewer')), work);
const browser = await launchChromium(opt['node-modules']);

// The canvas's pixels once the page has stopped changing them: a texture
// level is decoded (createImageBitmap) and drawn a frame or two after the
// `done` that brought it, so the picture of a step is the one that stays.
async function settledFrame(page) {
  const canvas = page.locator('#view canvas');
  let last = null;
  for (let i = 0; i < 30; ++i) {
    await page.evaluate(() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r))));
    const png = await canvas.screenshot();
    if (last && png.equals(last)) return png;
    last = png;
  }
  throw new Error('the picture kept changing for 30 screenshots after the step was done');
}

// The viewer's readouts after a step.
const readouts = (page) => page.evaluate(() => {
  const $ = (id) => document.getElementById(id);
  return {
    bytes: Number($('r-bytes').dataset.value), packets: Number($('r-packets').textContent),
    level: $('r-level').textContent, texture: $('r-texture').textContent,
    textured: $('r-texture').dataset.value !== '',
    complete: $('status').textContent.startsWith('complete'),
  };
});

// The texture level the readout names ("W × H (level L of N)"): [L, N].
function textureLevel(text) {
  const m = text.match(/level (\d+) of (\d+)/);
  return m ? [Number(m[1]), Number(m[2])] : [0, 0];
}

// Of each frame (PNG) against the reference (PNG, same size), decoded by the
// browser's own image decoder: pixels covered in either (not the white
// background), the mean squared BT.709 luma difference over them (8-bit
// units), and the frame's own covered and chromatic pixels (max - min
// channel over 40: the untextured grey material has none).
async function renderedErrors(frames, reference) {
  const page = await browser.context.newPage();
  try {
    return await page.evaluate(async ([frames64, ref64]) => {
      const pixels = async (data) => {
        const img = new Image();
        img.src = `data:image/png;base64,${data}`;
        await img.decode();
        const c = new OffscreenCanvas(img.width, img.height);
        const g = c.getContext('2d');
        g.drawImage(img, 0, 0);
        return g.getImageData(0, 0, img.width, img.height).data;
      };
      const ref = await pixels(ref64);
      const covered = (p, i) => p[i] < 255 || p[i + 1] < 255 || p[i + 2] < 255;
      const luma = (p, i) => 0.2126 * p[i] + 0.7152 * p[i + 1] + 0.0722 * p[i + 2];
      const out = [];
      for (const f of frames64) {
        const p = await pixels(f);
        if (p.length !== ref.length) throw new Error('a frame and the reference differ in size');
        let union = 0, own = 0, chromatic = 0, sum = 0;
        for (let i = 0; i < p.length; i += 4) {
          const a = covered(p, i), b = covered(ref, i);
          if (a) {
            ++own;
            if (Math.max(p[i], p[i + 1], p[i + 2]) - Math.min(p[i], p[i + 1], p[i + 2]) > 40) ++chromatic;
          }
          if (!a && !b) continue;
          ++union;
          const d = luma(p, i) - luma(ref, i);
          sum += d * d;
        }
        out.push({ union, covered: own, chromatic, mse: union ? sum / union : 0 });
      }
      return out;
    }, [frames.map((f) => f.toString('base64')), reference.toString('base64')]);
  } finally {
    await page.close();
  }
}

const psnr = (mse) => (mse > 0 ? `${(10 * Math.log10(255 * 255 / mse)).toFixed(2)} dB` : 'identical');
const describe = (s) => `step ${s.step} (${s.request}: ${s.bytes} bytes, ${s.packets} packets, ` +
  `texture ${s.texture})`;

const { test, failed } = checks();
try {
  await test(`${path.basename(opt.mesh)} refined from ${BUDGET_KIB} KiB by +${STEP_KIB} KiB: ` +
             'textured at every step, its rendered error never up, none at the end', async () => {
    const errors = [];
    const page = await openQualityViewer(browser, server.url, id, BUDGET_KIB, errors);
    // Only the budget and the refines asked for: no view refines either
    // (the camera does not move anyway).
    await page.uncheck('#follow-view');
    await page.fill('#refine-kib', String(STEP_KIB));

    const steps = [];
    await page.click('#stream');
    let request = `start ${BUDGET_KIB} KiB`;
    for (;;) {
      await waitStreamDone(page);
      const step = steps.length;
      // A texture level within the bytes held reaches the drawn mesh once
      // the browser has decoded it: waited for (it fails (a) below if never).
      await page.waitForFunction(() => document.getElementById('r-texture').dataset.value !== '',
        null, { timeout: 5000 }).catch(() => {});
      const frame = await settledFrame(page);
      const r = await readouts(page);
      writeFileSync(path.join(opt.artefacts, `textured_refine_step${step}.png`), frame);
      steps.push({ step, request, frame, ...r });
      if (step > 0) {
        assert.ok(r.bytes > steps[step - 1].bytes,
          `${describe(steps[step])} brought nothing after ${steps[step - 1].bytes} bytes: the next ` +
          `packet is larger than the step; give a larger --step-kib`);
      }
      if (r.complete) break;
      assert.ok(steps.length < MAX_STEPS, `the stream was not complete after ${MAX_STEPS} steps`);
      assert.equal(await page.isDisabled('#refine'), false,
        `${describe(steps[step])}: the viewer is done, not complete, and its refine button is disabled`);
      request = `refine +${STEP_KIB} KiB`;
      await page.click('#refine');
    }

    // The complete stream's final frame: the finest texture level decoded
    // and drawn, nothing left to change.
    await page.waitForFunction(() => {
      const m = document.getElementById('r-texture').textContent.match(/level (\d+) of (\d+)/);
      return m && m[1] === m[2];
    }, null, { timeout: 5000 }).catch(() => {});
    await page.waitForTimeout(300);
    const reference = await settledFrame(page);
    const final = await readouts(page);
    writeFileSync(path.join(opt.artefacts, 'textured_refine_final.png'), reference);

    const measured = await renderedErrors(steps.map((s) => s.frame), reference);
    console.log('  | step | request | bytes | packets | level | texture | covered px | luma MSE | luma PSNR |');
    steps.forEach((s, i) => {
      Object.assign(s, measured[i]);
      console.log(`  | ${s.step} | ${s.request} | ${s.bytes} | ${s.packets} | ${s.level} | ${s.texture} | ` +
                  `${s.union} | ${s.mse.toFixed(6)} | ${psnr(s.mse)} |`);
    });
    console.log(`  final frame: ${final.bytes} bytes, ${final.packets} packets, texture ${final.texture}; ` +
                `screenshots ${opt.artefacts}/textured_refine_step*.png, textured_refine_final.png`);

    // (a) textured at every step, the texture never coarser than before.
    for (const s of steps) {
      assert.ok(s.textured, `${describe(s)}: no texture level is drawn (the readout says "${s.texture}")`);
      assert.ok(s.covered > 0.01 * 960 * 640, `${describe(s)}: the mesh is not drawn (${s.covered} pixels)`);
      assert.ok(s.chromatic > 0.3 * s.covered,
        `${describe(s)}: drawn without its texture (${s.chromatic} of ${s.covered} drawn pixels in ` +
        'colour; the untextured material is grey)');
      if (s.step > 0) {
        const [now, before] = [textureLevel(s.texture)[0], textureLevel(steps[s.step - 1].texture)[0]];
        assert.ok(now >= before, `${describe(s)}: a coarser texture level than step ${s.step - 1}'s (${before})`);
      }
    }
    const [level, levels] = textureLevel(steps.at(-1).texture);
    assert.equal(level, levels, `${describe(steps.at(-1))}: complete, but not drawn with the finest texture level`);

    // (b) the rendered error never up, none at the end.
    for (const s of steps.slice(1)) {
      const before = steps[s.step - 1];
      assert.ok(s.mse <= before.mse * (1 + NOISE) + 1e-12,
        `the rendered error went up at ${describe(s)}: luma MSE ${s.mse.toFixed(6)} ` +
        `(${psnr(s.mse)}, over ${s.union} pixels) after ${before.mse.toFixed(6)} (${psnr(before.mse)}, ` +
        `over ${before.union} pixels) at ${describe(before)}, both against the complete stream's final ` +
        `frame; compare textured_refine_step${before.step}.png, textured_refine_step${s.step}.png and ` +
        `textured_refine_final.png in ${opt.artefacts}`);
    }
    const last = steps.at(-1);
    assert.ok(last.mse <= NOISE * Math.max(steps[0].mse, 1),
      `${describe(last)} completes the stream, yet its frame is not the final one: luma MSE ` +
      `${last.mse.toFixed(6)} over ${last.union} pixels (the final frame: ${final.bytes} bytes, ` +
      `texture ${final.texture})`);
    assert.deepEqual(errors, [], 'console errors');
    await page.close();
  });
} finally {
  await browser.close();
  await server.stop();
  rmSync(work, { recursive: true, force: true });
}
console.log(`screenshots in ${opt.artefacts}`);
if (failed()) process.exit(1);
console.log('viewer_textured_refine_test: all passed');
