// Drives the cutting page (cut.html) in headless Chromium: the cut face against the reading
// rule, a drag of the plane, knife strokes and frame times, with the mouse as a person would.
// Usage: node tests/tools/cut_in_chromium.mjs BASE_URL NAME... [--out DIR]
//   BASE_URL serves /cut.html, /cutting_view.js, /lib/three/... and
//   /api/volume/NAME.{json,colour.png,structure.png,material.png,glb}.
// or:    node tests/tools/cut_in_chromium.mjs --cutaway CUTAWAY FILE.yaml... [--out DIR]
//          [--volume-voxels N]
//   starts `cutaway edit FILE --port 0 --volume-voxels N` for each template file, the server
//   the page is made for, and opens the page on it (NAME: the file's `name:`).
// For each NAME the page is opened on ?volume=/api/volume/NAME.json&model=/api/volume/NAME.glb:
//   bytes: the page's flipbooks against this tool's own decoding of the PNGs (bytes_ok);
//   (a) planes through the object's centre with several normals, and offset ones: about 30
//       points of the cut face each, the drawn pixel against the page's CPU reading of the
//       volume (max_diff, mean_diff: largest channel difference, 0..255; points within 1.5 px
//       of a change of region are left out), and empty points, where the cap must draw nothing;
//   (b) the plane's handle dragged along the normal (drag_ok: the offset moved as dragged and
//       the camera stayed), then the Flip button;
//   (c) knife strokes, Shift-drag and the Knife button (knife_ok: the new normal is
//       perpendicular to the stroke's rays, i.e. the plane holds the stroke and the view
//       direction);
//   (d) frame times over about 30 frames while Alt-dragging the plane.
// With --stones, only the bytes and (e): a plane through each stone's centre, seen head-on,
//   then flipped: the half that holds the stone shows it whole, the other its cavity in the
//   flesh's colour where the cap would read the stone's inside (stones_ok).
// Screenshots go to DIR/cut-NAME-*.png when --out is given.
// Prints one JSON line {ok, pages: [{name, cap_points, max_diff, mean_diff, knife_ok, drag_ok,
// frame_ms_mean, frame_ms_p95, ...}], warnings, error}; exit code 0 when ok.
import fs from 'node:fs';
import path from 'node:path';
import zlib from 'node:zlib';
import { decodePng } from '../../app/edit/web/png_decode.js';
import { openPage, startEditor } from './chromium.mjs';

const TIMEOUT_MS = 300000;
const VIEWPORT = { width: 960, height: 720 };
const POINTS_PER_PLANE = 30;
const EMPTY_PER_PLANE = 10;
const MAX_DIFF = 2;        // 8-bit rounding, and float32 on the GPU against float64 here
const MEAN_DIFF = 1;
const started = Date.now();
const result = { ok: false, pages: [], warnings: [], error: '' };
let onlyStones = false;  // --stones: the bytes and the stones' check only

function report(fields) {
  Object.assign(result, fields, { seconds: (Date.now() - started) / 1000 });
  console.log(JSON.stringify(result));
  return result.ok ? 0 : 1;
}

// --- the page's bytes ----------------------------------------------------------------------

/// FNV-1a (32 bits) of `data`, as the page's volumeDigest() computes it.
function digest(data) {
  let h = 0x811c9dc5;
  for (let i = 0; i < data.length; ++i) h = Math.imul(h ^ data[i], 0x01000193) >>> 0;
  return h.toString(16).padStart(8, '0');
}

