// Drives the template editor (`cutaway edit`) in headless Chromium as a person would: pointer
// strokes on the sketch canvases, the panel's controls, the Save button.
// Usage:
//   node tests/tools/edit_in_chromium.mjs CUTAWAY sketch DIR
//     starts the editor on DIR/new-fruit.yaml (not existing yet), sketches a skin profile and a
//     section, makes the object 5-fold, adds Type II chambers and redraws their section, sets
//     colours (a picker, and the eyedropper on DIR/photo.png when that file exists), undoes and
//     redoes, then saves; screenshots DIR/editor-*.png along the way.
//   node tests/tools/edit_in_chromium.mjs CUTAWAY rewrite FILE.yaml
//     opens FILE.yaml, sets every surface's profile and section to the values they already
//     have (so their text is rewritten by the page), and saves.
// Prints one JSON line {ok, steps: [{what, verdict}], cut_seconds, coarse_cut_seconds,
// warnings, error}; exit code 0 when every step went as expected.
import { spawn } from 'node:child_process';
import fs from 'node:fs';
import path from 'node:path';
import { openPage } from './chromium.mjs';

const TIMEOUT_MS = 240000;
const started = Date.now();
const result = { ok: false, steps: [], warnings: [], error: '' };

function report(fields) {
  Object.assign(result, fields, { seconds: (Date.now() - started) / 1000 });
  console.log(JSON.stringify(result));
  return result.ok ? 0 : 1;
}

/// Starts `cutaway edit FILE --port 0`; resolves with {child, origin} once it prints its URL.
function startEditor(cutaway, file) {
  return new Promise((resolve, reject) => {
    const child = spawn(cutaway, ['edit', file, '--port', '0'], { stdio: ['ignore', 'pipe', 'pipe'] });
    let seen = '';
    const look = (data) => {
      seen += data;
      const m = /http:\/\/127\.0\.0\.1:(\d+)\//.exec(seen);
      if (m) resolve({ child, origin: `http://127.0.0.1:${m[1]}` });
    };
    child.stdout.on('data', look);
    child.stderr.on('data', look);
    child.on('exit', (code) => reject(new Error(`cutaway edit exited (${code}): ${seen}`)));
  });
}

/// Waits until the page has asked the server about its latest text and shown the answer.
async function settled(page) {
  await page.waitForFunction(() => window.editorReady && !window.editorBusy, null,
                             { timeout: TIMEOUT_MS });
}

async function step(page, what) {
  await settled(page);
  const verdict = await page.locator('#verdict').textContent();
  result.steps.push({ what, verdict });
  return verdict;
}

/// Draws a stroke through world points (template units) on the canvas `id`.
async function stroke(page, id, points) {
  const box = await page.locator(`#${id}`).boundingBox();
  const pixels = await page.evaluate(([which, pts]) =>
    pts.map((p) => window.editorViews[which].toCanvas(p)), [id, points]);
  const at = ([x, y]) => [box.x + x, box.y + y];
  await page.mouse.move(...at(pixels[0]));
  await page.mouse.down();
  for (const p of pixels.slice(1)) await page.mouse.move(...at(p), { steps: 2 });
  await page.mouse.up();
}

const range = (n, f) => Array.from({ length: n }, (_, k) => f(k / (n - 1)));

