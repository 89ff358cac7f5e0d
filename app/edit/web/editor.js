// The template editor's page (the paper's §4 sketching interface): profiles are sketched in the
// side view and sections in the top view, over photos of the real object; colours come from
// pickers or from the photos; every change edits the template's YAML (template_doc.js) and is
// sent to the server, whose library answers with the verdict (the same parser and checks as
// `cutaway check`), the curves as it fits them, the model in 3D and a cross-section. Nothing
// about the model is computed here.
import { TemplateDoc, starterText } from '/template_doc.js';
import { fitStroke } from '/stroke_fit.js';
import { SketchView } from '/sketch_view.js';
import { ModelView } from '/model_view.js';
import { ask } from '/server_request.js';

const $ = (id) => document.getElementById(id);
const text = $('template');
const verdictLine = $('verdict');
const statusLine = $('status');

let doc = new TemplateDoc('');
let saved = '';                 // the text on disk
const past = [], future = [];   // undo history: texts
let selected = 0;               // the selected surface
let selectedHeight = 0;         // of a surface with `sections`: the one the top view edits
let verdict = null;             // the last answer of /api/check
let verdictText = '';           // the text `verdict` answers: the views show it, never newer
                                // text still being checked (which may not build)
let version = 0;                // of the text sent; older answers are dropped
let framed = false;             // the 3D view is framed on the first model

// ---- reading the template -------------------------------------------------------------------

/// The surfaces as written; an item that is not a mapping reads as {} (the verdict says why).
const surfaces = () => {
  const list = doc.get(['surfaces']);
  return Array.isArray(list) ? list.map((s) => (s && typeof s === 'object' ? s : {})) : [];
};
const isNfold = () => doc.get(['symmetry', 'type']) === 'nfold';
const folds = () => (isNfold() ? Number(doc.get(['symmetry', 'folds'])) || 1 : 1);
/// The [a, b] points of a curve as written, leaving out what is not a pair of numbers (the
/// verdict says what is wrong with them).
const pairs = (list) => (Array.isArray(list) ? list : []).filter((p) =>
  Array.isArray(p) && p.length === 2 && p.every((c) => typeof c === 'number'));
const isLoopList = (s) => Array.isArray(s) && Array.isArray(s[0]) && Array.isArray(s[0][0]);
/// A surface's sections at several heights (`sections`), or null when it has one `section`.
const heightsOf = (s) => (Array.isArray(s?.sections) ? s.sections : null);
/// The height of `s`'s sections that the top view edits (0 when it has one section).
const heightOf = (s) => Math.min(selectedHeight, Math.max(0, (heightsOf(s)?.length ?? 1) - 1));
/// The section of `s` that the top view shows and edits, and the path of surface i's.
const sectionOf = (s) => (heightsOf(s) ? heightsOf(s)[heightOf(s)]?.section : s?.section);
const sectionPath = (i) => {
  const s = surfaces()[i];
  return heightsOf(s) ? ['surfaces', i, 'sections', heightOf(s), 'section']
                      : ['surfaces', i, 'section'];
};

/// A section as loops of view points (top view: [x, -z]); polar points become [x, -z] too.
function sectionLoops(section) {
  if (!section || section === 'circle') return [];
  if (section.polar) {
    return [pairs(section.polar).map(([deg, r]) => [r * Math.cos(deg * Math.PI / 180),
                                               r * Math.sin(deg * Math.PI / 180)])];
  }
  const loops = isLoopList(section) ? section : [section];
  return loops.map((loop) => pairs(loop).map(([x, z]) => [x, -z]));
}

function circle(radius) {
  return Array.from({ length: 64 }, (_, k) => [radius * Math.cos(k * Math.PI / 32),
                                               radius * Math.sin(k * Math.PI / 32)]);
}

function maxRadius(profile) {
  return Math.max(1e-9, ...pairs(profile).map((p) => Math.abs(p[0])));
}

function hex(colour) {
  if (typeof colour === 'string') return colour;
  if (Array.isArray(colour)) {
    return '#' + colour.map((c) => Math.round(255 * Math.min(1, Math.max(0, c)))
      .toString(16).padStart(2, '0')).join('');
  }
  // a stop of a gradient along ripeness may itself be a gradient: show its first colour
  if (colour && Array.isArray(colour.stops)) return hex(colour.stops[0]?.[1]);
  return '#808080';
}

