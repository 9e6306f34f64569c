// /rosout with severities (as rqt_console): the last 500 messages of /rosout_agg, filtered
// by level, newest first.
import { subscribe, el } from '../ros.js';

const LEVELS = { 1: 'DEBUG', 2: 'INFO', 4: 'WARN', 8: 'ERROR', 16: 'FATAL' };
const KEEP = 500;

export default {
  type: 'rosout', title: '/rosout', size: [520, 300],
  create({ ros, body, opts, changed }) {
    const shown = new Set(opts.levels || [1, 2, 4, 8, 16]);
    const filter = el('div', { className: 'row' }, ...Object.entries(LEVELS).map(([lv, name]) => {
      const box = el('input', { type: 'checkbox', checked: shown.has(+lv) });
      box.onchange = () => { if (box.checked) shown.add(+lv); else shown.delete(+lv); render(); changed(); };
      return el('label', { className: `log-${lv}` }, box, name);
    }));
    const tbody = el('tbody');
    body.append(filter, el('table', {}, tbody));
    const log = [];
    const row = m => el('tr', { className: `log-${m.level}` },
      el('td', {}, LEVELS[m.level] || String(m.level)),
      el('td', {}, `${m.header.stamp.secs}.${String(m.header.stamp.nsecs).padStart(9, '0').slice(0, 3)}`),
      el('td', {}, m.name), el('td', { style: 'white-space:pre-wrap' }, m.msg));
    const render = () => tbody.replaceChildren(...log.filter(m => shown.has(m.level)).slice(-KEEP).reverse().map(row));
    const unsub = subscribe(ros, '/rosout_agg', 'rosgraph_msgs/Log', m => {
      log.push(m);
      if (log.length > KEEP) log.shift();
      if (shown.has(m.level)) { tbody.prepend(row(m)); while (tbody.rows.length > KEEP) tbody.lastChild.remove(); }
    });
    return { state: () => ({ levels: [...shown] }), stats: () => ({ messages: log.length }), destroy: unsub };
  },
};