/// The page's flipbooks against the files decoded here (png_decode.js with node's zlib), and
/// the decoding against what the sidecar counts: the solid voxels (region not 0, and colour
/// alpha 255) and the largest region id. The files are asked for as the page asks: with POST and
/// the token the page holds when `cutaway edit` served it, else with GET.
async function checkBytes(page, base, name) {
  const token = await page.evaluate(
    () => document.querySelector('meta[name="cutaway-token"]')?.content ?? '');
  const asking = token ? { method: 'POST', headers: { 'X-Cutaway-Token': token } } : {};
  const meta = await (await fetch(`${base}/api/volume/${name}.json`, asking)).json();
  const mine = {}, images = {};
  for (const [which, file] of Object.entries(meta.images)) {
    const response = await fetch(new URL(file, `${base}/api/volume/${name}.json`), asking);
    if (!response.ok) throw new Error(`${file}: HTTP ${response.status}`);
    images[which] = (await decodePng(new Uint8Array(await response.arrayBuffer()),
                                     (bytes) => zlib.inflateSync(bytes))).data;
    mine[which] = digest(images[which]);
  }
  const theirs = await page.evaluate(() => window.cutting.volumeDigest());
  const differing = Object.keys(mine).filter((k) => mine[k] !== theirs[k]);
  let solid = 0, opaque = 0, largest = 0;
  for (let p = 0; p < images.structure.length; p += 4) {
    const region = images.structure[p] + 256 * images.structure[p + 1];
    solid += region !== 0;
    largest = Math.max(largest, region);
    opaque += images.colour[p + 3] === 255;
  }
  const counts_ok = solid === meta.solid_voxels && opaque === meta.solid_voxels &&
                    largest === meta.regions;
  return { bytes_ok: differing.length === 0 && counts_ok, bytes_differing: differing,
           counts_ok };
}

// --- vectors ---------------------------------------------------------------------------------

const sub = (a, b) => a.map((x, i) => x - b[i]);
const dot = (a, b) => a.reduce((s, x, i) => s + x * b[i], 0);
const cross = (a, b) => [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2],
                         a[0] * b[1] - a[1] * b[0]];
const unit = (a) => { const l = Math.hypot(...a); return a.map((x) => x / l); };
const scaled = (a, s) => a.map((x) => x * s);
const add = (a, b) => a.map((x, i) => x + b[i]);

// --- (a) the cut face against the reading rule -------------------------------------------------

/// In the page: picks points of the cut face at pixel centres (a seeded shuffle of a grid over
/// the canvas), leaving out those within 1.5 px of a change of region, taking the regions in
/// turn so that small ones (seeds) get points too, and compares the drawn pixel with the CPU
/// reading. Empty points: the pixel must be the same with the cap hidden.
async function comparePlane(page, seed) {
  return page.evaluate(async ([want, wantEmpty, seed0]) => {
    const c = window.cutting;
    c.showHandle(false);
    await c.nextFrame();
    const [w, h] = c.info().canvas;
    let seed = seed0 >>> 0;
    const random = () => {
      seed = (Math.imul(seed, 1664525) + 1013904223) >>> 0;
      return seed / 4294967296;
    };
    const regionAt = (x, y) => {
      const p = c.pointOnPlane(x, y);
      return p ? c.sampleVolume(...p).region : -1;
    };
    const cells = [];
    for (let y = 4; y < h - 4; y += 3) for (let x = 4; x < w - 4; x += 3) cells.push([x, y]);
    for (let i = cells.length - 1; i > 0; --i) {
      const j = Math.floor(random() * (i + 1));
      [cells[i], cells[j]] = [cells[j], cells[i]];
    }
    const ring = [[1.5, 0], [-1.5, 0], [0, 1.5], [0, -1.5],
                  [1.06, 1.06], [1.06, -1.06], [-1.06, 1.06], [-1.06, -1.06]];
    const byRegion = new Map(), empty = [];
    let candidates = 0, nearOutline = 0, inside = 0;
    const { box } = c.info();
    const inBox = (p) => p.every((v, a) => v >= box.min[a] && v <= box.max[a]);
    for (const [ix, iy] of cells) {
      if (candidates >= 20 * want && empty.length >= wantEmpty) break;
      const x = ix + 0.5, y = iy + 0.5;
      const p = c.pointOnPlane(x, y);
      if (!p || !inBox(p)) continue;
      ++inside;
      const s = c.sampleVolume(...p);
      if (ring.some(([dx, dy]) => regionAt(x + dx, y + dy) !== s.region)) {
        ++nearOutline;
        continue;
      }
      if (s.region) {
        if (!byRegion.has(s.region)) byRegion.set(s.region, []);
        byRegion.get(s.region).push({ x, y, p, s });
        ++candidates;
      } else if (empty.length < wantEmpty) {
        empty.push({ x, y, p });
      }
    }
    const solid = [];
    for (let round = 0; solid.length < want && solid.length < candidates; ++round) {
      for (const list of byRegion.values()) {
        if (round < list.length && solid.length < want) solid.push(list[round]);
      }
    }
    const diffs = solid.map((q) => {
      const got = c.capPixel(q.x, q.y);
      return { ...q, got, diff: Math.max(...got.map((v, k) => Math.abs(v - q.s.rgb[k]))) };
    });
    const withCap = empty.map((q) => c.capPixel(q.x, q.y));
    c.showCap(false);
    await c.nextFrame();
    const emptyMismatches = empty.filter((q, i) =>
      c.capPixel(q.x, q.y).some((v, k) => v !== withCap[i][k])).length;
    c.showCap(true);
    c.showHandle(true);
    await c.nextFrame();
    const worst = diffs.reduce((m, d) => (!m || d.diff > m.diff ? d : m), null);
    return {
      points: diffs.length, diffs: diffs.map((d) => d.diff), empty: empty.length,
      empty_mismatches: emptyMismatches, near_outline: nearOutline, inside,
      regions: [...new Set(diffs.map((d) => d.s.region))].sort((a, b) => a - b),
      worst: worst && { at: [worst.x, worst.y], want: worst.s.rgb, got: worst.got,
                        region: worst.s.region },
    };
  }, [POINTS_PER_PLANE, EMPTY_PER_PLANE, seed]);
}