/// Which surface and which of its fields the verdict's field path names, if any.
function errorPlace() {
  if (!verdict || verdict.ok) return null;
  const m = /^surfaces\[(\d+)\](?:\.(\w+))?/.exec(verdict.field ?? '');
  return m ? { surface: Number(m[1]), field: m[2] ?? '' } : null;
}

// ---- the sketch views ------------------------------------------------------------------------

const side = new SketchView($('side'), {
  stroke: (points) => sideStroke(points),
  movePoint: (curve, index, point, done) => movePoint('side', curve, index, point, done),
  scale: askLength,
  pick: (c) => pickColour(c),
});
const top = new SketchView($('top'), {
  stroke: (points) => topStroke(points),
  movePoint: (curve, index, point, done) => movePoint('top', curve, index, point, done),
  scale: askLength,
  pick: (c) => pickColour(c),
});
let sideCurves = [], topCurves = [];   // which surface (and loop) each drawn curve is

function askLength(worldLength) {
  const answer = prompt(`Length of this line in ${doc.get(['units']) ?? 'mm'}?`,
                        worldLength.toFixed(1));
  return Number(answer);
}

function layoutCurves() {
  const list = surfaces();
  const place = errorPlace();
  const fitted = verdict && verdict.ok ? verdict.curves : null;
  side.curves = [];
  sideCurves = [];
  top.curves = [];
  topCurves = [];
  list.forEach((s, i) => {
    const profile = pairs(s.profile);
    if (!profile.length) return;
    const colour = s.role === 'skin' ? '#b02a1a' : s.kind === 'within' ? '#b07a10' : '#2a6ab0';
    const chosen = i === selected;
    const bad = place && place.surface === i;
    side.curves.push({ points: profile, closed: s.kind === 'within',
                       fitted: fitted?.[i]?.profile, mirror: s.kind !== 'within', colour,
                       selected: chosen,
                       error: bad && !['section', 'sections'].includes(place.field) });
    sideCurves.push({ surface: i });
    const section = sectionOf(s);
    let loops = sectionLoops(section);
    // The server fits the first of a surface's sections at several heights.
    let fittedLoops = heightOf(s) === 0
      ? fitted?.[i]?.sections?.map((l) => l.map(([x, z]) => [x, -z])) : undefined;
    if (!loops.length && s.kind === 'around') loops = [circle(maxRadius(profile))];
    loops.forEach((loop, k) => {
      top.curves.push({ points: loop, closed: true, fitted: fittedLoops?.[k], colour,
                        selected: chosen && !(section === 'circle' || !section),
                        error: bad && (place.field === 'section' || place.field === 'sections') });
      topCurves.push({ surface: i, loop: k });
    });
    // The selected surface's other heights, drawn faintly for comparison.
    if (chosen) {
      (heightsOf(s) ?? []).forEach((h, k) => {
        if (k === heightOf(s)) return;
        for (const loop of sectionLoops(h?.section)) {
          top.curves.push({ points: [], fitted: loop, closed: true, colour: '#9a9a9a',
                            selected: false });
          topCurves.push({ surface: i, ghost: true });
        }
      });
    }
    // A within surface drawn once is repeated in every fold: show the copies.
    if (s.kind === 'within' && loops.length === 1 && folds() > 1) {
      for (let f = 1; f < folds(); ++f) {
        const a = 2 * Math.PI * f / folds();
        const turned = (fittedLoops?.[0] ?? loops[0]).map(([u, v]) =>
          [u * Math.cos(a) - v * Math.sin(a), u * Math.sin(a) + v * Math.cos(a)]);
        top.curves.push({ points: [], fitted: turned, closed: true, colour, selected: false });
        topCurves.push({ surface: i, ghost: true });
      }
    }
  });
  side.guides = [{ angle: Math.PI / 2, dashed: true }];
  top.guides = [];
  for (let f = 0; f < folds() && folds() > 1; ++f) {
    top.guides.push({ angle: (f + 0.5) * 2 * Math.PI / folds(), dashed: true, ray: true });
  }
  side.draw();
  top.draw();
}

