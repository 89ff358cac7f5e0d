// Drives the template editor (`cutaway edit`) in headless Chromium as a person would: pointer
// strokes on the sketch canvases, the panel's controls, the Save button.
// Usage:
//   node tests/tools/edit_in_chromium.mjs CUTAWAY sketch DIR
//     starts the editor on DIR/new-fruit.yaml (not existing yet), sketches a skin profile and a
//     section, makes the object 5-fold, adds Type II chambers and redraws their section, sets
//     colours (a picker, and the eyedropper on DIR/photo.png when that file exists), undoes and
//     redoes, then saves; screenshots DIR/editor-*.png along the way.
//   node tests/tools/edit_in_chromium.mjs CUTAWAY rewrite FILE.yaml...
//     opens the first file, sets every surface's profile and section to the values they
//     already have (so their text is rewritten by the page), and saves; then has the page
//     rewrite the text of every file the same way, reporting the files whose text changed
//     ("changed").
//   node tests/tools/edit_in_chromium.mjs CUTAWAY outside FILE.yaml DIR
//     opens FILE.yaml, checks "outside", looks from the file's camera and screenshots the 3D
//     view to DIR/editor-outside.png; saves the skin's glTF the page showed to DIR/skin.glb
//     (to be rendered by another client for comparison).
// Prints one JSON line {ok, steps: [{what, verdict}], cut_seconds, coarse_cut_seconds,
// warnings, error}; exit code 0 when every step went as expected.
import fs from 'node:fs';
import path from 'node:path';
import { openPage, startEditor } from './chromium.mjs';

const TIMEOUT_MS = 240000;
const started = Date.now();
const result = { ok: false, steps: [], warnings: [], error: '' };

