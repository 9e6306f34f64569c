// A TF buffer without time: the latest transform of every child frame (/tf and /tf_static),
// and lookups of a frame in a fixed frame through their common root.
import * as THREE from 'three';

export class TfTree {
  constructor() { this.edges = new Map(); }   // child -> {parent, m: Matrix4 (child in parent)}

  add(transforms, isStatic) {
    for (const t of transforms) {
      const child = t.child_frame_id.replace(/^\//, ''), parent = t.header.frame_id.replace(/^\//, '');
      if (!child || !parent || child === parent) continue;
      const { translation: p, rotation: q } = t.transform;
      const m = new THREE.Matrix4().compose(new THREE.Vector3(p.x, p.y, p.z),
        new THREE.Quaternion(q.x ?? 0, q.y ?? 0, q.z ?? 0, q.w ?? 1).normalize(), new THREE.Vector3(1, 1, 1));
      this.edges.set(child, { parent, m, isStatic });
    }
  }

  frames() {
    const s = new Set();
    for (const [c, e] of this.edges) { s.add(c); s.add(e.parent); }
    return [...s];
  }

  roots() { return this.frames().filter(f => !this.edges.has(f)); }

  // [root, Matrix4 of frame in root]
  toRoot(frame) {
    const m = new THREE.Matrix4();
    let f = frame;
    for (let i = 0; i < 64 && this.edges.has(f); i++) {
      const e = this.edges.get(f);
      m.premultiply(e.m);
      f = e.parent;
    }
    return [f, m];
  }

  // Matrix4 of `frame` in `fixed`, or null when they are not connected
  lookup(frame, fixed) {
    frame = frame.replace(/^\//, '');
    if (!fixed || frame === fixed) return frame === fixed ? new THREE.Matrix4() : null;
    const [r1, m1] = this.toRoot(frame), [r2, m2] = this.toRoot(fixed);
    if (r1 !== r2) return null;
    return m2.invert().multiply(m1);
  }
}
