// The 3D panel's scene editor (gzclient in the browser): Insert (the simulator's model library
// from course_web_server's /sim/models.json, and box / sphere / cylinder), select, move and
// rotate with the mouse or the pose fields, delete, pause / play / step, the real-time factor,
// sim time, real time and iterations (/gazebo/world_stats), and Save World (the simulator's
// /gazebo/get_world_sdf as a .world download). Everything goes through rosbridge to the
// simulator's own services, as the desktop window does; the view shows the world through
// /gazebo/scene_markers (one marker namespace "ode_sim/MODEL" per model).
import * as THREE from 'three';
import { subscribe, callService, el } from '../ros.js';

const G = '/gazebo';
const MODEL_NS = 'ode_sim/';
const CLICK_PX = 4;            // a pointer moving less than this between down and up clicks
const ROTATE_RAD_PER_PX = 0.01;

// Gazebo's simple shapes as its Insert toolbar makes them (1 m, 1 kg, grey)
const SHAPES = {
  box: { geometry: '<box><size>1 1 1</size></box>', inertia: [0.166667, 0.166667, 0.166667] },
  sphere: { geometry: '<sphere><radius>0.5</radius></sphere>', inertia: [0.1, 0.1, 0.1] },
  cylinder: { geometry: '<cylinder><radius>0.5</radius><length>1</length></cylinder>', inertia: [0.145833, 0.145833, 0.125] },
};

export function shapeSdf(kind, name) {
  const s = SHAPES[kind];
  if (!s) throw new Error(`unknown shape "${kind}" (box, sphere, cylinder)`);
  const [ixx, iyy, izz] = s.inertia;
  return `<?xml version="1.0"?>
<sdf version="1.6">
  <model name="${name}">
    <link name="link">
      <inertial>
        <mass>1</mass>
        <inertia><ixx>${ixx}</ixx><ixy>0</ixy><ixz>0</ixz><iyy>${iyy}</iyy><iyz>0</iyz><izz>${izz}</izz></inertia>
      </inertial>
      <collision name="collision"><geometry>${s.geometry}</geometry></collision>
      <visual name="visual">
        <geometry>${s.geometry}</geometry>
        <material><script><uri>file://media/materials/scripts/gazebo.material</uri><name>Gazebo/Grey</name></script></material>
      </visual>
    </link>
  </model>
</sdf>`;
}

// what spawn_sdf_model takes to insert a library model (the simulator keeps it an include)
export const includeSdf = uri => `<sdf version="1.6"><include><uri>${uri}</uri></include></sdf>`;

// Gazebo's naming of inserted models: NAME, then NAME_0, NAME_1, ...
export function uniqueName(base, taken) {
  if (!taken.has(base)) return base;
  for (let i = 0; ; i++) if (!taken.has(`${base}_${i}`)) return `${base}_${i}`;
}

// gzclient's bottom bar: "DD HH:MM:SS.mmm"
export function formatTime(sec) {
  const ms = Math.round((sec || 0) * 1000);
  const two = n => String(n).padStart(2, '0');
  const d = Math.floor(ms / 86400000), h = Math.floor(ms / 3600000) % 24, m = Math.floor(ms / 60000) % 60;
  return `${two(d)} ${two(h)}:${two(m)}:${two(Math.floor(ms / 1000) % 60)}.${String(ms % 1000).padStart(3, '0')}`;
}

const secs = t => (t ? (t.secs || 0) + (t.nsecs || 0) * 1e-9 : 0);

export function rpyToQuat(r, p, y) {
  const q = new THREE.Quaternion().setFromEuler(new THREE.Euler(r, p, y, 'ZYX'));
  return { x: q.x, y: q.y, z: q.z, w: q.w };
}

export function quatToRpy(q) {
  const e = new THREE.Euler().setFromQuaternion(new THREE.Quaternion(q.x, q.y, q.z, q.w), 'ZYX');
  return [e.x, e.y, e.z];
}

const poseMatrix = p => new THREE.Matrix4().compose(new THREE.Vector3(p.position.x, p.position.y, p.position.z),
  new THREE.Quaternion(p.orientation.x, p.orientation.y, p.orientation.z, p.orientation.w), new THREE.Vector3(1, 1, 1));