/// Frames both views on the model (or on a default 100 x 100 box for an empty template).
function frameViews() {
  if (verdict && verdict.ok) {
    const lo = verdict.bbox_min, hi = verdict.bbox_max;
    const r = 1.15 * Math.max(Math.abs(lo[0]), hi[0], Math.abs(lo[2]), hi[2]);
    const pad = 0.08 * (hi[1] - lo[1]);
    side.frame(-r, r, lo[1] - pad, hi[1] + pad);
    top.frame(-r, r, -r, r);
  } else {
    side.frame(-50, 50, -10, 90);
    top.frame(-50, 50, -50, 50);
  }
}

function sideStroke(stroke) {
  const list = surfaces();
  if (!list.length) {
    const profile = axisProfile(stroke, true);
    commit(doc.set(['surfaces'], [{ name: 'skin', kind: 'around', role: 'skin', profile,
                                    front: '#c03020', back: '#e06040', blur: 0.5 }]));
    return;
  }
  const s = list[selected];
  if (!s || s.kind === 'mesh') return;
  const profile = s.kind === 'within'
    ? fitStroke(stroke.map(([u, v]) => [Math.abs(u), v]), { closed: true, minPoints: 6 })
    : axisProfile(stroke, s.role === 'skin');
  commit(doc.set(['surfaces', selected, 'profile'], profile));
}

/// A profile around the axis from a stroke drawn on either side of it: r = |u|, ordered bottom
/// to top; ends near the axis (or any end, for the skin, which must be closed) are put on it.
function axisProfile(stroke, closeBothEnds) {
  let pts = fitStroke(stroke.map(([u, v]) => [Math.abs(u), v]), { minPoints: 4 });
  if (pts[0][1] > pts[pts.length - 1][1]) pts = pts.reverse();
  const r = maxRadius(pts);
  for (const k of [0, pts.length - 1]) {
    if (closeBothEnds || pts[k][0] < 0.12 * r) pts[k] = [0, pts[k][1]];
  }
  return pts;
}

function topStroke(stroke) {
  const s = surfaces()[selected];
  if (!s || s.kind === 'mesh') return;
  const loop = fitStroke(stroke, { closed: true, minPoints: 6 }).map(([u, v]) => [u, -v]);
  if (s.kind === 'within' && isLoopList(sectionOf(s))) {
    // Replace the loop of the fold the stroke was drawn in.
    const cx = stroke.reduce((a, p) => a + p[0], 0), cy = stroke.reduce((a, p) => a + p[1], 0);
    const angle = (Math.atan2(cy, cx) + 2 * Math.PI) % (2 * Math.PI);
    const fold = Math.round(angle / (2 * Math.PI / folds())) % folds();
    commit(doc.set([...sectionPath(selected), fold], loop));
  } else {
    commit(doc.set(sectionPath(selected), loop));
  }
}

function movePoint(view, curve, index, point, done) {
  if (!done) return;  // the view moves the point on screen; the file changes on release
  if (view === 'side') {
    const i = sideCurves[curve].surface;
    const [u, v] = point;
    commit(doc.set(['surfaces', i, 'profile', index], [Math.round(Math.abs(u) * 100) / 100,
                                                       Math.round(v * 100) / 100]));
    return;
  }
  const { surface, loop } = topCurves[curve];
  const section = sectionOf(surfaces()[surface]);
  const [u, v] = point.map((c) => Math.round(c * 100) / 100);
  if (section.polar) {
    const deg = Math.round(((Math.atan2(v, u) * 180 / Math.PI + 360) % 360) * 100) / 100;
    commit(doc.set([...sectionPath(surface), 'polar', index], [deg, Math.round(Math.hypot(u, v) * 100) / 100]));
  } else {
    const path = isLoopList(section) ? [...sectionPath(surface), loop, index] : [...sectionPath(surface), index];
    commit(doc.set(path, [u, -v]));
  }
}

for (const radio of document.querySelectorAll('input[name=tool]')) {
  radio.addEventListener('change', () => { side.tool = top.tool = radio.value; hint(); });
}