function report(fields) {
  Object.assign(result, fields, { seconds: (Date.now() - started) / 1000 });
  console.log(JSON.stringify(result));
  return result.ok ? 0 : 1;
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

/// Where the side view's photo lies: its scale, centre and angle.
const photoPlacement = (page) => page.evaluate(() => {
  const p = window.editorViews.side.photo;
  return { unitsPerPixel: p.unitsPerPixel, centre: p.centre, angle: p.angle };
});

const range = (n, f) => Array.from({ length: n }, (_, k) => f(k / (n - 1)));

async function sketch(page, dir) {
  const shot = (name) => page.screenshot({ path: path.join(dir, `editor-${name}.png`) });
  await step(page, 'opened an empty template');
  // The variants' strip off while sketching (seconds of CPU after every step), on again below.
  await page.uncheck('#show-variants');
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
  let picked = null, photoScale = null;
  if (fs.existsSync(photo)) {
    await page.locator('#side-photo').setInputFiles(photo);
    await page.waitForFunction(() => window.editorViews.side.photo !== null);
    // The photo's scale: a line across it said to be 70 units long; then moved 5 units right.
    const photoBefore = await photoPlacement(page);
    page.once('dialog', (d) => d.accept('70'));
    await page.check('input[name=tool][value=scale]');
    await stroke(page, 'side', [[-30, 30], [0, 30], [30, 30]]);
    await page.check('input[name=tool][value=move-photo]');
    await stroke(page, 'side', [[0, 30], [2.5, 30], [5, 30]]);
    // Turned by a quarter turn round its centre, and back.
    await page.check('input[name=tool][value=turn-photo]');
    const c = await page.evaluate(() => window.editorViews.side.photo.centre);
    const arc = (from, to) => range(12, (t) => {
      const a = from + (to - from) * t;
      return [c[0] + 25 * Math.cos(a), c[1] + 25 * Math.sin(a)];
    });
    await stroke(page, 'side', arc(0, Math.PI / 2));
    const turned = await page.evaluate(() => window.editorViews.side.photo.angle);
    await stroke(page, 'side', arc(Math.PI / 2, 0));
    await page.check('input[name=tool][value=draw]');
    photoScale = { before: photoBefore, after: await photoPlacement(page), turned };
    await page.click('#surfaces li:first-child');
    await step(page, 'selected the skin');
    await page.click('#surface .side[data-side=front] [data-eyedropper]');
    const box = await page.locator('#side').boundingBox();
    await page.mouse.click(box.x + box.width / 2, box.y + box.height / 2);
    await step(page, 'picked the skin colour from the photo');
    picked = await page.locator('#surface .side[data-side=front] input[data-stop=first]').inputValue();
  }
  // The variants' strip, switched on again, follows the last good text after a moment; while
  // it was off, none was asked for.
  if (await page.evaluate(() => document.getElementById('variants').naturalWidth > 0)) {
    throw new Error('the variants strip was drawn while switched off');
  }
  await page.check('#show-variants');
  await page.waitForFunction(() => document.getElementById('variants').naturalWidth > 0, null,
                             { timeout: TIMEOUT_MS });
  await shot('sketched');
  const before = await page.locator('#template').inputValue();
  await page.click('#undo');
  await step(page, 'undid');
  const undone = await page.locator('#template').inputValue();
  await page.click('#redo');
  await step(page, 'redid');
  const redone = await page.locator('#template').inputValue();
  // A point dragged: the skin's widest point moved 4 units outwards.
  await page.click('#surfaces li:first-child');
  await page.check('input[name=tool][value=edit]');
  const widest = await page.evaluate(() => {
    const pts = window.editorViews.side.curves[0].points;
    return pts.reduce((a, p) => (p[0] > a[0] ? p : a));
  });
  const box = await page.locator('#side').boundingBox();
  const [from, to] = await page.evaluate(([p]) =>
    [window.editorViews.side.toCanvas(p), window.editorViews.side.toCanvas([p[0] + 4, p[1]])], [widest]);
  await page.mouse.move(box.x + from[0], box.y + from[1]);
  await page.mouse.down();
  await page.mouse.move(box.x + to[0], box.y + to[1], { steps: 5 });
  await page.mouse.up();
  await step(page, 'dragged the skin\'s widest point outwards');
  const dragged = await page.evaluate(() => Math.max(...window.editorViews.side.curves[0].points.map((p) => p[0])));
  // A profile that crosses itself: the error is shown at the curve; undo takes it back.
  await page.check('input[name=tool][value=draw]');
  await stroke(page, 'side', [[0, 2], [30, 10], [5, 40], [30, 40], [5, 10], [0, 60]]);
  const refused = await step(page, 'drew a profile that crosses itself');
  const atCurve = await page.locator('#side-error').textContent();
  await shot('error');
  await page.click('#undo');
  const restored = await step(page, 'undid the bad profile');
  // Text typed into the YAML box that is not YAML, then YAML of the wrong shape: the page says
  // why and keeps working (the test fails on any page error); undo brings the fruit back.
  const good = await page.locator('#template').inputValue();
  await page.evaluate(() => { document.querySelector('details').open = true; });
  await page.locator('#template').fill('surfaces: [unclosed');
  const notYaml = await step(page, 'typed text that is not YAML');
  await page.locator('#template').fill('format: cutaway-template/1\nsurfaces: [1, null, {profile: [3, [a, b], [1, 2, 3]]}, {section: {polar: 5}}]\n');
  const wrongShape = await step(page, 'typed YAML of the wrong shape');
  await page.click('#undo');
  await page.click('#undo');
  await step(page, 'undid the typing');
  const back = await page.locator('#template').inputValue();
  await page.evaluate(() => { document.querySelector('details').open = false; });
  // The cut plane dragged: coarse cuts while it moves, a full one when it stops.
  await page.locator('#plane').fill('0.4');
  await step(page, 'moved the cut plane');
  const full = await page.locator('#cut-time').textContent();
  await page.locator('#plane').evaluate((e) => { e.value = '0.6'; e.dispatchEvent(new Event('input')); });
  await page.waitForFunction(() => /coarse/.test(document.getElementById('cut-time').textContent));
  const coarse = await page.locator('#cut-time').textContent();
  // Text typed while a cut waits behind a slow one (the server's answers held back 1.5 s): the
  // waiting cut is of the last checked text, not of the typing, which does not build (a cut of
  // it would be refused with a 422, an error in the console).
  const sectionCut = (url) => url.pathname === '/api/section.png';
  await page.route(sectionCut, async (route) => {
    await new Promise((done) => setTimeout(done, 1500));
    await route.continue();
  });
  await page.locator('#plane').evaluate((e) => {
    e.value = '0.5';
    e.dispatchEvent(new Event('input'));
    e.dispatchEvent(new Event('change'));
  });
  await page.evaluate(() => { document.querySelector('details').open = true; });
  await page.locator('#template').fill('surfaces: [unclosed');
  await page.waitForFunction(() => !/coarse/.test(document.getElementById('cut-time').textContent),
                             null, { timeout: TIMEOUT_MS });
  await page.unroute(sectionCut);
  const cutWhileTyping = await page.evaluate(() => !!document.getElementById('section').getAttribute('src'));
  await page.click('#undo');
  await page.evaluate(() => { document.querySelector('details').open = false; });
  await step(page, 'typed text that is not YAML while a cut waited, and undid it');
  await page.click('#save');
  await page.waitForFunction(() => /saved/.test(document.getElementById('status').textContent));
  await step(page, 'saved');
  await shot('saved');
  return {
    ok: /^ok/.test(skin) && before !== undone && redone === before && !/^ok/.test(refused) &&
        /^skin: /.test(atCurve) && /^ok/.test(restored) && /^YAML: /.test(notYaml) &&
        /^line /.test(wrongShape) && back === good && Math.abs(dragged - widest[0] - 4) < 0.5 &&
        cutWhileTyping,
    photo: photoScale, dragged_from: widest[0], dragged_to: dragged, error_at_curve: atCurve,
    picked, cut_seconds: parseFloat(full), coarse_cut_seconds: parseFloat(coarse),
    cut_while_typing: cutWhileTyping,
  };
}

async function outside(page, dir) {
  await step(page, 'opened the template');
  await page.uncheck('#show-variants');
  await page.check('#show-outside');
  const verdict = await step(page, 'showed the outside');
  const skin = await page.evaluate(() => Array.from(new Uint8Array(window.editorModel.shown)));
  fs.writeFileSync(path.join(dir, 'skin.glb'), Buffer.from(skin));
  await page.evaluate(() => window.editorModel.viewFromFile());
  await page.locator('#model3d').screenshot({ path: path.join(dir, 'editor-outside.png') });
  return { ok: /^ok/.test(verdict) };
}

async function rewrite(page, file) {
  await step(page, `opened ${path.basename(file)}`);
  await page.evaluate(() => window.editorRewriteCurves());
  const verdict = await step(page, `rewrote every curve of ${path.basename(file)}`);
  // A file already written as the page writes it stays the same: nothing to save.
  if (await page.locator('#save').isDisabled()) return /^ok/.test(verdict);
  await page.click('#save');
  await page.waitForFunction(() => /saved/.test(document.getElementById('status').textContent));
  return /^ok/.test(verdict);
}

/// Runs `work(page)` on the editor of `file`, in the browser of `session` (opened on first use
/// with the editor's origin; every editor gets a new page).
async function withEditor(cutaway, file, session, work, webgl) {
  const editor = await startEditor(cutaway, file);
  try {
    if (!session.open) {
      Object.assign(session, await openPage(editor.origin, {
        webgl, timeoutMs: TIMEOUT_MS, warnings: result.warnings,
        viewport: { width: 1400, height: 900 } }), { open: true });
    }
    const page = session.page;
    // Each editor has its own port: let the page reach this one.
    await page.context().unroute('**/*');
    await page.context().route('**/*', (route) =>
      route.request().url().startsWith(editor.origin + '/') ? route.continue() : route.abort());
    await page.goto(editor.origin + '/', { timeout: TIMEOUT_MS });
    return await work(page);
  } finally {
    editor.child.kill('SIGTERM');
  }
}

async function main() {
  const [cutaway, mode, ...targets] = process.argv.slice(2);
  if (!cutaway || !['sketch', 'rewrite', 'outside'].includes(mode) || !targets.length) {
    return report({ error: 'usage: node tests/tools/edit_in_chromium.mjs CUTAWAY sketch DIR | rewrite FILE.yaml... | outside FILE.yaml DIR' });
  }
  const session = { open: false };
  const timer = setTimeout(() => {
    process.exit(report({ error: `timed out after ${TIMEOUT_MS / 1000} s` }));
  }, TIMEOUT_MS);
  try {
    if (mode === 'sketch') {
      const dir = path.resolve(targets[0]);
      return report(await withEditor(cutaway, path.join(dir, 'new-fruit.yaml'), session,
                                     (page) => sketch(page, dir), true));
    }
    if (mode === 'outside') {
      const dir = path.resolve(targets[1]);
      return report(await withEditor(cutaway, path.resolve(targets[0]), session,
                                     (page) => outside(page, dir), true));
    }
    let changed = [];
    const ok = await withEditor(cutaway, path.resolve(targets[0]), session, async (page) => {
      const saved = await rewrite(page, targets[0]);
      for (const file of targets) {
        const text = fs.readFileSync(file, 'utf8');
        if (await page.evaluate((t) => window.editorRewriteText(t), text) !== text) changed.push(file);
      }
      return saved;
    }, false);
    result.changed = changed;
    return report({ ok: ok && !changed.length });
  } catch (e) {
    return report({ error: String(e?.message ?? e).split('\n')[0] });
  } finally {
    clearTimeout(timer);
    if (session.open) await session.close();
  }
}

process.exitCode = await main();
