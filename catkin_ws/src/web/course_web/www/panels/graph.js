// The node graph (as rqt_graph, "Nodes/Topics (all)"): nodes as ellipses, topics as boxes,
// arrows publisher -> topic -> subscriber, from /rosapi/nodes and /rosapi/node_details.
// "hide debug" hides /rosout, rosapi, rosbridge and this page's server, as rqt_graph does.
import { callService, el } from '../ros.js';

const DEBUG_NODES = /^\/(rosout|rosapi|rosbridge_websocket|course_web_server)$/;
const DEBUG_TOPICS = /^\/(rosout|rosout_agg)$/;
const SVG = 'http://www.w3.org/2000/svg';
const svgEl = (tag, attrs = {}, text) => {
  const e = document.createElementNS(SVG, tag);
  for (const [k, v] of Object.entries(attrs)) e.setAttribute(k, v);
  if (text !== undefined) e.textContent = text;
  return e;
};

export async function readGraph(ros) {
  const { nodes } = await callService(ros, '/rosapi/nodes', 'rosapi/Nodes', {});
  const details = await Promise.all(nodes.map(n => callService(ros, '/rosapi/node_details', 'rosapi/NodeDetails', { node: n })
    .catch(() => ({ publishing: [], subscribing: [] }))));
  return nodes.map((n, i) => ({ name: n, pub: details[i].publishing || [], sub: details[i].subscribing || [] }));
}

// ranks (columns) of a publisher -> topic -> subscriber graph, cycles cut after a bound
export function layers(graph) {
  const rank = new Map();
  graph.forEach(n => { rank.set('n' + n.name, 0); n.pub.concat(n.sub).forEach(t => rank.set('t' + t, 0)); });
  const edges = graph.flatMap(n => n.pub.map(t => ['n' + n.name, 't' + t]).concat(n.sub.map(t => ['t' + t, 'n' + n.name])));
  const cap = 2 * rank.size;
  for (let it = 0; it < rank.size; it++) {
    let moved = false;
    for (const [a, b] of edges) if (rank.get(b) < rank.get(a) + 1 && rank.get(a) + 1 <= cap) { rank.set(b, rank.get(a) + 1); moved = true; }
    if (!moved) break;
  }
  return { rank, edges };
}

export default {
  type: 'graph', title: 'Node graph (rqt_graph)', size: [640, 320],
  create({ ros, body, opts, changed }) {
    const hide = el('input', { type: 'checkbox', checked: opts.hideDebug ?? true });
    const refreshBtn = el('button', {}, 'refresh');
    const info = el('span');
    const holder = el('div');
    body.append(el('div', { className: 'row' }, refreshBtn, el('label', {}, hide, 'hide debug'), info), holder);
    let last = null;
    const draw = graph => {
      const g = graph.filter(n => !(hide.checked && DEBUG_NODES.test(n.name))).map(n => ({
        name: n.name,
        pub: n.pub.filter(t => !(hide.checked && DEBUG_TOPICS.test(t))),
        sub: n.sub.filter(t => !(hide.checked && DEBUG_TOPICS.test(t))) }));
      // only topics with at least one publisher and one subscriber among the shown nodes (rqt_graph's "dead sinks / leaf topics" hidden)
      const pubs = new Set(g.flatMap(n => n.pub)), subs = new Set(g.flatMap(n => n.sub));
      g.forEach(n => { n.pub = n.pub.filter(t => subs.has(t)); n.sub = n.sub.filter(t => pubs.has(t)); });
      const { rank, edges } = layers(g);
      const cols = [];
      for (const [k, r] of rank) (cols[r] = cols[r] || []).push(k);
      const pos = new Map(), W = 170, H = 34;
      Array.from(cols, c => c || []).forEach((c, x) => c.sort().forEach((k, y) => pos.set(k, [20 + x * W, 20 + y * H])));
      const width = 40 + cols.length * W, height = 40 + Math.max(1, ...Array.from(cols, c => (c || []).length)) * H;
      const svg = svgEl('svg', { width, height, class: 'graph-svg' });
      const defs = svgEl('defs');
      const marker = svgEl('marker', { id: 'arrow', viewBox: '0 0 10 10', refX: 10, refY: 5, markerWidth: 6, markerHeight: 6, orient: 'auto' });
      marker.append(svgEl('path', { d: 'M0,0 L10,5 L0,10 z', fill: '#aaa' }));
      defs.append(marker); svg.append(defs);
      for (const [a, b] of edges) {
        if (!pos.has(a) || !pos.has(b)) continue;
        const [x1, y1] = pos.get(a), [x2, y2] = pos.get(b);
        svg.append(svgEl('path', { class: 'graph-edge', d: `M${x1 + 140},${y1 + 11} C${x1 + 155},${y1 + 11} ${x2 - 15},${y2 + 11} ${x2},${y2 + 11}` }));
      }
      for (const [k, [x, y]] of pos) {
        const isNode = k[0] === 'n';
        svg.append(isNode ? svgEl('ellipse', { class: 'graph-node', cx: x + 70, cy: y + 11, rx: 70, ry: 12 })
          : svgEl('rect', { class: 'graph-topic', x, y, width: 140, height: 22 }));
        svg.append(svgEl('text', { x: x + 70, y: y + 15, 'text-anchor': 'middle' }, k.slice(1).length > 24 ? '…' + k.slice(-23) : k.slice(1)));
      }
      holder.replaceChildren(svg);
      info.textContent = `${g.length} nodes, ${rank.size - g.length} topics`;
    };
    const refresh = async () => {
      try { last = await readGraph(ros); draw(last); } catch (e) { info.textContent = `rosapi: ${e}`; }
    };
    refreshBtn.onclick = refresh;
    hide.onchange = () => { if (last) draw(last); changed(); };
    refresh();
    const timer = setInterval(refresh, 10000);
    return {
      state: () => ({ hideDebug: hide.checked }),
      stats: () => ({ nodes: last ? last.map(n => n.name) : [] }),
      destroy: () => clearInterval(timer),
    };
  },
};
