// The sliders of an .lsys page: one per `define` of the grammar, its range from the server
// (the define's `# range A..B` comment, else around its value). Dragging one regrows the
// creature with the values set (at most one request at a time, the latest values winning,
// no more often than every MIN_GAP ms), and the page's address carries them
// (`?define.NAME=VALUE`), so a link opens with them. Only the defines moved (or named in the
// address) are sent: a define computed from another follows it. The tests read
// document.body.dataset.defines: the values shown, as JSON {name: value}.

const PREFIX = 'define.';
const MIN_GAP = 80;
const body = document.body;
const panel = document.getElementById('defines');

// The values set, by name, as text: from the address first, then from the sliders.
const set = new Map();
for (const [key, value] of new URLSearchParams(location.search)) {
  if (key.startsWith(PREFIX)) set.set(key.slice(PREFIX.length), value);
}

// The query string of the values set, for /data.json: '' or '?define.A=1&...'.
export function definesQuery() {
  const query = new URLSearchParams();
  for (const [name, value] of set) query.append(PREFIX + name, value);
  const text = query.toString();
  return text ? '?' + text : '';
}

// The page's address with the values set, its other keys kept.
function updateAddress() {
  const params = new URLSearchParams(location.search);
  for (const key of [...params.keys()]) if (key.startsWith(PREFIX)) params.delete(key);
  for (const [name, value] of set) params.append(PREFIX + name, value);
  const text = params.toString();
  history.replaceState(null, '', location.pathname + (text ? '?' + text : ''));
}

// Regrowing, one request at a time: a change made meanwhile is sent when it is done.
let regrow = async () => {};
let busy = false;
let pending = false;
async function request() {
  if (busy) { pending = true; return; }
  busy = true;
  body.dataset.regrowing = 'yes';
  try { await regrow(); } catch (e) { /* the page shows the error */ }
  await new Promise((done) => setTimeout(done, MIN_GAP));
  busy = false;
  if (pending) { pending = false; request(); } else body.dataset.regrowing = 'no';
}

function setValue(name, value) {
  set.set(name, value);
  updateAddress();
  request();
}

let shownNames = '';
const rows = new Map();

function row(define) {
  const label = document.createElement('label');
  label.className = 'define';
  const name = document.createElement('span');
  name.className = 'define-name';
  name.textContent = define.name;
  const input = document.createElement('input');
  input.type = 'range';
  input.dataset.define = define.name;
  const value = document.createElement('span');
  value.className = 'define-value';
  input.addEventListener('input', () => {
    value.textContent = input.value;
    setValue(define.name, input.value);
  });
  label.append(name, input, value);
  return { label, input, value };
}

// Shows the sliders of `defines` ([{name, value, min, max, step, note, set}] from /data.json);
// `regrowWith` fetches and shows the page's data for the values set.
export function showDefines(defines, regrowWith) {
  regrow = regrowWith;
  panel.style.display = defines.length ? 'flex' : 'none';
  const names = defines.map((d) => d.name).join(',');
  if (names !== shownNames) {
    panel.replaceChildren();
    rows.clear();
    for (const define of defines) {
      const r = row(define);
      rows.set(define.name, r);
      panel.append(r.label);
    }
    if (defines.length) {
      const reset = document.createElement('button');
      reset.type = 'button';
      reset.id = 'defines-reset';
      reset.textContent = 'file values';
      reset.title = "grow with the file's own values";
      reset.addEventListener('click', () => { set.clear(); updateAddress(); request(); });
      panel.append(reset);
    }
    shownNames = names;
  }
  const shown = {};
  for (const define of defines) {
    const r = rows.get(define.name);
    r.input.min = String(define.min);
    r.input.max = String(define.max);
    r.input.step = String(define.step);
    // A slider being dragged keeps the value under the pointer.
    if (document.activeElement !== r.input || !set.has(define.name)) r.input.value = String(define.value);
    r.value.textContent = String(+define.value.toPrecision(6));
    r.label.title = define.note || `${define.min} to ${define.max}`;
    r.label.classList.toggle('set', set.has(define.name));
    shown[define.name] = define.value;
  }
  body.dataset.defines = JSON.stringify(shown);
}