function hint() {
  const tips = {
    draw: 'Draw a profile in the side view and a section in the top view; they replace the selected surface\'s curves.',
    edit: 'Drag a point of the selected surface.',
    scale: 'Draw a line over something of known length in the photo.',
    'move-photo': 'Drag the photo so that the object\'s axis lies on the dashed line.',
    'turn-photo': 'Drag round the photo\'s centre to turn it upright.',
    eyedropper: 'Click the photo to take its colour.',
  };
  $('hint').textContent = tips[side.tool] ?? '';
}

function openPhoto(view, file) {
  if (!file || !file.type.startsWith('image/')) return;
  const image = new Image();
  image.onload = () => view.setPhoto(image);
  image.src = URL.createObjectURL(file);
}
for (const [view, input] of [[side, $('side-photo')], [top, $('top-photo')]]) {
  input.addEventListener('change', () => openPhoto(view, input.files[0]));
  view.canvas.addEventListener('dragover', (e) => e.preventDefault());
  view.canvas.addEventListener('drop', (e) => {
    e.preventDefault();
    openPhoto(view, e.dataTransfer.files[0]);
  });
}

// ---- the panel -------------------------------------------------------------------------------

function fillPanel() {
  const list = surfaces();
  selected = Math.min(selected, Math.max(0, list.length - 1));
  $('symmetry').value = isNfold() ? 'nfold' : 'cylindrical';
  $('folds').value = folds() > 1 ? folds() : 5;
  $('folds').disabled = !isNfold();
  $('add-within').disabled = !isNfold() || !list.length;
  $('add-around').disabled = !list.length;
  $('remove-surface').disabled = list.length < 2;
  const ul = $('surfaces');
  ul.replaceChildren(...list.map((s, i) => {
    const li = document.createElement('li');
    li.textContent = `${s.name ?? '?'} (${s.kind ?? '?'}${s.role === 'skin' ? ', skin' : ''})`;
    li.className = i === selected ? 'selected' : '';
    li.addEventListener('click', () => {
      if (selected !== i) selectedHeight = 0;
      selected = i;
      refresh();
    });
    return li;
  }));
  const s = list[selected];
  $('surface').disabled = !s;
  if (!s) return;
  const heights = heightsOf(s);
  $('height-choice').hidden = !heights;
  if (heights) {
    $('height').replaceChildren(...heights.map((h, k) => {
      const option = document.createElement('option');
      option.value = k;
      option.textContent = `at ${h?.at ?? '?'}`;
      return option;
    }));
    $('height').value = heightOf(s);
  }
  $('name').value = s.name ?? '';
  $('skin').checked = s.role === 'skin';
  $('smooth').checked = s.smooth !== false;
  for (const div of document.querySelectorAll('#surface .side')) {
    const which = div.dataset.side;
    const value = s[which];
    const gradient = value && typeof value === 'object' && !Array.isArray(value);
    const stops = gradient ? value.stops ?? [] : null;
    div.querySelector('[data-stop=first]').value = hex(gradient ? stops[0]?.[1] : value);
    const last = div.querySelector('[data-stop=last]');
    last.value = hex(gradient ? stops[stops.length - 1]?.[1] : value);
    last.hidden = !gradient;
    div.querySelector('[data-gradient]').checked = gradient;
    div.querySelector('[data-visible]').checked = s.visible?.[which] !== false;
  }
  const blur = s.blur;
  $('blur').disabled = blur !== undefined && typeof blur !== 'number';
  $('blur').value = typeof blur === 'number' ? blur : '';
  const grain = grainIndex();
  $('grains').checked = grain >= 0;
  $('grain-spacing').value = grain >= 0 ? doc.get(['grains', grain, 'spacing']) : '';
  const place = errorPlace();
  for (const input of document.querySelectorAll('#surface [data-field]')) {
    input.classList.toggle('bad', !!place && place.surface === selected &&
                                  place.field === input.dataset.field);
  }
}

const setSurface = (field, value) => commit(doc.set(['surfaces', selected, field], value));

$('height').addEventListener('change', () => {
  selectedHeight = Number($('height').value);
  refresh();
});

