// The simulated robot and its world in 3D (the RViz displays the course uses): the robot
// model from /robot_description (meshes fetched through package:// -> /package/...), TF live
// from /tf and /tf_static, and one display per topic of a supported type: LaserScan,
// PointCloud2, OccupancyGrid (maps; costmaps in RViz's costmap colours), Path, PoseArray,
// Marker and MarkerArray (the simulator's world models come as /gazebo/scene_markers).
// With a simulator, the scene editor of simedit.js (Insert, move, delete, pause/step, Save World).
import * as THREE from 'three';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';
import { subscribe, topicTypes, every, el } from '../ros.js';
import { TfTree } from './tf.js';
import { parseUrdf } from './urdf.js';
import * as D from './displays.js';
import { attachSimEditor } from './simedit.js';

const DISPLAYS = {
  'sensor_msgs/LaserScan': D.laserScan, 'sensor_msgs/PointCloud2': D.pointCloud2,
  'nav_msgs/OccupancyGrid': D.occupancyGrid, 'nav_msgs/Path': D.path,
  'geometry_msgs/PoseArray': D.poseArray, 'visualization_msgs/Marker': D.markers,
  'visualization_msgs/MarkerArray': D.markers,
};
const THROTTLE = { 'sensor_msgs/PointCloud2': 200, 'nav_msgs/OccupancyGrid': 1000, 'sensor_msgs/LaserScan': 100 };
// topics that re-send the whole scene each time (ode_sim's world, ~1 MB): every 2 s is enough
const SNAPSHOT_TOPICS = { '/gazebo/scene_markers': 2000 };
// offered even before anyone publishes them: ode_sim advertises its scene markers only once
// something subscribes (Gazebo has no such topic; ode_sim's README)
const ALWAYS_OFFERED = { '/gazebo/scene_markers': 'visualization_msgs/MarkerArray' };
const FRAME_MS = 100;   // at most 10 frames per second, and only when something changed
const SCENE = '/gazebo/scene_markers';
const FIXED_PREFERENCE = ['map', 'odom', 'world', 'base_footprint', 'base_link'];
const BASE_FRAMES = ['base_footprint', 'base_link'];

