// Camera images: sensor_msgs/Image (rgb8, bgr8, rgba8, bgra8, mono8, mono16, 32FC1) and
// sensor_msgs/CompressedImage (jpeg, png), throttled to 5 Hz.
import { subscribe, topicTypes, every, el } from '../ros.js';

const TYPES = ['sensor_msgs/Image', 'sensor_msgs/CompressedImage'];

function toRGBA(m) {
  const raw = Uint8Array.from(atob(m.data), c => c.charCodeAt(0));
  const { width: w, height: h, step } = m;
  const out = new Uint8ClampedArray(w * h * 4);
  const enc = m.encoding;
  const ch = { rgb8: 3, bgr8: 3, rgba8: 4, bgra8: 4, mono8: 1, '8UC1': 1, '8UC3': 3 }[enc];
  let fmin = Infinity, fmax = -Infinity, f32 = null;
  if (enc === '32FC1') {
    f32 = new Float32Array(w * h);
    const dv = new DataView(raw.buffer);
    for (let y = 0; y < h; y++) for (let x = 0; x < w; x++) {
      const v = dv.getFloat32(y * step + 4 * x, !m.is_bigendian); f32[y * w + x] = v;
      if (Number.isFinite(v)) { fmin = Math.min(fmin, v); fmax = Math.max(fmax, v); }
    }
  }
  for (let y = 0; y < h; y++) for (let x = 0; x < w; x++) {
    const o = 4 * (y * w + x), i = y * step + x * (ch || 2);
    let r, g, b;
    if (f32) { const v = f32[y * w + x]; r = g = b = Number.isFinite(v) ? 255 * (v - fmin) / (fmax - fmin || 1) : 0; }
    else if (enc === 'mono16' || enc === '16UC1') { r = g = b = (m.is_bigendian ? raw[i] : raw[i + 1]); }
    else if (ch === 1) { r = g = b = raw[i]; }
    else if (enc.startsWith('bgr')) { b = raw[i]; g = raw[i + 1]; r = raw[i + 2]; }
    else { r = raw[i]; g = raw[i + 1]; b = raw[i + 2]; }
    out[o] = r; out[o + 1] = g; out[o + 2] = b; out[o + 3] = 255;
  }
  return new ImageData(out, w, h);
}

export default {
  type: 'camera', title: 'Camera', size: [480, 420],
  create({ ros, body, opts, changed }) {
    const select = el('select', { className: 'camera-topic' });
    const info = el('span');
    const canvas = el('canvas', { width: 320, height: 240, style: 'max-width:100%' });
    body.append(el('div', { className: 'row' }, select, info), canvas);
    let topic = opts.topic || '', unsub = null, count = 0;
    const show = (name, type) => {
      if (unsub) unsub();
      unsub = null; topic = name;
      if (!name) return;
      unsub = subscribe(ros, name, type, m => {
        count++;
        if (type.endsWith('CompressedImage')) {
          const img = new Image();
          img.onload = () => { canvas.width = img.width; canvas.height = img.height; canvas.getContext('2d').drawImage(img, 0, 0); };
          img.src = `data:image/${m.format.includes('png') ? 'png' : 'jpeg'};base64,${m.data}`;
          info.textContent = m.format;
        } else {
          try {
            const d = toRGBA(m);
            canvas.width = d.width; canvas.height = d.height; canvas.getContext('2d').putImageData(d, 0, 0);
            info.textContent = `${m.width}×${m.height} ${m.encoding}`;
          } catch (e) { info.textContent = `${m.encoding}: ${e.message}`; }
        }
      }, { throttle_rate: 200, queue_length: 1 });
    };
    let types = {};
    const stopRefresh = every(2000, async () => {
      const all = await topicTypes(ros);
      types = Object.fromEntries(Object.entries(all).filter(([, t]) => TYPES.includes(t)));
      const names = Object.keys(types).sort();
      if (select.options.length !== names.length + 1) {
        select.replaceChildren(new Option('— image topic —', ''), ...names.map(n => new Option(`${n} (${types[n].split('/')[1]})`, n, false, n === topic)));
        if (!topic && names.length) topic = names.find(n => n.endsWith('image_raw')) || names[0];
        if (topic && types[topic] && !unsub) { select.value = topic; show(topic, types[topic]); }
      }
    });
    select.onchange = () => { show(select.value, types[select.value]); changed(); };
    return { state: () => ({ topic }), stats: () => ({ topic, images: count }), destroy: () => { stopRefresh(); if (unsub) unsub(); } };
  },
};