$('name').addEventListener('change', () => {
  const old = surfaces()[selected].name;
  let next = doc.set(['surfaces', selected, 'name'], $('name').value);
  // grains follow their surface's new name (on it, or through the region it bounds)
  (doc.get(['grains']) ?? []).forEach((g, k) => {
    for (const key of ['on', 'inside', 'outside']) {
      if (g[key] === old) next = next.set(['grains', k, key], $('name').value);
    }
  });
  commit(next);
});
$('skin').addEventListener('change', () => {
  let next = doc;
  surfaces().forEach((s, i) => {
    if (i !== selected && s.role === 'skin') next = next.remove(['surfaces', i, 'role']);
  });
  commit($('skin').checked ? next.set(['surfaces', selected, 'role'], 'skin')
                           : next.remove(['surfaces', selected, 'role']));
});
$('smooth').addEventListener('change', () => {
  commit($('smooth').checked ? doc.remove(['surfaces', selected, 'smooth'])
                             : doc.set(['surfaces', selected, 'smooth'], false));
});
$('blur').addEventListener('change', () => setSurface('blur', Number($('blur').value)));

let pickTarget = null;  // [side, stop] the eyedropper fills
function pickColour(colour) {
  if (!pickTarget) return;
  const [which, stop] = pickTarget;
  pickTarget = null;
  side.tool = top.tool = document.querySelector('input[name=tool]:checked').value;
  hint();
  setColour(which, stop, colour);
}

function setColour(which, stop, colour) {
  const value = surfaces()[selected][which];
  if (value && typeof value === 'object' && !Array.isArray(value)) {
    const k = stop === 'first' ? 0 : value.stops.length - 1;
    commit(doc.set(['surfaces', selected, which, 'stops', k, 1], colour));
  } else {
    setSurface(which, colour);
  }
}

for (const div of document.querySelectorAll('#surface .side')) {
  const which = div.dataset.side;
  div.innerHTML = $('side-controls').innerHTML.replaceAll('SIDE', which);
  for (const input of div.querySelectorAll('input[type=color]')) {
    input.addEventListener('change', () => setColour(which, input.dataset.stop, input.value));
  }
  div.querySelector('[data-gradient]').addEventListener('change', (e) => {
    const value = surfaces()[selected][which];
    const first = div.querySelector('[data-stop=first]').value;
    setSurface(which, e.target.checked
      ? { along: 'profile', stops: [[0, first], [1, hex(value)]] }
      : hex(value?.stops?.[0]?.[1]));
  });
  div.querySelector('[data-eyedropper]').addEventListener('click', () => {
    pickTarget = [which, 'first'];
    side.tool = top.tool = 'eyedropper';
    hint();
  });
  div.querySelector('[data-visible]').addEventListener('change', () => {
    const v = { front: true, back: true, ...surfaces()[selected].visible };
    v[which] = div.querySelector('[data-visible]').checked;
    commit(v.front && v.back ? doc.remove(['surfaces', selected, 'visible'])
                             : doc.set(['surfaces', selected, 'visible'], v));
  });
}

function grainIndex() {
  const name = surfaces()[selected].name;
  return (doc.get(['grains']) ?? []).findIndex((g) => g.on === name);
}
$('grains').addEventListener('change', () => {
  const s = surfaces()[selected];
  const k = grainIndex();
  if (!$('grains').checked) {
    if (k >= 0) commit(doc.remove(['grains', k]));
    return;
  }
  const r = maxRadius(s.profile);
  const size = Math.round(r * 4) / 100;  // semi-axes a few percent of the surface's radius
  const grains = doc.get(['grains']) ?? [];
  commit(doc.set(['grains', grains.length], {
    name: `${s.name}-grains`, on: s.name, spacing: Math.round(r * 25) / 100, side: 'back',
    shape: { ellipsoid: [size * 1.5, size, size * 0.5] }, front: '#e8d8a0', back: '#c8b070',
  }));
});
$('grain-spacing').addEventListener('change', () => {
  const k = grainIndex();
  if (k >= 0) commit(doc.set(['grains', k, 'spacing'], Number($('grain-spacing').value)));
});

function setSymmetry() {
  commit(doc.set(['symmetry'], $('symmetry').value === 'nfold'
    ? { type: 'nfold', folds: Number($('folds').value) || 5 } : { type: 'cylindrical' }));
}
$('symmetry').addEventListener('change', setSymmetry);
$('folds').addEventListener('change', setSymmetry);