export default {
  type: 'view3d', title: '3D view (RViz)', size: [640, 560],
  create({ ros, body, opts, changed }) {
    const fixedSel = el('select', { className: 'view3d-fixed' });
    const follow = el('input', { type: 'checkbox', checked: opts.follow ?? true });
    const showRobot = el('input', { type: 'checkbox', checked: opts.robot ?? true });
    const list = el('div', { className: 'view3d-displays', style: 'max-height:90px;overflow:auto' });
    const info = el('span');
    const bar = el('div', {}, el('div', { className: 'row' }, 'fixed frame', fixedSel, el('label', {}, follow, 'follow robot'),
      el('label', {}, showRobot, 'robot model'), info), list);
    const holder = el('div', { style: 'position:relative' });
    body.append(bar, holder);

    const renderer = new THREE.WebGLRenderer({ antialias: false, preserveDrawingBuffer: true });
    renderer.setPixelRatio(1);
    holder.append(renderer.domElement);
    renderer.domElement.className = 'view3d-canvas';
    const scene = new THREE.Scene();
    scene.background = new THREE.Color(0x303030);
    const camera = new THREE.PerspectiveCamera(50, 1, 0.02, 500);
    camera.up.set(0, 0, 1);
    const distance = opts.distance || 4;   // of the camera from its target, m
    const offset = new THREE.Vector3(-1, -1, 0.9).normalize().multiplyScalar(distance);
    camera.position.copy(offset);
    const controls = new OrbitControls(camera, renderer.domElement);
    controls.target.set(0, 0, 0);
    controls.update();
    const grid = new THREE.GridHelper(20, 20, 0x707070, 0x505050);
    grid.rotation.x = Math.PI / 2;
    scene.add(grid);
    scene.add(new THREE.AmbientLight(0xffffff, 1.2));
    const sun = new THREE.DirectionalLight(0xffffff, 1.8);
    sun.position.set(2, -3, 5);
    scene.add(sun);

    const tf = new TfTree();
    let dirty = true;   // render only when something changed
    controls.addEventListener('change', () => { dirty = true; });
    let fixed = opts.fixed || '';
    const unsubs = [
      subscribe(ros, '/tf', 'tf2_msgs/TFMessage', m => { tf.add(m.transforms, false); dirty = true; }),
      subscribe(ros, '/tf_static', 'tf2_msgs/TFMessage', m => { tf.add(m.transforms, true); dirty = true; }),
    ];

    // robot model
    let robot = null;   // {links: Map(name -> Object3D), meshes}
    const loadRobot = () => new ROSLIB.Param({ ros, name: opts.robotParam || '/robot_description' }).get(xml => {
      if (typeof xml !== 'string' || !xml) return;
      if (robot) robot.links.forEach(o => scene.remove(o));
      try {
        robot = parseUrdf(xml, url => url.startsWith('package://') ? '/package/' + url.slice(10) : null, msg => { info.textContent = msg; });
        robot.links.forEach(o => scene.add(o));
        dirty = true;
      } catch (e) { info.textContent = `robot_description: ${e.message}`; }
    });
    loadRobot();
    const robotTimer = setInterval(() => { if (!robot) loadRobot(); }, 3000);

    // displays
    const displays = new Map();   // topic -> {type, obj: display instance, unsub, box}
    const wanted = opts.displays || {};
    const enable = (topic, type, on) => {
      const d = displays.get(topic);
      if (on && !d.inst) {
        d.inst = DISPLAYS[type](THREE, topic);
        scene.add(d.inst.object);
        const throttle = SNAPSHOT_TOPICS[topic] || THROTTLE[type] || 0;
        d.unsub = subscribe(ros, topic, type, m => {
          d.inst.update(m); dirty = true;
          if (topic === SCENE) editor.onMarkers();
        }, { throttle_rate: throttle, queue_length: throttle ? 1 : 0 });
      } else if (!on && d.inst) {
        d.unsub(); scene.remove(d.inst.object); d.inst.dispose && d.inst.dispose(); d.inst = null; dirty = true;
      }
    };
    const refresh = async () => {
      const types = { ...ALWAYS_OFFERED, ...(await topicTypes(ros)) };
      for (const [topic, type] of Object.entries(types).sort()) {
        if (!DISPLAYS[type] || displays.has(topic)) continue;
        const box = el('input', { type: 'checkbox', checked: wanted[topic] ?? true });
        displays.set(topic, { type, inst: null, unsub: null, box });
        box.onchange = () => { wanted[topic] = box.checked; enable(topic, type, box.checked); changed(); };
        list.append(el('label', { style: 'margin-right:10px' }, box, `${topic} (${type.split('/')[1]})`));
        enable(topic, type, box.checked);
      }
      const frames = tf.frames().sort();
      // a world without TF (empty_world.launch, no robot): the scene markers' frame
      if (!fixed && !frames.length && displays.has(SCENE)) fixed = 'odom';
      if (!fixed || !frames.includes(fixed)) {
        const pick = FIXED_PREFERENCE.find(f => frames.includes(f)) || tf.roots()[0];
        if (pick && pick !== fixed && !opts.fixed) fixed = pick;
      }
      if (fixedSel.options.length !== frames.length) fixedSel.replaceChildren(...frames.map(f => new Option(f, f, false, f === fixed)));
      fixedSel.value = fixed;
    };
    const stopRefresh = every(2000, refresh);
    fixedSel.onchange = () => { fixed = fixedSel.value; opts.fixed = fixed; changed(); };
    follow.onchange = showRobot.onchange = () => { dirty = true; changed(); };

    const fit = () => {
      const w = Math.max(100, body.clientWidth - 8), h = Math.max(100, body.clientHeight - bar.offsetHeight - 12);
      renderer.setSize(w, h);
      camera.aspect = w / h;
      camera.updateProjectionMatrix();
      dirty = true;
    };
    const editor = attachSimEditor({
      ros, bar, holder, canvas: renderer.domElement, camera, controls, scene,
      markers: () => { const d = displays.get(SCENE); return d && d.inst; },
      toFixed: frame => tf.lookup(frame, fixed), dirty: () => { dirty = true; }, relayout: () => fit(),
      place: () => placeScene(),
    });
    fit();

    let raf = 0, last = 0, lastBase = null;
    const place = (obj, frame) => {
      const m = frame ? tf.lookup(frame, fixed) : null;
      obj.visible = !!m;
      if (m) { obj.matrixAutoUpdate = false; obj.matrix.copy(m); obj.matrixWorldNeedsUpdate = true; }
    };
    // everything where TF (and the editor's live poses) put it now; the editor picks with it
    const placeScene = () => {
      if (robot) robot.links.forEach((o, name) => { place(o, name); o.visible = o.visible && showRobot.checked; });
      for (const d of displays.values()) if (d.inst) d.inst.place((obj, frame) => place(obj, frame));
      editor.afterPlace();
    };
    const frameLoop = now => {
      raf = requestAnimationFrame(frameLoop);
      if (!dirty || now - last < FRAME_MS) return;
      last = now;
      dirty = false;
      placeScene();
      if (follow.checked) {
        const base = BASE_FRAMES.map(f => tf.lookup(f, fixed)).find(Boolean);
        if (base) {
          const p = new THREE.Vector3().setFromMatrixPosition(base);
          if (lastBase) { const dp = p.clone().sub(lastBase); camera.position.add(dp); controls.target.add(dp); }
          else { controls.target.copy(p); camera.position.copy(p).add(offset); }
          lastBase = p;
          controls.update();
        }
      }
      renderer.render(scene, camera);
    };
    raf = requestAnimationFrame(frameLoop);

    return {
      resize: fit,
      state: () => ({ fixed: opts.fixed, distance: opts.distance, follow: follow.checked, robot: showRobot.checked, displays: wanted }),
      stats: () => ({
        fixed, frames: tf.frames(), links: robot ? robot.links.size : 0, robotVisuals: robot ? robot.visuals : 0,
        visibleLinks: robot ? [...robot.links.values()].filter(o => o.visible).length : 0,
        displays: Object.fromEntries([...displays].map(([t, d]) => [t, d.inst ? d.inst.stats() : null])),
        sim: editor.stats(),
      }),
      destroy: () => {
        cancelAnimationFrame(raf); stopRefresh(); editor.destroy(); clearInterval(robotTimer); unsubs.forEach(u => u());
        displays.forEach(d => d.unsub && d.unsub()); controls.dispose(); renderer.dispose(); renderer.forceContextLoss();
      },
    };
  },
};
