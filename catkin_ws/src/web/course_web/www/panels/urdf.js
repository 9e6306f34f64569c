// The URDF's visuals as three.js objects, one Group per link (placed by TF each frame):
// box, cylinder, sphere and mesh (STL, COLLADA) with the URDF's origins, scales and colours.
import * as THREE from 'three';
import { STLLoader } from 'three/addons/loaders/STLLoader.js';
import { ColladaLoader } from 'three/addons/loaders/ColladaLoader.js';

const nums = (s, n, dflt) => { const v = (s || '').trim().split(/\s+/).filter(Boolean).map(Number); return v.length === n ? v : dflt; };

export function originMatrix(originEl) {
  const xyz = nums(originEl && originEl.getAttribute('xyz'), 3, [0, 0, 0]);
  const rpy = nums(originEl && originEl.getAttribute('rpy'), 3, [0, 0, 0]);
  return new THREE.Matrix4().compose(new THREE.Vector3(...xyz),
    new THREE.Quaternion().setFromEuler(new THREE.Euler(rpy[0], rpy[1], rpy[2], 'ZYX')), new THREE.Vector3(1, 1, 1));
}

function loadMesh(url, scale, material, group, report) {
  const lower = url.toLowerCase();
  const fail = e => report(`mesh ${url}: ${e && e.message ? e.message : 'cannot load'}`);
  if (lower.endsWith('.stl')) {
    new STLLoader().load(url, geom => {
      const mesh = new THREE.Mesh(geom, material);
      mesh.scale.set(...scale);
      group.add(mesh);
    }, undefined, fail);
  } else if (lower.endsWith('.dae')) {
    new ColladaLoader().load(url, collada => {
      const s = collada.scene;
      // ROS is z-up: undo the loader's y-up conversion
      if (s.rotation.x !== 0) s.rotation.set(0, 0, 0); else s.rotation.set(Math.PI / 2, 0, 0);
      s.scale.multiply(new THREE.Vector3(...scale));
      group.add(s);
    }, undefined, fail);
  } else report(`mesh ${url}: only STL and COLLADA (.dae) meshes are shown`);
}

// xml: the URDF text; resolve(url) -> an HTTP URL or null; report(msg) for problems.
// Returns {links: Map(link -> Group), visuals: count}.
export function parseUrdf(xml, resolve, report) {
  const doc = new DOMParser().parseFromString(xml, 'application/xml');
  if (doc.querySelector('parsererror')) throw new Error('not valid XML');
  const root = doc.documentElement;
  if (root.tagName !== 'robot') throw new Error(`the root element is <${root.tagName}>, not <robot>`);
  const colors = {};
  for (const m of root.children) {
    if (m.tagName !== 'material') continue;
    const c = m.querySelector('color');
    if (c) colors[m.getAttribute('name')] = nums(c.getAttribute('rgba'), 4, [0.8, 0.8, 0.8, 1]);
  }
  const links = new Map();
  let visuals = 0;
  for (const link of root.children) {
    if (link.tagName !== 'link') continue;
    const group = new THREE.Group();
    group.name = link.getAttribute('name');
    group.matrixAutoUpdate = false;
    for (const v of link.children) {
      if (v.tagName !== 'visual') continue;
      const g = v.querySelector('geometry');
      if (!g || !g.firstElementChild) continue;
      const matEl = v.querySelector('material');
      let rgba = [0.8, 0.8, 0.8, 1];
      if (matEl) {
        const c = matEl.querySelector('color');
        rgba = c ? nums(c.getAttribute('rgba'), 4, rgba) : (colors[matEl.getAttribute('name')] || rgba);
      }
      const material = new THREE.MeshLambertMaterial({ color: new THREE.Color(rgba[0], rgba[1], rgba[2]),
        transparent: rgba[3] < 1, opacity: rgba[3] });
      const holder = new THREE.Group();
      holder.matrixAutoUpdate = false;
      holder.matrix.copy(originMatrix(v.querySelector('origin')));
      const shape = g.firstElementChild;
      const a = n => parseFloat(shape.getAttribute(n));
      if (shape.tagName === 'box') {
        holder.add(new THREE.Mesh(new THREE.BoxGeometry(...nums(shape.getAttribute('size'), 3, [0.1, 0.1, 0.1])), material));
      } else if (shape.tagName === 'cylinder') {
        const m = new THREE.Mesh(new THREE.CylinderGeometry(a('radius'), a('radius'), a('length'), 24), material);
        m.rotation.x = Math.PI / 2;   // three's cylinders are along y, URDF's along z
        holder.add(m);
      } else if (shape.tagName === 'sphere') {
        holder.add(new THREE.Mesh(new THREE.SphereGeometry(a('radius'), 20, 14), material));
      } else if (shape.tagName === 'mesh') {
        const file = shape.getAttribute('filename') || '';
        const url = resolve(file);
        if (url) loadMesh(url, nums(shape.getAttribute('scale'), 3, [1, 1, 1]), material, holder, report);
        else report(`mesh ${file}: only package:// URLs are served`);
      } else continue;
      group.add(holder);
      visuals++;
    }
    links.set(group.name, group);
  }
  return { links, visuals };
}