function uniqueName(base) {
  const names = new Set(surfaces().map((s) => s.name));
  for (let k = 1; ; ++k) if (!names.has(`${base}-${k}`)) return `${base}-${k}`;
}

/// The skin (or the first surface): its profile's points, the middle and the height of its y
/// range, its largest radius; new surfaces are placed inside it.
function skinShape() {
  const skin = surfaces().find((s) => s.role === 'skin') ?? surfaces()[0];
  const profile = pairs(skin.profile);
  const ys = profile.map((p) => p[1]);
  return { profile, mid: (Math.min(...ys) + Math.max(...ys)) / 2,
           height: Math.max(...ys) - Math.min(...ys), radius: maxRadius(profile) };
}

$('add-around').addEventListener('click', () => {
  const { profile: outer, mid } = skinShape();
  const profile = outer.map(([r, y]) => [Math.round(r * 70) / 100,
                                                Math.round((mid + (y - mid) * 0.8) * 100) / 100]);
  const n = surfaces().length;
  commit(doc.set(['surfaces', n], { name: uniqueName('layer'), kind: 'around', profile,
                                    front: '#e0a060', back: '#f0d0a0', blur: 1 }));
  selected = n;
  refresh();
});
$('add-within').addEventListener('click', () => {
  const { mid, height: h, radius: R } = skinShape();
  const ring = (cx, cy, rx, ry) => Array.from({ length: 8 }, (_, k) =>
    [Math.round((cx + rx * Math.cos(k * Math.PI / 4)) * 100) / 100,
     Math.round((cy + ry * Math.sin(k * Math.PI / 4)) * 100) / 100]);
  const across = Math.min(0.2 * R, 0.45 * R * Math.sin(Math.PI / folds()));
  const n = surfaces().length;
  commit(doc.set(['surfaces', n], {
    name: uniqueName('chambers'), kind: 'within', profile: ring(0.5 * R, mid, 0.2 * R, 0.25 * h),
    section: ring(0.5 * R, 0, 0.2 * R, across), front: '#f06040', back: '#f0c060', blur: 1,
  }));
  selected = n;
  refresh();
});
$('remove-surface').addEventListener('click', () => {
  const name = surfaces()[selected].name;
  let next = doc.remove(['surfaces', selected]);
  for (let k = (next.get(['grains']) ?? []).length - 1; k >= 0; --k) {
    if (next.get(['grains', k, 'on']) === name) next = next.remove(['grains', k]);
  }
  selected = 0;
  commit(next);
});

// ---- history, text and the server ------------------------------------------------------------

function commit(next) {
  if (next.text === doc.text) return;
  past.push(doc.text);
  future.length = 0;
  doc = next;
  text.value = doc.text;
  refresh();
}

function restore(from, to) {
  if (!from.length) return;
  to.push(doc.text);
  doc = new TemplateDoc(from.pop());
  text.value = doc.text;
  refresh();
}
$('undo').addEventListener('click', () => restore(past, future));
$('redo').addEventListener('click', () => restore(future, past));
document.addEventListener('keydown', (e) => {
  if (!(e.ctrlKey || e.metaKey) || e.key.toLowerCase() !== 'z') return;
  if (e.target === text || e.target.tagName === 'INPUT') return;
  e.preventDefault();
  if (e.shiftKey) restore(future, past); else restore(past, future);
});

let typing = 0;
text.addEventListener('input', () => {
  clearTimeout(typing);
  window.editorBusy = true;  // until the text is checked
  typing = setTimeout(() => {
    const next = new TemplateDoc(text.value);
    if (next.text !== doc.text) {
      past.push(doc.text);
      future.length = 0;
      doc = next;
    }
    refresh();
  }, 300);
});

/// Redraws everything from `doc` and asks the server about it.
function refresh() {
  $('undo').disabled = !past.length;
  $('redo').disabled = !future.length;
  if (!doc.error) fillPanel();
  layoutCurves();
  check();
}

const inFlight = {};   // by view ('model', 'cut', 'variants'): the AbortController of its request

