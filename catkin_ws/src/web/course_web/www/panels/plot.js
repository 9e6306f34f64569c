// A plot of numeric fields over time, as rqt_plot: type "/topic/field/sub" (e.g.
// /turtle1/pose/x, /scan/ranges/0, /odom/twist/twist/linear/x) and press Enter or "add".
// The topic is the longest known topic that prefixes the path; the rest is the field.
import { subscribe, topicTypes, fieldValue, el } from '../ros.js';

const COLORS = ['#1f77ff', '#ff7f0e', '#2ca02c', '#d62728', '#9467bd', '#8c564b'];
const WINDOW_S = 20;

export default {
  type: 'plot', title: 'Plot (rqt_plot)', size: [520, 300],
  create({ ros, body, opts, changed }) {
    const input = el('input', { type: 'text', size: 30, placeholder: '/turtle1/pose/x', className: 'plot-field' });
    const add = el('button', {}, 'add');
    const pause = el('input', { type: 'checkbox' });
    const legend = el('div', { className: 'row' });
    const canvas = el('canvas', { width: 500, height: 200, className: 'plot-canvas' });
    const status = el('div', {});
    body.append(el('div', { className: 'row' }, input, add, el('label', {}, pause, 'pause')), legend, canvas, status);
    const series = [];   // {path, topic, field, data: [[t, v]], unsub, color}
    const t0 = performance.now() / 1000;

    const start = async path => {
      if (series.some(s => s.path === path)) return;
      const types = await topicTypes(ros);
      const topic = Object.keys(types).filter(t => path === t || path.startsWith(t + '/'))
        .sort((a, b) => b.length - a.length)[0];
      if (!topic) { status.textContent = `${path}: no such topic (yet); retrying`; setTimeout(() => start(path), 2000); return; }
      const field = path.slice(topic.length + 1);
      const s = { path, topic, field, data: [], color: COLORS[series.length % COLORS.length] };
      s.unsub = subscribe(ros, topic, types[topic], m => {
        if (pause.checked) return;
        const v = field ? fieldValue(m, field) : m.data;
        if (typeof v === 'number' || typeof v === 'boolean') {
          s.data.push([performance.now() / 1000 - t0, +v]);
          const cut = s.data.length && s.data[s.data.length - 1][0] - WINDOW_S;
          while (s.data.length && s.data[0][0] < cut) s.data.shift();
        } else status.textContent = `${path}: not a number (${typeof v})`;
      });
      series.push(s);
      const rm = el('button', { title: 'remove' }, '×');
      const item = el('span', { style: `color:${s.color}` }, path, rm);
      rm.onclick = () => { s.unsub(); series.splice(series.indexOf(s), 1); item.remove(); changed(); };
      legend.append(item);
      status.textContent = '';
      changed();
    };
    add.onclick = () => { if (input.value.trim()) start(input.value.trim()); input.value = ''; };
    input.addEventListener('keydown', ev => { if (ev.key === 'Enter') add.onclick(); });
    for (const f of opts.fields || []) start(f);

    const draw = () => {
      const W = canvas.width, H = canvas.height, c = canvas.getContext('2d');
      c.fillStyle = '#ffffff'; c.fillRect(0, 0, W, H);
      const pts = series.flatMap(s => s.data);
      if (!pts.length) return;
      const tmax = Math.max(...pts.map(p => p[0])), tmin = tmax - WINDOW_S;
      let vmin = Math.min(...pts.map(p => p[1])), vmax = Math.max(...pts.map(p => p[1]));
      if (vmax - vmin < 1e-9) { vmin -= 1; vmax += 1; }
      const pad = (vmax - vmin) * 0.05; vmin -= pad; vmax += pad;
      const L = 48, B = 18;
      const X = t => L + (t - tmin) / WINDOW_S * (W - L - 4), Y = v => (H - B) - (v - vmin) / (vmax - vmin) * (H - B - 4);
      c.strokeStyle = '#ccc'; c.fillStyle = '#444'; c.lineWidth = 1; c.font = '10px sans-serif';
      for (let i = 0; i <= 4; i++) {
        const v = vmin + (vmax - vmin) * i / 4;
        c.beginPath(); c.moveTo(L, Y(v)); c.lineTo(W, Y(v)); c.stroke();
        c.fillText(v.toPrecision(3), 2, Y(v) + 3);
      }
      c.fillText(`last ${WINDOW_S} s`, L, H - 4);
      for (const s of series) {
        if (!s.data.length) continue;
        c.strokeStyle = s.color; c.lineWidth = 2; c.beginPath();
        s.data.forEach(([t, v], i) => (i ? c.lineTo(X(t), Y(v)) : c.moveTo(X(t), Y(v))));
        if (s.data.length === 1) c.lineTo(X(s.data[0][0]) + 2, Y(s.data[0][1]));
        c.stroke();
      }
    };
    const fit = () => { canvas.width = Math.max(200, body.clientWidth - 10); canvas.height = Math.max(100, body.clientHeight - 70); };
    fit();
    const timer = setInterval(draw, 100);
    return {
      resize: fit,
      state: () => ({ fields: series.map(s => s.path) }),
      stats: () => ({ series: series.map(s => ({ path: s.path, points: s.data.length, color: s.color })) }),
      destroy: () => { clearInterval(timer); series.forEach(s => s.unsub()); },
    };
  },
};
