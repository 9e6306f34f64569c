// turtlesim's window: every turtle (found as */pose topics of type turtlesim/Pose), its pen
// trail and the background colour parameters (read live), plus turtle_teleop_key's arrow
// keys (click the canvas, then use the arrows; the teleop publishes on <turtle>/cmd_vel).
import { subscribe, advertise, topicTypes, every, el } from '../ros.js';

const PX = 500;                      // window size, pixels (as turtlesim)
const METER = 45.0;                  // pixels per metre
const PEN = 'rgb(179,184,255)';      // turtlesim's default pen colour, width 3
const BG_DEFAULT = [69, 86, 255];
const L_SCALE = 2.0, A_SCALE = 2.0;  // turtle_teleop_key's ~scale_linear, ~scale_angular
const KEYS = { ArrowUp: [1, 0], ArrowDown: [-1, 0], ArrowLeft: [0, 1], ArrowRight: [0, -1] };

const toPx = (x, y) => [x * METER, PX - 1 - y * METER];

function drawTurtle(ctx, x, y, theta, hue) {
  const [px, py] = toPx(x, y);
  ctx.save();
  ctx.translate(px, py);
  ctx.rotate(-theta);
  ctx.fillStyle = '#4a7a2a';                     // legs and head
  for (const [lx, ly] of [[7, -11], [7, 11], [-9, -11], [-9, 11]]) { ctx.beginPath(); ctx.ellipse(lx, ly, 5, 3.5, 0, 0, 7); ctx.fill(); }
  ctx.beginPath(); ctx.ellipse(15, 0, 5, 5, 0, 0, 7); ctx.fill();
  ctx.fillStyle = `hsl(${hue},45%,35%)`;          // shell
  ctx.beginPath(); ctx.ellipse(0, 0, 13, 11, 0, 0, 7); ctx.fill();
  ctx.strokeStyle = `hsl(${hue},40%,65%)`; ctx.lineWidth = 2; ctx.stroke();
  ctx.restore();
}

export default {
  type: 'turtlesim', title: 'turtlesim', size: [516, 580],
  create({ ros, body, opts, changed }) {
    const trail = el('canvas', { width: PX, height: PX });     // background + pen trails
    const view = el('canvas', { width: PX, height: PX, tabIndex: 0, className: 'turtlesim-canvas', title: 'click, then drive with the arrow keys' });
    const select = el('select', { className: 'teleop-turtle' });
    const info = el('span', {}, '');
    body.append(el('div', { className: 'row' }, 'arrow keys drive', select, info), view);
    const tctx = trail.getContext('2d'), vctx = view.getContext('2d');
    let bg = BG_DEFAULT.slice();
    const fill = () => { tctx.fillStyle = `rgb(${bg.join(',')})`; tctx.fillRect(0, 0, PX, PX); };
    fill();
    const turtles = new Map();   // name -> {pose, unsub, hue}
    let driven = opts.turtle || 'turtle1';
    let pub = null;

    const render = () => {
      vctx.drawImage(trail, 0, 0);
      for (const t of turtles.values()) if (t.pose) drawTurtle(vctx, t.pose.x, t.pose.y, t.pose.theta, t.hue);
    };
    let raf = 0;
    const redraw = () => { if (!raf) raf = requestAnimationFrame(() => { raf = 0; render(); }); };

    // every pose draws a segment from the last one, as turtlesim does (teleports included)
    const onPose = (t, p) => {
      if (t.pose) {
        tctx.strokeStyle = PEN; tctx.lineWidth = 3; tctx.lineCap = 'round';
        tctx.beginPath(); tctx.moveTo(...toPx(t.pose.x, t.pose.y)); tctx.lineTo(...toPx(p.x, p.y)); tctx.stroke();
      }
      t.pose = p;
      redraw();
    };

    const refresh = async () => {
      const types = await topicTypes(ros);
      const names = Object.keys(types).filter(n => types[n] === 'turtlesim/Pose' && n.endsWith('/pose'))
        .map(n => n.slice(1, -'/pose'.length));
      for (const n of names) if (!turtles.has(n)) {
        const t = { pose: null, hue: (turtles.size * 67) % 360 };
        t.unsub = subscribe(ros, `/${n}/pose`, 'turtlesim/Pose', p => onPose(t, p));
        turtles.set(n, t);
      }
      for (const [n, t] of turtles) if (!names.includes(n)) { t.unsub(); turtles.delete(n); }   // killed
      const opts_ = [...turtles.keys()].sort();
      if (select.options.length !== opts_.length || opts_.some((n, i) => select.options[i].value !== n)) {
        select.replaceChildren(...opts_.map(n => new Option(n, n, false, n === driven)));
      }
      // background colour: turtlesim's ~background_r/g/b (any node name)
      const params = await new Promise(res => ros.getParams(res, () => res([])));
      const bgName = params.find(p => p.endsWith('/background_r'));
      if (bgName) {
        const base = bgName.slice(0, -1);
        const vals = await Promise.all('rgb'.split('').map(c => new Promise(res =>
          new ROSLIB.Param({ ros, name: base + c }).get(v => res(v), () => res(null)))));
        if (vals.every(v => Number.isFinite(v)) && vals.some((v, i) => v !== bg[i])) {
          bg = vals.map(v => Math.max(0, Math.min(255, Math.round(v))));
          fill();   // a new background clears the trails, as turtlesim's /clear does
          redraw();
        }
      }
      info.textContent = `${turtles.size} turtle(s)`;
      redraw();
    };
    const stopRefresh = every(1000, refresh);
    redraw();
    select.onchange = () => { driven = select.value; pub = null; changed(); };

    view.addEventListener('keydown', ev => {
      const k = KEYS[ev.key];
      if (!k) return;
      ev.preventDefault();
      if (!pub || pub.name !== `/${driven}/cmd_vel`) pub = advertise(ros, `/${driven}/cmd_vel`, 'geometry_msgs/Twist');
      pub.publish({ linear: { x: L_SCALE * k[0], y: 0, z: 0 }, angular: { x: 0, y: 0, z: A_SCALE * k[1] } });
    });
    view.addEventListener('click', () => view.focus());

    return {
      state: () => ({ turtle: driven }),
      stats: () => ({ turtles: [...turtles.keys()], poses: Object.fromEntries([...turtles].map(([n, t]) => [n, t.pose])), background: bg }),
      destroy: () => { stopRefresh(); turtles.forEach(t => t.unsub()); if (pub) pub.unadvertise(); },
    };
  },
};
