// The template editor's page: the template's text, checked by the server as it is typed (the
// same parser and checks as `cutaway check`), with the model and a cross-section the server
// renders, and Save. Every answer comes from the server; nothing is computed here.
const text = document.getElementById('template');
const verdict = document.getElementById('verdict');
const save = document.getElementById('save');
const statusLine = document.getElementById('status');
const model = document.getElementById('model');
const section = document.getElementById('section');
const plane = document.getElementById('plane');
const height = document.getElementById('height');

let bbox = null;       // of the last model that built, template units
let version = 0;       // of the text; older answers are dropped
let saved = '';        // the text on disk

async function post(path, body) {
  return fetch(path, { method: 'POST', body, headers: { 'Content-Type': 'text/plain' } });
}

/// The line of a 1-based line number selected in the text area.
function selectLine(line) {
  const lines = text.value.split('\n');
  let start = 0;
  for (let i = 0; i < line - 1 && i < lines.length; ++i) start += lines[i].length + 1;
  text.setSelectionRange(start, start + (lines[line - 1] || '').length);
}

function showVerdict(v) {
  if (v.ok) {
    verdict.className = '';
    verdict.textContent = `ok: ${v.surfaces} surfaces`;
    return;
  }
  verdict.className = 'bad';
  verdict.textContent = `line ${v.line}, column ${v.column}: ${v.field}: ${v.rule}`;
  verdict.onclick = () => { text.focus(); selectLine(v.line); };
}

async function picture(img, path) {
  const answer = await post(path, text.value);
  if (answer.ok) {
    URL.revokeObjectURL(img.src);
    img.src = URL.createObjectURL(await answer.blob());
  } else {
    img.removeAttribute('src');
    img.alt = (await answer.json()).message;
  }
}

function planeHeight() {
  return bbox ? bbox.lo + (bbox.hi - bbox.lo) * Number(plane.value) : 0;
}

async function refreshSection() {
  if (!bbox) return;
  const y = planeHeight();
  height.textContent = y.toFixed(2);
  await picture(section, `/api/section.png?y=${y}`);
}

async function check() {
  const mine = ++version;
  const answer = await (await post('/api/check', text.value)).json();
  if (mine !== version) return;
  showVerdict(answer);
  save.disabled = !answer.ok || text.value === saved;
  if (!answer.ok) return;
  bbox = { lo: answer.bbox_min[1], hi: answer.bbox_max[1] };
  statusLine.textContent = text.value === saved ? 'saved' : 'edited';
  await picture(model, '/api/model.png');
  await refreshSection();
}

let timer = 0;
text.addEventListener('input', () => {
  clearTimeout(timer);
  timer = setTimeout(check, 300);
});
plane.addEventListener('change', refreshSection);
plane.addEventListener('input', () => { height.textContent = planeHeight().toFixed(2); });
save.addEventListener('click', async () => {
  const body = text.value;
  const answer = await (await post('/api/save', body)).json();
  if (answer.ok) {
    saved = body;
    save.disabled = true;
    statusLine.textContent = `saved ${answer.file}`;
  } else {
    showVerdict(answer);
  }
});

const start = await (await fetch('/api/template')).json();
document.getElementById('file').textContent = start.file;
text.value = start.text;
saved = start.exists ? start.text : '';
await check();
