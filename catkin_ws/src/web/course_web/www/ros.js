// The one rosbridge connection (roslibjs, global ROSLIB) and small helpers the panels share.
// rosbridge started by web.launch authenticates its clients (rosauth): before each connection
// the page asks course_web_server (which it reached with its token) for a fresh `auth`
// message, sent as the first op. Without /rosauth (another server) nothing is sent.
async function freshAuth() {
  try {
    const r = await fetch('rosauth', { cache: 'no-store' });
    return r.ok ? await r.json() : null;
  } catch (e) { return null; }
}

export function connect(url, onState, onReconnect) {
  const ros = new ROSLIB.Ros();
  let everClosed = false;
  let auth = null;
  // registered first: goes out before anything the panels queued for the connection
  ros.on('connection', () => {
    if (auth) ros.authenticate(auth.mac, auth.client, auth.dest, auth.rand, auth.t, auth.level, auth.end);
    auth = null;
  });
  ros.on('connection', () => { onState('connected'); if (everClosed) onReconnect(); });
  ros.on('error', () => onState('error (is rosbridge running? roslaunch rosbridge_server rosbridge_websocket.launch)'));
  const open = async () => { auth = await freshAuth(); ros.connect(url); };
  ros.on('close', () => {
    everClosed = true;
    onState('disconnected, retrying…');
    setTimeout(open, 2000);
  });
  open();
  return ros;
}

// subscribe(ros, name, type, cb, {throttle_rate, queue_length}) -> unsubscribe function
export function subscribe(ros, name, type, cb, options = {}) {
  const t = new ROSLIB.Topic({ ros, name, messageType: type, ...options });
  t.subscribe(cb);
  return () => t.unsubscribe(cb);
}

export function advertise(ros, name, type) {
  const t = new ROSLIB.Topic({ ros, name, messageType: type, queue_size: 1 });
  t.advertise();
  return t;
}

// {topic: type} of every topic the master knows (via /rosapi/topics). Panels poll it: one
// call per second at most is shared by all of them.
const topicCache = new WeakMap();   // ros -> {at, promise}
export function topicTypes(ros) {
  const c = topicCache.get(ros);
  if (c && performance.now() - c.at < 1000) return c.promise;
  // an answer that never comes (a call lost while rosbridge or rosapi restarts) must not
  // stop the panels' polling loops: give up after 5 s
  const promise = new Promise((resolve, reject) => {
    const timer = setTimeout(() => reject(new Error('/rosapi/topics: no answer in 5 s')), 5000);
    ros.getTopics(r => {
      clearTimeout(timer);
      const out = {};
      r.topics.forEach((t, i) => { out[t] = r.types[i]; });
      resolve(out);
    }, e => { clearTimeout(timer); reject(e); });
  });
  promise.catch(() => topicCache.delete(ros));
  topicCache.set(ros, { at: performance.now(), promise });
  return promise;
}

export function callService(ros, name, type, args) {
  const s = new ROSLIB.Service({ ros, name, serviceType: type });
  return new Promise((resolve, reject) => {
    const timer = setTimeout(() => reject(new Error(`${name}: no answer in 10 s`)), 10000);
    s.callService(new ROSLIB.ServiceRequest(args), r => { clearTimeout(timer); resolve(r); }, e => { clearTimeout(timer); reject(e); });
  });
}

// a value of a message by a path like "pose/position/x" or "ranges/0" or "data[2]"
export function fieldValue(msg, path) {
  let v = msg;
  for (const part of path.replace(/\[(\d+)\]/g, '/$1').split('/').filter(Boolean)) {
    if (v === null || v === undefined) return undefined;
    v = v[part];
  }
  return v;
}

// repeat fn every ms (first call now) until the returned stop function is called
export function every(ms, fn) {
  let stopped = false;
  const tick = async () => { if (stopped) return; try { await fn(); } catch (e) { console.warn('course_web:', e); } if (!stopped) timer = setTimeout(tick, ms); };
  let timer = setTimeout(tick, 0);
  return () => { stopped = true; clearTimeout(timer); };
}

export function el(tag, attrs = {}, ...children) {
  const e = document.createElement(tag);
  for (const [k, v] of Object.entries(attrs)) {
    if (k.startsWith('on')) e.addEventListener(k.slice(2), v); else if (k in e && k !== 'list') e[k] = v; else e.setAttribute(k, v);
  }
  e.append(...children);
  return e;
}
