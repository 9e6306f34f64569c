// A teleop pad as rqt_robot_steering: geometry_msgs/Twist on a chosen topic, 10 Hz while
// moving, one zero Twist on stop. Buttons (hold), sliders, or keys w/a/s/d/space when focused.
import { advertise, el } from '../ros.js';

export default {
  type: 'teleop', title: 'Teleop (robot steering)', size: [300, 300],
  create({ ros, body, opts, changed }) {
    const topic = el('input', { type: 'text', value: opts.topic || '/turtle1/cmd_vel', size: 22, className: 'teleop-topic' });
    const vmax = el('input', { type: 'number', value: opts.vmax ?? 1.0, step: 0.1, style: 'width:4em' });
    const wmax = el('input', { type: 'number', value: opts.wmax ?? 1.0, step: 0.1, style: 'width:4em' });
    const lin = el('input', { type: 'range', min: -1, max: 1, step: 0.01, value: 0, className: 'teleop-linear' });
    const ang = el('input', { type: 'range', min: -1, max: 1, step: 0.01, value: 0, className: 'teleop-angular' });
    const out = el('div', {}, 'stopped');
    const b = (label, v, w, cls) => el('button', { className: cls, title: label }, label);
    const pad = el('div', { className: 'pad', tabIndex: 0 },
      el('span'), b('↑', 1, 0, 'teleop-forward'), el('span'),
      b('↺', 0, 1, 'teleop-left'), b('■', 0, 0, 'teleop-stop'), b('↻', 0, -1, 'teleop-right'),
      el('span'), b('↓', -1, 0, 'teleop-back'), el('span'));
    body.append(el('div', { className: 'row' }, 'topic', topic),
      el('div', { className: 'row' }, 'max v', vmax, 'm/s  max ω', wmax, 'rad/s'),
      el('div', { className: 'row' }, 'linear', lin), el('div', { className: 'row' }, 'angular', ang), pad, out);

    let pub = null, timer = null;
    const twist = () => ({ linear: { x: +lin.value * +vmax.value, y: 0, z: 0 }, angular: { x: 0, y: 0, z: +ang.value * +wmax.value } });
    const publish = () => {
      if (!pub || pub.name !== topic.value) { if (pub) pub.unadvertise(); pub = advertise(ros, topic.value, 'geometry_msgs/Twist'); }
      const t = twist();
      pub.publish(t);
      out.textContent = `${topic.value}: v=${t.linear.x.toFixed(2)} ω=${t.angular.z.toFixed(2)}`;
    };
    const update = () => {
      const moving = +lin.value !== 0 || +ang.value !== 0;
      publish();
      if (moving && !timer) timer = setInterval(publish, 100);
      if (!moving && timer) { clearInterval(timer); timer = null; }
    };
    const set = (v, w) => { lin.value = v; ang.value = w; update(); };
    const dirs = { 'teleop-forward': [1, 0], 'teleop-back': [-1, 0], 'teleop-left': [0, 1], 'teleop-right': [0, -1] };
    for (const btn of pad.querySelectorAll('button')) {
      const d = dirs[btn.className];
      if (d) { btn.addEventListener('pointerdown', () => set(...d)); btn.addEventListener('pointerup', () => set(0, 0)); btn.addEventListener('pointerleave', ev => { if (ev.buttons) set(0, 0); }); }
      else btn.addEventListener('click', () => set(0, 0));
    }
    lin.oninput = ang.oninput = update;
    const keys = { w: [1, 0], s: [-1, 0], a: [0, 1], d: [0, -1], ' ': [0, 0] };
    pad.addEventListener('keydown', ev => { const k = keys[ev.key]; if (k) { ev.preventDefault(); set(...k); } });
    topic.onchange = vmax.onchange = wmax.onchange = changed;
    return {
      state: () => ({ topic: topic.value, vmax: +vmax.value, wmax: +wmax.value }),
      stats: () => ({ topic: topic.value, moving: !!timer }),
      destroy: () => { if (timer) { clearInterval(timer); lin.value = 0; ang.value = 0; publish(); } if (pub) pub.unadvertise(); },
    };
  },
};
