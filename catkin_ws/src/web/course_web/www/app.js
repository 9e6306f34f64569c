// course_web: the panel desk (add, move, resize, close, save/export/import a layout) and
// the rosbridge connection the panels share. Each panel is a module in panels/.
import { connect } from './ros.js';
import turtlesim from './panels/turtlesim.js';
import teleop from './panels/teleop.js';
import view3d from './panels/view3d.js';
import camera from './panels/camera.js';
import plot from './panels/plot.js';
import topics from './panels/topics.js';
import graph from './panels/graph.js';
import rosout from './panels/rosout.js';

const KINDS = Object.fromEntries([turtlesim, teleop, view3d, camera, plot, topics, graph, rosout]
  .map(k => [k.type, k]));
const STORAGE_KEY = 'course_web.layout';
const DEFAULT_LAYOUT = { version: 1, panels: [
  { type: 'turtlesim', x: 8, y: 8, w: 516, h: 580 },
  { type: 'teleop', x: 532, y: 8, w: 300, h: 300 },
  { type: 'plot', x: 532, y: 316, w: 520, h: 272, opts: { fields: ['/turtle1/pose/x', '/turtle1/pose/y'] } },
  { type: 'view3d', x: 1060, y: 8, w: 640, h: 580 },
  { type: 'topics', x: 8, y: 596, w: 520, h: 300 },
  { type: 'rosout', x: 532, y: 596, w: 520, h: 300 },
  { type: 'graph', x: 1060, y: 596, w: 640, h: 300 },
]};

const desk = document.getElementById('desk');
const msg = text => { document.getElementById('msg').textContent = text; };
let ros = null;
let panels = [];   // {id, kind, el, body, inst, opts}
let nextId = 1;

function validLayout(layout) {
  if (!layout || !Array.isArray(layout.panels)) throw new Error('a layout is {"version": 1, "panels": [...]}');
  for (const p of layout.panels) {
    if (!KINDS[p.type]) throw new Error(`unknown panel type "${p.type}" (known: ${Object.keys(KINDS).join(', ')})`);
  }
  return layout;
}

function currentLayout() {
  return { version: 1, panels: panels.map(p => ({
    type: p.kind.type, x: p.el.offsetLeft, y: p.el.offsetTop, w: p.el.offsetWidth, h: p.el.offsetHeight,
    opts: p.inst && p.inst.state ? p.inst.state() : p.opts })) };
}

function save() {
  localStorage.setItem(STORAGE_KEY, JSON.stringify(currentLayout()));
}

function instantiate(p) {
  p.body.replaceChildren();
  try {
    p.inst = p.kind.create({ ros, body: p.body, opts: p.opts || {}, changed: save, panelId: p.id });
  } catch (e) {
    p.body.textContent = `${p.kind.title}: ${e.message}`;
    console.error(e);
    p.inst = null;
  }
}

function addPanel(type, geom = {}, opts = undefined) {
  const kind = KINDS[type];
  if (!kind) throw new Error(`unknown panel type "${type}"`);
  const [dw, dh] = kind.size || [400, 300];
  const el = document.createElement('section');
  el.className = 'panel';
  el.dataset.type = type;
  const id = `panel-${nextId++}`;
  el.id = id;
  el.style.left = `${geom.x ?? 20 + 30 * (panels.length % 10)}px`;
  el.style.top = `${geom.y ?? 20 + 30 * (panels.length % 10)}px`;
  el.style.width = `${geom.w ?? dw}px`;
  el.style.height = `${geom.h ?? dh}px`;
  const title = document.createElement('div');
  title.className = 'title';
  title.innerHTML = `<span class="name">${kind.title}</span><button class="close" title="close">×</button>`;
  const body = document.createElement('div');
  body.className = 'body';
  el.append(title, body);
  desk.append(el);
  const p = { id, kind, el, body, inst: null, opts };
  panels.push(p);
  title.querySelector('.close').onclick = () => closePanel(p);
  dragBy(title, el);
  new ResizeObserver(() => { if (p.inst && p.inst.resize) p.inst.resize(); }).observe(el);
  el.addEventListener('mouseup', save);   // end of a CSS resize
  instantiate(p);
  return p;
}