async function checkPlanes(page, info, shot) {
  const c = info.centre, r = info.radius;
  const planes = [
    { what: 'centre +z', point: c, normal: [0, 0, 1] },
    { what: 'centre +x', point: c, normal: [1, 0, 0] },
    { what: 'centre +y', point: c, normal: [0, 1, 0] },
    { what: 'centre -x', point: c, normal: [-1, 0, 0] },
    { what: 'centre oblique', point: c, normal: unit([1, 1, 1]) },
    { what: 'centre oblique 2', point: c, normal: unit([0.8, -0.4, 0.45]) },
    { what: 'offset +z', point: add(c, [0, 0, 0.3 * r]), normal: [0, 0, 1] },
    { what: 'offset -x', point: add(c, [-0.35 * r, 0, 0]), normal: [1, 0, 0] },
    { what: 'offset y', point: add(c, [0, 0.25 * r, 0]), normal: unit([0.2, 1, 0.1]) },
  ];
  const out = [];
  for (const [i, plane] of planes.entries()) {
    await page.evaluate(([p, n]) => {
      window.cutting.setPlane(p, n);
      window.cutting.faceCap(25);
    }, [plane.point, plane.normal]);
    const got = await comparePlane(page, 1234 + i);
    out.push({ what: plane.what, ...got });
    await shot(`plane${i}`);
  }
  return out;
}

// --- (b) dragging the handle, flipping ---------------------------------------------------------

async function checkDrag(page, box, info, shot) {
  await page.evaluate(([p]) => {
    window.cutting.setPlane(p, [0, 0, 1]);
    window.cutting.frameView();
  }, [info.centre]);
  await page.evaluate(() => window.cutting.nextFrame());
  const before = await page.evaluate(() => ({ plane: window.cutting.plane(),
                                              camera: window.cutting.camera(),
                                              handle: window.cutting.handle() }));
  const { foot, tip } = before.handle;
  const along = unit(sub(tip, foot));
  const grab = [foot[0] + 0.6 * (tip[0] - foot[0]), foot[1] + 0.6 * (tip[1] - foot[1])];
  const pull = 50;   // pixels along the handle, towards its tip
  await page.mouse.move(box.x + grab[0], box.y + grab[1]);
  await page.mouse.down();
  for (let k = 1; k <= 10; ++k) {
    const t = (pull * k) / 10;
    await page.mouse.move(box.x + grab[0] + along[0] * t, box.y + grab[1] + along[1] * t);
  }
  await page.mouse.up();
  await page.evaluate(() => window.cutting.nextFrame());
  const after = await page.evaluate(() => ({ plane: window.cutting.plane(),
                                             camera: window.cutting.camera() }));
  await shot('dragged');
  const moved = after.plane.offset - before.plane.offset;
  // Pulling the handle by its own length on the screen moves the plane by its length.
  const handlePx = Math.hypot(tip[0] - foot[0], tip[1] - foot[1]);
  const expected = (pull / handlePx) * before.handle.length_m;
  const cameraStill = Math.hypot(...sub(after.camera.position, before.camera.position)) <
                      1e-9 + 1e-6 * info.radius;
  const dragOk = Math.abs(moved - expected) < 0.1 * expected && cameraStill &&
                 Math.abs(dot(after.plane.normal, [0, 0, 1]) - 1) < 1e-9;

  // The Flip button: the same plane, the other side kept.
  await page.click('#flip');
  await page.evaluate(() => window.cutting.nextFrame());
  const flipped = await page.evaluate(() => window.cutting.plane());
  await shot('flipped');
  const flipOk = dot(flipped.normal, after.plane.normal) < -0.999999 &&
                 Math.abs(dot(sub(flipped.point, after.plane.point), after.plane.normal)) < 1e-9;
  return { drag_ok: dragOk, flip_ok: flipOk, drag_offset_mm: moved * 1000,
           drag_expected_mm: expected * 1000, drag_camera_still: cameraStill };
}