const samePose = (a, b) => ['x', 'y', 'z'].every(k => Math.abs(a.position[k] - b.position[k]) < 1e-6) &&
  ['x', 'y', 'z', 'w'].every(k => Math.abs((a.orientation[k] ?? 0) - (b.orientation[k] ?? 0)) < 1e-6);

// ctx: {ros, bar (element for the tool rows), holder (the canvas' parent), canvas, camera,
// controls, scene, markers() (the scene markers display or null), toFixed(frame) (Matrix4 of a
// frame in the view's fixed frame or null), dirty(), relayout() (the tool rows changed height),
// place() (put everything where it is now)}
export function attachSimEditor(ctx) {
  const { ros, camera, controls, scene, canvas } = ctx;
  const info = el('span', { className: 'sim-info' });
  const say = text => { info.textContent = text; };
  const fail = (what, e) => say(`${what}: ${e && e.message ? e.message : e}`);

  // ---------------------------------------------------------------- simulation bar
  const pauseBtn = el('button', { className: 'sim-pause', title: 'pause / play the simulation' }, 'Pause');
  const stepBtn = el('button', { className: 'sim-step', title: 'run N physics steps (paused)' }, 'Step');
  const stepN = el('input', { className: 'sim-steps', type: 'number', min: 1, value: 1, style: 'width:60px', title: 'steps' });
  const statsText = el('span', { className: 'sim-stats' }, 'no simulator (/gazebo/world_stats)');
  let stats = null;            // the last WorldStatistics
  let lastStep = null;         // the last step_world answer
  const unsubStats = subscribe(ros, `${G}/world_stats`, 'ode_sim_msgs/WorldStatistics', m => {
    if (!stats) refreshSoon();   // a simulator is there: its models
    stats = m;
    pauseBtn.textContent = m.paused ? 'Play' : 'Pause';
    statsText.textContent = `Real time factor ${m.real_time_factor.toFixed(2)}  Sim time ${formatTime(secs(m.sim_time))}` +
      `  Real time ${formatTime(secs(m.real_time))}  Iterations ${m.iterations}${m.paused ? '  (paused)' : ''}`;
  }, { throttle_rate: 100, queue_length: 1 });
  pauseBtn.onclick = () => {
    const pause = !(stats && stats.paused);
    callService(ros, `${G}/${pause ? 'pause' : 'unpause'}_physics`, 'std_srvs/Empty', {})
      .then(() => { pauseBtn.textContent = pause ? 'Play' : 'Pause'; say(pause ? 'paused' : 'running'); refreshSoon(); })
      .catch(e => fail(pause ? 'pause_physics' : 'unpause_physics', e));
  };
  // Edit → Reset Model Poses (/gazebo/reset_world) and Reset World (/gazebo/reset_simulation)
  const resetPoses = el('button', { className: 'sim-reset-poses', title: 'Edit → Reset Model Poses' }, 'Reset poses');
  const resetWorld = el('button', { className: 'sim-reset-world', title: 'Edit → Reset World (poses and time)' }, 'Reset world');
  for (const [b, srv, done] of [[resetPoses, 'reset_world', 'model poses reset'], [resetWorld, 'reset_simulation', 'world reset']]) {
    b.onclick = () => callService(ros, `${G}/${srv}`, 'std_srvs/Empty', {})
      .then(() => { say(done); refreshSoon(); }).catch(e => fail(srv, e));
  }
  stepBtn.onclick = () => {
    const steps = Math.floor(Number(stepN.value));
    if (!(steps >= 1)) { say(`steps: "${stepN.value}" is not a whole number of at least 1`); return; }
    callService(ros, `${G}/step_world`, 'ode_sim_msgs/StepWorld', { steps }).then(r => {
      if (!r.success) { say(`step_world: ${r.status_message}`); return; }
      lastStep = { steps, sim_time: r.sim_time, iterations: r.iterations };
      say(`${steps} step${steps > 1 ? 's' : ''}: sim time ${r.sim_time.toFixed(4)} s, iteration ${r.iterations}`);
      refreshSoon();
    }).catch(e => fail('step_world', e));
  };

  // ---------------------------------------------------------------- tools
  let mode = 'select';
  const modeBtns = {};
  for (const m of ['select', 'translate', 'rotate']) {
    modeBtns[m] = el('button', { className: `sim-mode sim-mode-${m}`, title: `${m} mode`, onclick: () => setMode(m) }, m[0].toUpperCase() + m.slice(1));
  }
  const setMode = m => {
    mode = m;
    Object.entries(modeBtns).forEach(([k, b]) => { b.style.borderColor = k === m ? '#9bd' : ''; });
  };
  setMode('select');
  const shapeBtns = Object.keys(SHAPES).map(k => el('button', { className: `sim-shape-${k}`, title: `insert a ${k} (click on the ground)`,
    onclick: () => startPlacing({ kind: 'shape', shape: k, base: `unit_${k}` }) }, k[0].toUpperCase() + k.slice(1)));
  const insertBtn = el('button', { className: 'sim-insert-toggle', title: 'the model library' }, 'Insert ▸');
  const deleteBtn = el('button', { className: 'sim-delete', title: 'delete the selected model (Delete key)' }, 'Delete');
  const modelSel = el('select', { className: 'sim-model', title: 'the selected model' });
  const poseIn = {};
  for (const k of ['x', 'y', 'z', 'roll', 'pitch', 'yaw']) {
    poseIn[k] = el('input', { className: `sim-pose-${k}`, type: 'number', step: k.length > 1 ? 0.05 : 0.1, style: 'width:62px', title: k });
  }
  const applyBtn = el('button', { className: 'sim-apply', title: 'set the selected model to this pose' }, 'Set pose');
  const fileName = el('input', { className: 'sim-file', type: 'text', value: 'my_world.world', style: 'width:120px', title: 'file name of the saved world' });
  const saveBtn = el('button', { className: 'sim-save', title: 'File → Save World As: download the world as SDF' }, 'Save world');
  const insertList = el('div', { className: 'sim-insert', style: 'display:none;max-height:150px;overflow:auto' });

  ctx.bar.append(
    el('div', { className: 'row sim-bar' }, pauseBtn, stepBtn, stepN, resetPoses, resetWorld, statsText),
    el('div', { className: 'row sim-tools' }, ...Object.values(modeBtns), ...shapeBtns, insertBtn, deleteBtn,
      'model', modelSel, ...['x', 'y', 'z', 'roll', 'pitch', 'yaw'].flatMap(k => [k === 'roll' ? 'R' : k === 'pitch' ? 'P' : k === 'yaw' ? 'Y' : k, poseIn[k]]),
      applyBtn, fileName, saveBtn),
    insertList, el('div', { className: 'row' }, info));

  // ---------------------------------------------------------------- the world's models
  let names = [];              // model names (pose_info, get_world_properties: also while paused)
  let namesAt = 0;
  let selected = '';
  let selPose = null;          // the selected model's pose in the world
  const setNames = list => {
    names = list.slice();
    namesAt = performance.now();
    if (selected && !names.includes(selected)) select('');
    if (modelSel.options.length !== names.length + 1 || names.some((n, i) => modelSel.options[i + 1].value !== n)) {
      modelSel.replaceChildren(new Option('—', ''), ...names.map(n => new Option(n, n)));
    }
    modelSel.value = selected;
  };
  const refresh = async () => {
    const r = await callService(ros, `${G}/get_world_properties`, 'gazebo_msgs/GetWorldProperties', {});
    if (!r.success) return;
    setNames(r.model_names);
    if (selected && !poseLive()) await loadPose(selected);
    ctx.dirty();
  };
  let refreshTimer = 0;
  const refreshSoon = () => { clearTimeout(refreshTimer); refreshTimer = setTimeout(() => refresh().catch(() => {}), 50); };
  // polled only with a simulator (world_stats seen) that sends no pose_info: no calls of
  // missing services otherwise
  const poll = setInterval(() => { if (stats && !poseLive()) refresh().catch(() => {}); }, 2000);

  // live poses: /gazebo/pose_info (gzclient's ~/pose/info), running or paused. The scene
  // markers come every 2 s with the poses of their stamp; each model's markers are moved by
  // (its pose now) * (its pose at the markers' stamp)^-1, so moves, pushes and falls show at
  // once, also while paused.
  let poses = new Map();       // model -> pose (latest)
  let poseAt = 0;
  const history = [];          // [{t: sim time, poses}]: the FIRST message of each sim time
  const poseLive = () => performance.now() - poseAt < 1500;
  let hold = null;             // {name, D, answered}: a drag's move until pose_info has it
  const unsubPoses = subscribe(ros, `${G}/pose_info`, 'ode_sim_msgs/PoseInfo', m => {
    const map = new Map(m.model_name.map((n, i) => [n, m.model_pose[i]]));
    const t = secs(m.sim_time);
    if (!history.length || t > history[history.length - 1].t) history.push({ t, poses: map });
    else if (t < history[history.length - 1].t) history.splice(0, history.length, { t, poses: map });   // reset
    while (history.length > 100) history.shift();
    poses = map;
    poseAt = performance.now();
    if (hold && hold.answered) hold = null;
    setNames(m.model_name);
    if (selected && map.has(selected)) { selPose = map.get(selected); if (!editing()) showPose(selPose); }
    ctx.dirty();
  }, { throttle_rate: 100, queue_length: 1 });
  // a model's pose at sim time t (the first message at or after t), or null
  const poseAtTime = (name, t) => {
    const h = history.find(e => e.t >= t - 1e-9);
    return h ? h.poses.get(name) || null : null;
  };

  const loadPose = async name => {
    if (poseLive() && poses.has(name)) {
      selPose = poses.get(name);
      if (!editing()) showPose(selPose);
      return;
    }
    const r = await callService(ros, `${G}/get_model_state`, 'gazebo_msgs/GetModelState', { model_name: name, relative_entity_name: '' });
    if (!r.success || name !== selected) return;
    selPose = r.pose;
    if (!editing()) showPose(r.pose);
  };
  // fields the student typed into keep their values until Set pose or another selection
  let typed = false;
  Object.values(poseIn).forEach(f => ['input', 'change'].forEach(k => f.addEventListener(k, () => { typed = true; })));
  const editing = () => typed || Object.values(poseIn).includes(document.activeElement);
  const showPose = p => {
    typed = false;
    const [r, pi, y] = quatToRpy(p.orientation);
    const v = { x: p.position.x, y: p.position.y, z: p.position.z, roll: r, pitch: pi, yaw: y };
    for (const k in poseIn) poseIn[k].value = v[k].toFixed(3);
  };
  const select = name => {
    selected = name;
    selPose = null;
    typed = false;
    modelSel.value = name;
    if (!name) for (const k in poseIn) poseIn[k].value = '';
    else loadPose(name).catch(e => fail('get_model_state', e));
    ctx.dirty();
  };
  modelSel.onchange = () => select(modelSel.value);

  const setPose = async (name, pose) => {
    const r = await callService(ros, `${G}/set_model_state`, 'gazebo_msgs/SetModelState', { model_state: {
      model_name: name, pose, twist: { linear: { x: 0, y: 0, z: 0 }, angular: { x: 0, y: 0, z: 0 } }, reference_frame: 'world' } });
    if (hold && hold.name === name) hold.answered = true;   // pose_info shows it from now
    if (!r.success) { hold = null; throw new Error(r.status_message); }
    selPose = pose;
    showPose(pose);
    say(`set ${name} to x ${pose.position.x.toFixed(3)} y ${pose.position.y.toFixed(3)} z ${pose.position.z.toFixed(3)} yaw ${quatToRpy(pose.orientation)[2].toFixed(3)}`);
    ctx.dirty();
  };
  applyBtn.onclick = () => {
    if (!selected) { say('select a model first'); return; }
    const v = {};
    for (const k in poseIn) {
      v[k] = Number(poseIn[k].value);
      if (poseIn[k].value === '' || !Number.isFinite(v[k])) { say(`${k}: "${poseIn[k].value}" is not a number`); return; }
    }
    setPose(selected, { position: { x: v.x, y: v.y, z: v.z }, orientation: rpyToQuat(v.roll, v.pitch, v.yaw) })
      .catch(e => fail('set_model_state', e));
  };
  const deleteSelected = () => {
    if (!selected) { say('select a model first'); return; }
    const name = selected;
    callService(ros, `${G}/delete_model`, 'gazebo_msgs/DeleteModel', { model_name: name }).then(r => {
      say(r.success ? `deleted ${name}` : `delete_model: ${r.status_message}`);
      if (r.success) { names = names.filter(n => n !== name); select(''); refreshSoon(); }
    }).catch(e => fail('delete_model', e));
  };
  deleteBtn.onclick = deleteSelected;
  // Gazebo's keys in the view: Esc select mode (and no placing), T translate, R rotate, Delete
  const onKey = ev => {
    if (['INPUT', 'SELECT'].includes(document.activeElement.tagName)) return;
    if (ev.key === 'Escape') { placing = null; setMode('select'); say(''); }
    else if (ev.key === 't' || ev.key === 'T') setMode('translate');
    else if (ev.key === 'r' || ev.key === 'R') setMode('rotate');
    else if (ev.key === 'Delete' && selected) deleteSelected();
  };
  ctx.holder.tabIndex = 0;
  ctx.holder.addEventListener('keydown', onKey);

  // ---------------------------------------------------------------- insert
  let library = null;          // [{name, title, uri, source, thumbnail}]
  let placing = null;          // {kind: 'shape'|'include', shape|uri, base}
  const startPlacing = p => { placing = p; say(`click on the ground to place ${p.base} (Esc cancels)`); };
  const loadLibrary = async () => {
    const r = await fetch('sim/models.json', { cache: 'no-store' });
    if (!r.ok) throw new Error(`sim/models.json: ${r.status} ${(await r.text()).trim()}`);
    library = await r.json();
    const groups = [];
    let source = null;
    for (const m of library) {
      if (m.source !== source) { source = m.source; groups.push(el('div', { className: 'sim-source', style: 'width:100%;color:#aaa' }, source)); }
      groups.push(el('button', { className: 'sim-item', title: `${m.title} (${m.uri})`, style: 'display:inline-flex;flex-direction:column;align-items:center;width:84px',
        onclick: () => startPlacing({ kind: 'include', uri: m.uri, base: m.name }) },
      el('img', { src: m.thumbnail, loading: 'lazy', width: 64, height: 64, alt: '' }), el('span', { style: 'font-size:10px;overflow:hidden;max-width:80px' }, m.name)));
      groups[groups.length - 1].dataset.uri = m.uri;
      groups[groups.length - 1].dataset.name = m.name;
    }
    insertList.replaceChildren(...groups);
    ctx.relayout();
  };
  insertBtn.onclick = () => {
    const open = insertList.style.display === 'none';
    insertList.style.display = open ? 'flex' : 'none';
    insertList.style.flexWrap = 'wrap';
    insertBtn.textContent = open ? 'Insert ▾' : 'Insert ▸';
    if (open && !library) loadLibrary().catch(e => { insertList.textContent = e.message; });
    ctx.relayout();   // the canvas takes what the list leaves
  };
  const place = async (p, x, y) => {
    const taken = new Set(names);
    const name = uniqueName(p.base, taken);
    const xml = p.kind === 'shape' ? shapeSdf(p.shape, name) : includeSdf(p.uri);
    const z = p.kind === 'shape' ? 0.5 : 0;
    const r = await callService(ros, `${G}/spawn_sdf_model`, 'gazebo_msgs/SpawnModel', {
      model_name: name, model_xml: xml, robot_namespace: '', reference_frame: 'world',
      initial_pose: { position: { x, y, z }, orientation: { x: 0, y: 0, z: 0, w: 1 } } });
    if (!r.success) throw new Error(r.status_message);
    names.push(name);
    say(`inserted ${name} at x ${x.toFixed(2)} y ${y.toFixed(2)}`);
    await refresh();
    select(name);
  };

  // ---------------------------------------------------------------- mouse
  const ray = new THREE.Raycaster();
  const ndc = ev => {
    const r = canvas.getBoundingClientRect();
    return new THREE.Vector2(((ev.clientX - r.left) / r.width) * 2 - 1, -((ev.clientY - r.top) / r.height) * 2 + 1);
  };
  // the frame of the scene markers (ode_sim's ~scene_frame, the world)
  const sceneFrame = () => { const m = ctx.markers(); const e = m && m.entries(null)[0]; return (e && e.frame) || 'odom'; };
  const worldToFixed = () => ctx.toFixed(sceneFrame()) || new THREE.Matrix4();
  // the world point where the pointer's ray meets the horizontal plane at height z, or null
  const onPlane = (ev, z) => {
    ray.setFromCamera(ndc(ev), camera);
    const inv = worldToFixed().clone().invert();
    const o = ray.ray.origin.clone().applyMatrix4(inv);
    const d = ray.ray.direction.clone().transformDirection(inv);
    if (Math.abs(d.z) < 1e-9) return null;
    const t = (z - o.z) / d.z;
    return t > 0 ? o.add(d.multiplyScalar(t)) : null;
  };
  // [model name, hit point in the world] under the pointer, or null
  const pick = ev => {
    const m = ctx.markers();
    if (!m) return null;
    ctx.place();                        // markers that came since the last frame, placed
    m.object.updateMatrixWorld(true);
    camera.updateMatrixWorld();
    ray.setFromCamera(ndc(ev), camera);
    for (const hit of ray.intersectObject(m.object, true)) {
      if (!hit.object.isMesh || !hit.object.visible) continue;
      for (let o = hit.object; o; o = o.parent) {
        const ns = o.userData && o.userData.ns;
        if (ns && ns.startsWith(MODEL_NS)) {
          return [ns.slice(MODEL_NS.length), hit.point.clone().applyMatrix4(worldToFixed().clone().invert())];
        }
      }
    }
    return null;
  };
  let lastPick = null;  // the model under the last press (stats)
  let down = null;    // {x, y, drag: {name, start (world point), pose0, kind}}
  let dragD = null;   // the world-frame Matrix4 of the move being dragged
  let lastDown = null;  // client pixels of the last press (stats)
  const onDown = ev => {
    if (ev.button !== 0) return;
    lastDown = [ev.clientX, ev.clientY];
    down = { x: ev.clientX, y: ev.clientY, drag: null };
    if (placing || mode === 'select' || !selected || !selPose) return;
    const hit = pick(ev);
    lastPick = hit ? hit[0] : null;
    if (!hit || hit[0] !== selected) return;
    down.drag = { name: selected, start: hit[1], pose0: selPose, kind: mode };
    controls.enabled = false;   // the view does not orbit while a model is dragged
    canvas.setPointerCapture && canvas.setPointerCapture(ev.pointerId);
  };
  const onMove = ev => {
    if (!down || !down.drag) return;
    const d = down.drag;
    const p0 = d.pose0.position;
    if (d.kind === 'translate') {
      const p = onPlane(ev, d.start.z);
      if (!p) return;
      dragD = new THREE.Matrix4().makeTranslation(p.x - d.start.x, p.y - d.start.y, 0);
    } else {
      const a = (ev.clientX - down.x) * ROTATE_RAD_PER_PX;
      dragD = new THREE.Matrix4().makeTranslation(p0.x, p0.y, p0.z).multiply(new THREE.Matrix4().makeRotationZ(a))
        .multiply(new THREE.Matrix4().makeTranslation(-p0.x, -p0.y, -p0.z));
    }
    ctx.dirty();
  };
  const onUp = ev => {
    if (!down) return;
    const d = down.drag, moved = Math.hypot(ev.clientX - down.x, ev.clientY - down.y) >= CLICK_PX;
    down = null;
    controls.enabled = true;
    if (d) {
      const D = dragD;
      dragD = null;
      if (D && moved) {
        const target = poseMatrix(d.pose0).premultiply(D);
        const pos = new THREE.Vector3(), q = new THREE.Quaternion(), s = new THREE.Vector3();
        target.decompose(pos, q, s);
        hold = { name: d.name, D, answered: false };
        setPose(d.name, { position: { x: pos.x, y: pos.y, z: pos.z }, orientation: { x: q.x, y: q.y, z: q.z, w: q.w } })
          .catch(e => { fail('set_model_state', e); ctx.dirty(); });
        return;
      }
      ctx.dirty();
    }
    if (moved) return;        // an orbit, not a click
    if (placing) {
      const p = onPlane(ev, 0);
      const what = placing;
      placing = null;
      if (!p) { say('click on the ground to place a model'); return; }
      place(what, p.x, p.y).catch(e => fail(`inserting ${what.base}`, e));
      return;
    }
    const hit = pick(ev);
    select(hit ? hit[0] : '');
    if (hit) say(`selected ${hit[0]}`);
  };
  ctx.holder.addEventListener('pointerdown', onDown, true);   // before OrbitControls
  ctx.holder.addEventListener('pointermove', onMove);
  ctx.holder.addEventListener('pointerup', onUp);

  // ---------------------------------------------------------------- save
  saveBtn.onclick = () => {
    let file = fileName.value.trim() || 'my_world.world';
    if (/[\\/]/.test(file)) { say(`file name: "${file}" must not contain / or \\`); return; }
    if (!/\.(world|sdf)$/i.test(file)) file += '.world';
    callService(ros, `${G}/get_world_sdf`, 'ode_sim_msgs/GetWorldSDF', {}).then(r => {
      if (!r.success) { say(`get_world_sdf: ${r.status_message}`); return; }
      const a = el('a', { href: URL.createObjectURL(new Blob([r.sdf], { type: 'application/xml' })), download: file });
      document.body.append(a);
      a.click();
      a.remove();
      saved = { file, bytes: r.sdf.length };
      say(`saved the world as ${file} (${r.sdf.length} bytes, your browser's downloads)`);
    }).catch(e => fail('get_world_sdf', e));
  };
  let saved = null;

  // ---------------------------------------------------------------- drawing
  const highlight = new THREE.Box3Helper(new THREE.Box3(), 0xffd000);
  highlight.visible = false;
  scene.add(highlight);
  let selCentre = null;       // the selection box's centre in the view
  // where the selection is on the page now (client pixels of its box's centre), or null
  const selectedAt = () => {
    if (!selCentre) return null;
    camera.updateMatrixWorld();
    const c = selCentre.clone().project(camera), r = canvas.getBoundingClientRect();
    return [r.left + (c.x + 1) / 2 * r.width, r.top + (1 - c.y) / 2 * r.height];
  };
  return {
    // after the view placed the markers by TF: each model's markers at its pose now, the move
    // being dragged, deleted models hidden, the selection box
    afterPlace() {
      const m = ctx.markers();
      highlight.visible = false;
      selCentre = null;
      if (!m) return;
      const W = worldToFixed(), Winv = W.clone().invert();
      const fresh = performance.now() - namesAt < 5000;
      const box = new THREE.Box3();
      for (const e of m.entries(null)) {
        if (!e.ns || !e.ns.startsWith(MODEL_NS)) continue;
        const name = e.ns.slice(MODEL_NS.length);
        if (fresh && !names.includes(name)) { e.obj.visible = false; continue; }
        let D = null;
        const now = poses.get(name);
        if (now) {
          if (!e.ref) e.ref = poseAtTime(name, secs(e.stamp));
          if (e.ref && !samePose(now, e.ref)) D = poseMatrix(now).multiply(poseMatrix(e.ref).invert());
        }
        const extra = dragD && down && down.drag && down.drag.name === name ? dragD : hold && hold.name === name ? hold.D : null;
        if (extra) D = D ? extra.clone().multiply(D) : extra;
        if (D && e.obj.visible) {
          e.obj.matrix.premultiply(W.clone().multiply(D).multiply(Winv));
          e.obj.matrixWorldNeedsUpdate = true;
        }
        if (name === selected && e.obj.visible) { e.obj.updateMatrixWorld(true); box.expandByObject(e.obj); }
      }
      if (!box.isEmpty()) {
        highlight.box.copy(box);
        highlight.visible = true;
        selCentre = box.getCenter(new THREE.Vector3());
      }
    },
    onMarkers() { ctx.dirty(); },
    stats: () => ({
      simTime: stats ? secs(stats.sim_time) : null, iterations: stats ? stats.iterations : null,
      paused: stats ? stats.paused : null, rtf: stats ? stats.real_time_factor : null,
      stepSize: stats ? stats.max_step_size : null, lastStep, models: names.slice(), selected,
      selPose, selCentre: selCentre ? selCentre.toArray() : null, selectedAt: selectedAt(), lastPick, lastDown, held: hold ? hold.name : null, poseLive: poseLive(), placing: placing ? placing.base : null, mode,
      markersAt: (() => { const m = ctx.markers(); const e = m && m.entries(null)[0]; return e ? secs(e.stamp) : null; })(),
      drawn: (() => { const m = ctx.markers(); return m ? [...new Set(m.entries(null).filter(e => e.ns && e.ns.startsWith(MODEL_NS))
        .map(e => e.ns.slice(MODEL_NS.length)))] : []; })(), library: library ? library.length : null, saved, info: info.textContent,
    }),
    destroy: () => {
      unsubStats(); unsubPoses(); clearInterval(poll); clearTimeout(refreshTimer);
      ctx.holder.removeEventListener('pointerdown', onDown, true);
      ctx.holder.removeEventListener('pointermove', onMove);
      ctx.holder.removeEventListener('pointerup', onUp);
      ctx.holder.removeEventListener('keydown', onKey);
      scene.remove(highlight);
    },
  };
}