async function sketch(page, dir) {
  const shot = (name) => page.screenshot({ path: path.join(dir, `editor-${name}.png`) });
  await step(page, 'opened an empty template');
  // A round fruit 60 units tall, drawn on the left of the axis from top to bottom.
  await stroke(page, 'side', range(40, (t) => [-(3 + 32 * Math.sin(Math.PI * t)), 62 - 60 * t]));
  const skin = await step(page, 'drew the skin profile');
  // A section with five shallow lobes.
  await stroke(page, 'top', range(60, (t) => {
    const a = 2 * Math.PI * t, r = 33 + 2 * Math.cos(5 * a);
    return [r * Math.cos(a), r * Math.sin(a)];
  }));
  await step(page, 'drew the skin section');
  await page.selectOption('#symmetry', 'nfold');
  await step(page, 'made it 5-fold');
  await page.click('#add-within');
  await step(page, 'added chambers');
  // The chambers' section: a loop in fold 0 (centred on +x).
  await stroke(page, 'top', range(40, (t) => {
    const a = 2 * Math.PI * t;
    return [17 + 7 * Math.cos(a), 5 * Math.sin(a)];
  }));
  await step(page, 'redrew the chambers\' section');
  await page.locator('#surface .side[data-side=back] input[data-stop=first]').fill('#f0c040');
  await step(page, 'set the chambers\' back colour');
  const photo = path.join(dir, 'photo.png');
  let picked = null;
  if (fs.existsSync(photo)) {
    await page.locator('#side-photo').setInputFiles(photo);
    await page.waitForFunction(() => window.editorViews.side.photo !== null);
    await page.click('#surfaces li:first-child');
    await step(page, 'selected the skin');
    await page.click('#surface .side[data-side=front] [data-eyedropper]');
    const box = await page.locator('#side').boundingBox();
    await page.mouse.click(box.x + box.width / 2, box.y + box.height / 2);
    await step(page, 'picked the skin colour from the photo');
    picked = await page.locator('#surface .side[data-side=front] input[data-stop=first]').inputValue();
  }
  await shot('sketched');
  const before = await page.locator('#template').inputValue();
  await page.click('#undo');
  await step(page, 'undid');
  const undone = await page.locator('#template').inputValue();
  await page.click('#redo');
  await step(page, 'redid');
  const redone = await page.locator('#template').inputValue();
  // The cut plane dragged: coarse cuts while it moves, a full one when it stops.
  await page.locator('#plane').fill('0.4');
  await step(page, 'moved the cut plane');
  const full = await page.locator('#cut-time').textContent();
  await page.locator('#plane').evaluate((e) => { e.value = '0.6'; e.dispatchEvent(new Event('input')); });
  await page.waitForFunction(() => /coarse/.test(document.getElementById('cut-time').textContent));
  const coarse = await page.locator('#cut-time').textContent();
  await page.click('#save');
  await page.waitForFunction(() => /saved/.test(document.getElementById('status').textContent));
  await step(page, 'saved');
  await shot('saved');
  return {
    ok: /^ok/.test(skin) && before !== undone && redone === before,
    picked, cut_seconds: parseFloat(full), coarse_cut_seconds: parseFloat(coarse),
  };
}

async function rewrite(page) {
  await step(page, 'opened');
  await page.evaluate(() => window.editorRewriteCurves());
  const verdict = await step(page, 'rewrote every curve');
  await page.click('#save');
  await page.waitForFunction(() => /saved/.test(document.getElementById('status').textContent));
  return { ok: /^ok/.test(verdict) };
}

async function main() {
  const [cutaway, mode, target] = process.argv.slice(2);
  if (!cutaway || !['sketch', 'rewrite'].includes(mode) || !target) {
    return report({ error: 'usage: node tests/tools/edit_in_chromium.mjs CUTAWAY sketch DIR | rewrite FILE.yaml' });
  }
  const file = mode === 'sketch' ? path.join(path.resolve(target), 'new-fruit.yaml') : path.resolve(target);
  let editor = null, session = null;
  const timer = setTimeout(() => {
    editor?.child.kill();
    process.exit(report({ error: `timed out after ${TIMEOUT_MS / 1000} s` }));
  }, TIMEOUT_MS);
  try {
    editor = await startEditor(cutaway, file);
    session = await openPage(editor.origin, { webgl: true, timeoutMs: TIMEOUT_MS,
                                              warnings: result.warnings,
                                              viewport: { width: 1400, height: 900 } });
    await session.page.goto(editor.origin + '/', { timeout: TIMEOUT_MS });
    const outcome = mode === 'sketch' ? await sketch(session.page, path.resolve(target))
                                      : await rewrite(session.page);
    return report(outcome);
  } catch (e) {
    return report({ error: String(e?.message ?? e).split('\n')[0] });
  } finally {
    clearTimeout(timer);
    if (session) await session.close();
    if (editor) editor.child.kill('SIGTERM');
  }
}

process.exitCode = await main();