// --- (c) the knife ---------------------------------------------------------------------------

/// Draws a stroke from `from` to `to` (canvas CSS pixels); `how`: 'shift' or 'button'. The
/// expected normal is that of the plane through the two rays of the stroke's ends, taken before
/// the stroke (the page turns the camera afterwards).
async function knifeStroke(page, box, from, to, how, shot = null) {
  await page.evaluate(() => { window.cutting.frameView(); return window.cutting.nextFrame(); });
  const rays = await page.evaluate(([a, b]) => [window.cutting.ray(...a), window.cutting.ray(...b)],
                                   [from, to]);
  const expected = unit(cross(rays[0].direction, rays[1].direction));
  if (how === 'button') await page.click('#knife');
  else await page.keyboard.down('Shift');
  await page.mouse.move(box.x + from[0], box.y + from[1]);
  await page.mouse.down();
  for (let k = 1; k <= 12; ++k) {
    const t = k / 12;
    await page.mouse.move(box.x + from[0] + (to[0] - from[0]) * t,
                          box.y + from[1] + (to[1] - from[1]) * t);
    if (k === 9 && shot) await shot('knife-stroke');   // the stroke's trace, drawn so far
  }
  await page.mouse.up();
  if (how !== 'button') await page.keyboard.up('Shift');
  await page.evaluate(() => window.cutting.idle());
  const plane = await page.evaluate(() => window.cutting.plane());
  const alignment = Math.abs(dot(plane.normal, expected));
  // The plane holds the camera (the rays' common origin) and so both rays.
  const throughEye = Math.abs(dot(sub(rays[0].origin, plane.point), plane.normal));
  const armed = await page.locator('#knife').getAttribute('aria-pressed');
  return { how, alignment, through_eye_m: throughEye, normal: plane.normal,
           ok: alignment > 0.9999 && throughEye < 1e-6 && armed === 'false' };
}

async function checkKnife(page, box, info, shot) {
  const [cx, cy] = await page.evaluate((p) => window.cutting.project(...p), info.centre);
  const span = Math.min(box.width, box.height) * 0.3;
  const strokes = [
    await knifeStroke(page, box, [cx - span, cy - 0.4 * span], [cx + span, cy + 0.3 * span],
                      'shift', shot),
  ];
  await shot('knife-shift');
  strokes.push(await knifeStroke(page, box, [cx - 0.2 * span, cy - span],
                                 [cx + 0.3 * span, cy + span], 'button'));
  await shot('knife-button');
  return { knife_ok: strokes.every((s) => s.ok), knife: strokes };
}

// --- (d) frame times while dragging ------------------------------------------------------------

async function checkFrames(page, box, info) {
  await page.evaluate(([p]) => {
    window.cutting.setPlane(p, [0, 0, 1]);
    window.cutting.frameView();
    return window.cutting.nextFrame();
  }, [info.centre]);
  const x = box.x + box.width * 0.7, y0 = box.y + box.height * 0.5;
  await page.evaluate(() => window.cutting.resetFrameStats());
  await page.keyboard.down('Alt');
  await page.mouse.move(x, y0);
  await page.mouse.down();
  for (let k = 1; k <= 30; ++k) {
    const y = y0 + 60 * Math.sin((k / 30) * 2 * Math.PI);
    const seen = await page.evaluate(() => window.cutting.frameStats().frames);
    await page.mouse.move(x, y);
    await page.waitForFunction((n) => window.cutting.frameStats().frames > n, seen,
                               { timeout: 10000 });
  }
  await page.mouse.up();
  await page.keyboard.up('Alt');
  const stats = await page.evaluate(() => window.cutting.frameStats());
  return { frames: stats.frames, frame_ms_mean: stats.mean_ms, frame_ms_p95: stats.p95_ms };
}