function closePanel(p) {
  if (p.inst && p.inst.destroy) p.inst.destroy();
  p.el.remove();
  panels = panels.filter(q => q !== p);
  save();
}

function dragBy(handle, el) {
  handle.addEventListener('pointerdown', ev => {
    if (ev.target.tagName === 'BUTTON') return;
    const x0 = ev.clientX - el.offsetLeft, y0 = ev.clientY - el.offsetTop;
    handle.setPointerCapture(ev.pointerId);
    el.style.zIndex = String(1 + Math.max(0, ...panels.map(p => +p.el.style.zIndex || 0)));
    const move = e => {
      el.style.left = `${Math.max(0, e.clientX - x0)}px`;
      el.style.top = `${Math.max(0, e.clientY - y0)}px`;
    };
    const up = () => { handle.removeEventListener('pointermove', move); handle.removeEventListener('pointerup', up); save(); };
    handle.addEventListener('pointermove', move);
    handle.addEventListener('pointerup', up);
  });
}

function setLayout(layout) {
  validLayout(layout);
  for (const p of [...panels]) { if (p.inst && p.inst.destroy) p.inst.destroy(); p.el.remove(); }
  panels = [];
  for (const q of layout.panels) addPanel(q.type, q, q.opts);
  save();
}

function loadSaved() {
  const text = localStorage.getItem(STORAGE_KEY);
  if (!text) return DEFAULT_LAYOUT;
  try { return validLayout(JSON.parse(text)); } catch (e) {
    msg(`saved layout ignored: ${e.message}`);
    return DEFAULT_LAYOUT;
  }
}

function toolbar() {
  const sel = document.getElementById('add-panel');
  for (const k of Object.values(KINDS)) sel.add(new Option(k.title, k.type));
  sel.onchange = () => { if (sel.value) { addPanel(sel.value); save(); } sel.value = ''; };
  document.getElementById('save-layout').onclick = () => { save(); msg('layout saved in this browser'); };
  document.getElementById('reset-layout').onclick = () => setLayout(DEFAULT_LAYOUT);
  document.getElementById('export-layout').onclick = () => {
    const a = document.createElement('a');
    a.href = URL.createObjectURL(new Blob([JSON.stringify(currentLayout(), null, 2)], { type: 'application/json' }));
    a.download = 'course_web_layout.json';
    a.click();
  };
  document.getElementById('import-layout').onchange = async ev => {
    const f = ev.target.files[0];
    if (!f) return;
    try { setLayout(JSON.parse(await f.text())); msg(`layout loaded from ${f.name}`); }
    catch (e) { msg(`${f.name}: ${e.message}`); }
    ev.target.value = '';
  };
}

async function main() {
  toolbar();
  const params = new URLSearchParams(location.search);
  let port = 9090;
  try { port = (await (await fetch('config.json')).json()).rosbridge_port || port; } catch (e) { /* static hosting */ }
  const url = params.get('rosbridge') || `ws://${location.hostname || 'localhost'}:${port}`;
  const conn = document.getElementById('conn');
  ros = connect(url, state => {
    conn.textContent = `rosbridge ${url}: ${state}`;
    conn.className = state === 'connected' ? 'conn-on' : 'conn-off';
  }, () => panels.forEach(p => { if (p.inst && p.inst.destroy) p.inst.destroy(); instantiate(p); }));
  // ?layout=default: the default layout; ?layout=empty: no panel (tests set their own)
  const asked = params.get('layout');
  setLayout(asked === 'default' ? DEFAULT_LAYOUT : asked === 'empty' ? { version: 1, panels: [] } : loadSaved());
}

// for tests and the console: courseWeb.addPanel('plot', {x, y, w, h}, {fields: [...]})
window.courseWeb = { addPanel: (t, g, o) => addPanel(t, g, o).id, setLayout, currentLayout,
  panels: () => panels.map(p => ({ id: p.id, type: p.kind.type, stats: p.inst && p.inst.stats ? p.inst.stats() : {} })),
  connected: () => !!(ros && ros.isConnected), ros: () => ros };
main();