/// POSTs the template text `body` to `path` (server_request.js ask()). With a `view`, the
/// request replaces the view's earlier one, which is aborted (the server then drops or stops
/// its work), so that at most one request per view is in flight. Resolves to the answer, or to
/// null when a newer request of the view replaced this one.
async function post(path, body, view = null) {
  let signal;
  if (view) {
    inFlight[view]?.abort();
    inFlight[view] = new AbortController();
    signal = inFlight[view].signal;
  }
  try {
    return await ask(path, { method: 'POST', body, signal,
                             headers: { 'Content-Type': 'text/plain' } });
  } catch (e) {
    if (e.name === 'AbortError') return null;
    throw e;
  }
}

function showVerdict() {
  for (const id of ['side-error', 'top-error']) $(id).textContent = '';
  // While the text is wrong, the pictures are of the last good one: say so by fading them.
  document.querySelector('.views').classList.toggle('stale', !!doc.error || !verdict?.ok);
  if (doc.error) {
    verdictLine.className = 'bad';
    verdictLine.textContent = `YAML: ${doc.error}`;
    return;
  }
  if (verdict.ok) {
    verdictLine.className = '';
    verdictLine.textContent = `ok: ${verdict.surfaces} surfaces`;
    return;
  }
  verdictLine.className = 'bad';
  verdictLine.textContent = `line ${verdict.line}, column ${verdict.column}: ${verdict.field}: ${verdict.rule}`;
  const place = errorPlace();
  if (place && (place.field === 'profile' || place.field === 'section')) {
    $(place.field === 'profile' ? 'side-error' : 'top-error').textContent =
      `${surfaces()[place.surface]?.name}: ${verdict.rule}`;
  }
}

/// Shows the PNG of a server's answer in `img`, or its refusal as the image's text; returns
/// whether there was a picture.
async function showPicture(img, answer) {
  if (!answer.ok) {
    img.removeAttribute('src');
    img.alt = (await answer.json()).message;
    return false;
  }
  URL.revokeObjectURL(img.src);
  img.src = URL.createObjectURL(await answer.blob());
  return true;
}

let sectionBusy = false, sectionAgain = null;
/// Cuts the last checked text (verdictText, whose box the slider spans) at the slider's height:
/// coarse (a small PMVC cube) while the slider moves, full when it stops; at most one request
/// at a time, the latest one waiting. (Cutting the text being typed sent text that does not
/// build, or a plane outside its box, whenever a cut was queued while a check was pending.)
async function cut(coarse) {
  if (!verdict || !verdict.ok) return;
  if (sectionBusy) { sectionAgain = coarse; return; }
  sectionBusy = true;
  const lo = verdict.bbox_min[1], hi = verdict.bbox_max[1];
  const y = lo + (hi - lo) * Number($('plane').value);
  $('height').textContent = y.toFixed(2);
  const t0 = performance.now();
  const answer = await post(`/api/section.png?y=${y}${coarse ? '&coarse=1' : ''}`, verdictText,
                            'cut');
  if (answer) await showPicture($('section'), answer);
  $('cut-time').textContent = `${((performance.now() - t0) / 1000).toFixed(2)} s${coarse ? ' (coarse)' : ''}`;
  sectionBusy = false;
  if (sectionAgain !== null) {
    const again = sectionAgain;
    sectionAgain = null;
    await cut(again);
  }
}
$('plane').addEventListener('input', () => cut(true));
$('plane').addEventListener('change', () => cut(false));

let checkTimer = 0;
function check() {
  clearTimeout(checkTimer);
  const mine = ++version;
  window.editorBusy = true;
  checkTimer = setTimeout(() => {
    runCheck(mine).finally(() => { if (mine === version) window.editorBusy = false; });
  }, 200);
}

async function runCheck(mine) {
  const body = doc.text;
  $('save').disabled = true;
  if (doc.error) { showVerdict(); return; }
  const answer = await (await post('/api/check', body)).json();
  if (mine !== version) return;
  const firstGood = answer.ok && !(verdict && verdict.ok);
  verdict = answer;
  verdictText = body;
  showVerdict();
  fillPanel();
  layoutCurves();
  $('save').disabled = !verdict.ok || body === saved;
  statusLine.textContent = body === saved ? 'saved' : 'edited';
  if (!verdict.ok) return;
  if (firstGood) frameViews();
  await showModel(mine, body);
  await cut(false);
  askVariants(mine, body);
}