// --- one page ----------------------------------------------------------------------------------

async function checkName(page, base, name, out) {
  const entry = { name };
  const shot = async (what) => {
    if (!out) return;
    await page.evaluate(() => window.cutting.nextFrame());
    await page.screenshot({ path: path.join(out, `cut-${name}-${what}.png`) });
  };
  const query = `volume=/api/volume/${name}.json&model=/api/volume/${name}.glb`;
  await page.goto(`${base}/cut.html?${query}`, { timeout: TIMEOUT_MS });
  await page.waitForFunction(() => window.cutting && window.cutting.ready, null,
                             { timeout: TIMEOUT_MS });
  await page.evaluate(() => window.cutting.ready);
  const info = await page.evaluate(() => window.cutting.info());
  entry.template = info.template;
  await shot('opened');
  Object.assign(entry, await checkBytes(page, base, name));

  if (onlyStones) {
    Object.assign(entry, await checkStones(page, base, name, shot));
    entry.ok = entry.bytes_ok && entry.stones_ok;
    return entry;
  }
  const planes = await checkPlanes(page, info, shot);
  const diffs = planes.flatMap((p) => p.diffs);
  entry.cap_points = diffs.length;
  entry.max_diff = diffs.length ? Math.max(...diffs) : null;
  entry.mean_diff = diffs.length ? diffs.reduce((a, b) => a + b, 0) / diffs.length : null;
  entry.regions_compared = [...new Set(planes.flatMap((p) => p.regions))].length;
  entry.empty_points = planes.reduce((s, p) => s + p.empty, 0);
  entry.empty_mismatches = planes.reduce((s, p) => s + p.empty_mismatches, 0);
  entry.planes = planes.map(({ diffs: d, ...rest }) => ({ ...rest,
    max_diff: d.length ? Math.max(...d) : null }));

  const box = await page.locator('#view').boundingBox();
  Object.assign(entry, await checkDrag(page, box, info, shot));
  Object.assign(entry, await checkKnife(page, box, info, shot));
  Object.assign(entry, await checkFrames(page, box, info));
  await shot('end');

  entry.cap_ok = entry.cap_points >= planes.length * POINTS_PER_PLANE * 0.5 &&
                 entry.max_diff <= MAX_DIFF && entry.mean_diff <= MEAN_DIFF &&
                 entry.empty_mismatches === 0;
  entry.ok = entry.cap_ok && entry.bytes_ok && entry.drag_ok && entry.flip_ok &&
             entry.knife_ok && entry.frames >= 25;
  return entry;
}

// --- (e) stones kept whole --------------------------------------------------------------------

