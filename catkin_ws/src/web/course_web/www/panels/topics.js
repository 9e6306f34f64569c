// The topic list (as `rostopic list` + `rostopic hz` + `rostopic type`): every topic with its
// type and its rate over the last 5 s. Rates of heavy types (images, clouds, maps) and /clock
// are measured only when their "hz" box is ticked (measuring means receiving every message).
import { subscribe, topicTypes, every, el } from '../ros.js';

const HEAVY = /Image|PointCloud|OccupancyGrid|MarkerArray|rosgraph_msgs\/Clock|TFMessage/;
const WINDOW_MS = 5000;

export default {
  type: 'topics', title: 'Topics', size: [520, 300],
  create({ ros, body }) {
    const tbody = el('tbody');
    body.append(el('table', {}, el('thead', {}, el('tr', {}, el('th', {}, 'topic'), el('th', {}, 'type'), el('th', {}, 'hz'), el('th', {}, 'rate'))), tbody));
    const rows = new Map();   // topic -> {tr, stamps, unsub, rateCell, box}
    const measure = (name, type, r) => {
      if (r.box.checked && !r.unsub) r.unsub = subscribe(ros, name, type, () => r.stamps.push(performance.now()));
      if (!r.box.checked && r.unsub) { r.unsub(); r.unsub = null; r.stamps = []; }
    };
    const refresh = async () => {
      const types = await topicTypes(ros);
      for (const name of Object.keys(types).sort()) {
        if (rows.has(name)) continue;
        const box = el('input', { type: 'checkbox', checked: !HEAVY.test(types[name]) && name !== '/clock' });
        const rateCell = el('td', {}, '');
        const r = { stamps: [], unsub: null, rateCell, box, tr: el('tr', {}, el('td', {}, name), el('td', {}, types[name]), el('td', {}, box), rateCell) };
        box.onchange = () => measure(name, types[name], r);
        rows.set(name, r);
        measure(name, types[name], r);
        // keep rows sorted
        const after = [...rows.keys()].sort().find(n => n > name);
        tbody.insertBefore(r.tr, after ? rows.get(after).tr : null);
      }
      for (const [name, r] of rows) if (!(name in types)) { if (r.unsub) r.unsub(); r.tr.remove(); rows.delete(name); }
    };
    const stopRefresh = every(2000, refresh);
    const timer = setInterval(() => {
      const now = performance.now();
      for (const r of rows.values()) {
        r.stamps = r.stamps.filter(t => now - t < WINDOW_MS);
        const n = r.stamps.length;
        r.rateCell.textContent = !r.box.checked ? '' : n < 2 ? 'no messages' : `${((n - 1) * 1000 / (r.stamps[n - 1] - r.stamps[0])).toFixed(1)} Hz`;
      }
    }, 1000);
    return {
      stats: () => ({ topics: [...rows.keys()] }),
      destroy: () => { stopRefresh(); clearInterval(timer); rows.forEach(r => r.unsub && r.unsub()); },
    };
  },
};