/// The 3D view of the text: see-through, or with "outside" checked the uncut object with its
/// skin baked (/api/skin.glb).
async function showModel(mine, body) {
  if (!model) return;
  const outside = $('show-outside').checked;
  const glb = await post(outside ? '/api/skin.glb' : '/api/model.glb', body, 'model');
  if (!glb || mine !== version || !glb.ok || outside !== $('show-outside').checked) return;
  await model.show(await glb.arrayBuffer(), !framed, outside);
  framed = true;
}
$('show-outside').addEventListener('change', () => {
  if (!verdict?.ok) return;
  window.editorBusy = true;  // until the model is shown
  const mine = version;
  showModel(mine, verdictText).finally(() => { if (mine === version) window.editorBusy = false; });
});

let variantsTimer = 0;
/// Asks for the variants' strip once the text has rested for a moment, unless the strip is
/// switched off (it takes seconds of CPU: on a slow machine it competes with the cuts).
function askVariants(mine, body) {
  clearTimeout(variantsTimer);
  if ($('show-variants').checked) variantsTimer = setTimeout(() => showVariants(mine, body), 800);
}
$('show-variants').addEventListener('change', () => {
  $('variants').hidden = !$('show-variants').checked;
  if (verdict?.ok) askVariants(version, verdictText);
});

/// The variants' strip (the server answers checks and cuts of newer text meanwhile, and an
/// answer for older text is dropped).
async function showVariants(mine, body) {
  if (mine !== version || !$('show-variants').checked) return;
  const t0 = performance.now();
  const answer = await post('/api/variants.png?count=4', body, 'variants');
  if (!answer || mine !== version) return;
  if (await showPicture($('variants'), answer)) {
    $('variants-time').textContent = `${((performance.now() - t0) / 1000).toFixed(1)} s`;
  }
}

$('save').addEventListener('click', async () => {
  const body = doc.text;
  const answer = await (await post('/api/save', body)).json();
  if (answer.ok) {
    saved = body;
    $('save').disabled = true;
    statusLine.textContent = `saved ${answer.file}`;
  } else {
    verdict = answer;
    verdictText = body;
    showVerdict();
  }
});

/// The 3D view, or null where the browser has no WebGL (the page works without it).
function makeModelView() {
  try {
    return new ModelView($('model3d'));
  } catch (e) {
    $('model3d').replaceWith(Object.assign(document.createElement('p'),
      { textContent: `No 3D view: ${e.message}` }));
    return null;
  }
}
const model = makeModelView();
const start = await (await ask('/api/template')).json();
$('file').textContent = start.file;
saved = start.exists ? start.text : '';
const stem = start.file.replace(/\.yaml$/, '').toLowerCase().replace(/[^a-z0-9_-]/g, '-').slice(0, 64);
doc = new TemplateDoc(start.exists ? start.text : starterText(stem || 'new-fruit'));
text.value = doc.text;
hint();
frameViews();
refresh();
/// `d` with every surface's profile and sections set to the values they have.
function rewriteCurves(d) {
  (d.get(['surfaces']) ?? []).forEach((s, i) => {
    for (const field of ['profile', 'section']) {
      if (s && s[field] !== undefined) d = d.set(['surfaces', i, field], s[field]);
    }
    (heightsOf(s) ?? []).forEach((h, k) => {
      if (h?.section !== undefined) d = d.set(['surfaces', i, 'sections', k, 'section'], h.section);
    });
  });
  return d;
}

// For tests and tools: the views (their toCanvas() places pointer strokes), and the rewrite of
// every curve with the values it already has, which must leave the text as it was: of the
// open template (as an edit) and of any template text.
window.editorViews = { side, top };
window.editorModel = model;  // the 3D view (tests look from the file's camera: viewFromFile)
window.editorRewriteCurves = () => commit(rewriteCurves(doc));
window.editorRewriteText = (text) => rewriteCurves(new TemplateDoc(text)).text;
window.editorReady = true;