/// Cuts through each stone's centre both ways. The half that holds the stone must show it at
/// the centre (nearer its own colour than the flesh's), the other its cavity: nearer the
/// flesh's colour, and the pixel the same with the cap hidden (the cap is not drawn over the
/// cavity, where it would read the stone's inside).
async function checkStones(page, base, name, shot) {
  const stones = await page.evaluate(() => window.cutting.stones());
  const token = await page.evaluate(
    () => document.querySelector('meta[name="cutaway-token"]')?.content ?? '');
  const asking = token ? { method: 'POST', headers: { 'X-Cutaway-Token': token } } : {};
  const meta = await (await fetch(`${base}/api/volume/${name}.json`, asking)).json();
  const out = [];
  for (const [k, stone] of stones.entries()) {
    const spec = meta.stones[k];
    const mean = (list) => [0, 1, 2].map((a) =>
      list.filter((_, i) => i % 3 === a).reduce((s, v) => s + v, 0) / (list.length / 3));
    const cavity = mean(spec.flesh_srgb);
    const own = mean(spec.stone_srgb);
    const views = [];
    for (const normal of [[0, 0, 1], [0, 0, -1]]) {
      const seen = await page.evaluate(async ([p, n]) => {
        const c = window.cutting;
        c.setPlane(p, n);
        c.faceCap(0);
        c.showHandle(false);
        await c.nextFrame();
        const [x, y] = c.project(...p);
        const state = c.stones();
        const got = c.capPixel(x, y);
        c.showCap(false);
        await c.nextFrame();
        const uncapped = c.capPixel(x, y);
        c.showCap(true);
        c.showHandle(true);
        return { state, got, uncapped, volume: c.sampleVolume(...p).rgb };
      }, [stone.centre, normal]);
      await shot(`stone${k}-${normal[2] > 0 ? 'front' : 'back'}`);
      const s = seen.state[k];
      const far = (a, b) => Math.max(...a.map((v, i) => Math.abs(v - b[i])));
      views.push({ normal, holds: s.holds, kept: s.kept, pixel: seen.got, volume: seen.volume,
                   to_flesh: far(seen.got, cavity), to_own: far(seen.got, own),
                   cap_drawn: far(seen.got, seen.uncapped) > 1 });
    }
    const holder = views.find((v) => v.holds), other = views.find((v) => !v.holds);
    const ok = !!holder && !!other && holder.to_own < holder.to_flesh &&
               other.to_flesh < other.to_own && !other.cap_drawn && !holder.cap_drawn;
    out.push({ surface: stone.surface, flesh_srgb: cavity, stone_srgb: own, views, ok });
  }
  return { stones: out, stones_ok: out.length > 0 && out.every((s) => s.ok) };
}

/// Removes `flag` and the value after it from `args`; returns the value (null when absent).
function takeOption(args, flag) {
  const at = args.indexOf(flag);
  if (at < 0) return null;
  const value = args[at + 1] ?? '';
  args.splice(at, 2);
  return value;
}

/// Runs checkName for `name` on a page of its own that may talk to `base` only.
async function checkOn(base, name, out) {
  const browser = await openPage(new URL(base).origin, { webgl: true, viewport: VIEWPORT,
                                                         warnings: result.warnings });
  try {
    const before = result.warnings.length;
    const entry = await checkName(browser.page, base, name, out);
    if (result.warnings.slice(before).some((w) => w.startsWith('pageerror'))) entry.ok = false;
    return entry;
  } finally {
    await browser.close();
  }
}

async function main() {
  const args = process.argv.slice(2);
  const out = takeOption(args, '--out');
  const cutaway = takeOption(args, '--cutaway');
  const voxels = takeOption(args, '--volume-voxels');
  const stonesAt = args.indexOf('--stones');
  if (stonesAt >= 0) {
    onlyStones = true;
    args.splice(stonesAt, 1);
  }
  const usage = 'usage: node tests/tools/cut_in_chromium.mjs BASE_URL NAME... [--out DIR] | ' +
                '--cutaway CUTAWAY FILE.yaml... [--out DIR] [--volume-voxels N]';
  if (out === '' || cutaway === '' || voxels === '' || !args.length ||
      (!cutaway && args.length < 2)) {
    return report({ error: usage });
  }
  if (out) fs.mkdirSync(out, { recursive: true });
  const timer = setTimeout(() => {
    process.exit(report({ error: `timed out after ${TIMEOUT_MS / 1000} s` }));
  }, TIMEOUT_MS);
  try {
    if (!cutaway) {
      const [baseArg, ...names] = args;
      const base = baseArg.replace(/\/+$/, '');
      for (const name of names) result.pages.push(await checkOn(base, name, out));
    }
    for (const file of cutaway ? args : []) {
      const name = /^name:\s*["']?([a-z0-9_-]+)/m.exec(fs.readFileSync(file, 'utf8'))?.[1];
      if (!name) return report({ error: `${file}: no template name` });
      const editor = await startEditor(cutaway, file, voxels ? ['--volume-voxels', voxels] : []);
      try {
        result.pages.push(await checkOn(editor.origin, name, out));
      } finally {
        editor.child.kill('SIGTERM');
      }
    }
    return report({ ok: result.pages.every((p) => p.ok) });
  } catch (e) {
    return report({ error: String(e?.message ?? e).split('\n')[0] });
  } finally {
    clearTimeout(timer);
  }
}

process.exitCode = await main();
