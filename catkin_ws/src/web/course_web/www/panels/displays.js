// RViz-like displays. Each is made by fn(THREE, topic) -> {object, update(msg),
// place(setPose), stats()}: update() rebuilds geometry from a message (in its header's
// frame); place(setPose) asks the view to put each object at its frame's current TF pose.

const b64 = s => Uint8Array.from(atob(s), c => c.charCodeAt(0));

function single(THREE, topic, build) {
  const object = new THREE.Group();
  object.name = topic;
  let frame = null, count = 0, child = null;
  return {
    object,
    update(msg) {
      frame = msg.header.frame_id;
      if (child) { object.remove(child); child.traverse(o => { if (o.geometry) o.geometry.dispose(); if (o.material && o.material.map) o.material.map.dispose(); }); }
      const [obj, n] = build(msg);
      child = obj; count = n;
      if (child) object.add(child);
    },
    place(setPose) { if (frame !== null) setPose(object, frame); },
    stats: () => ({ frame, count }),
  };
}

const points = (THREE, xyz, color, size = 4) => {
  const g = new THREE.BufferGeometry();
  g.setAttribute('position', new THREE.Float32BufferAttribute(xyz, 3));
  return new THREE.Points(g, new THREE.PointsMaterial({ color, size, sizeAttenuation: false }));
};

export function laserScan(THREE, topic) {
  return single(THREE, topic, m => {
    const xyz = [];
    m.ranges.forEach((r, i) => {
      if (r === null || !Number.isFinite(r) || r < m.range_min || r > m.range_max) return;
      const a = m.angle_min + i * m.angle_increment;
      xyz.push(r * Math.cos(a), r * Math.sin(a), 0);
    });
    return [points(THREE, xyz, 0xff0000), xyz.length / 3];
  });
}

export function pointCloud2(THREE, topic) {
  return single(THREE, topic, m => {
    const f = Object.fromEntries(m.fields.map(x => [x.name, x]));
    if (!f.x || !f.y || !f.z) return [null, 0];
    const data = b64(m.data), dv = new DataView(data.buffer);
    const n = m.width * m.height, stride = Math.max(1, Math.ceil(n / 50000));
    const xyz = [], le = !m.is_bigendian;
    for (let i = 0; i < n; i += stride) {
      const o = (i % m.width) * m.point_step + Math.floor(i / m.width) * m.row_step;
      const x = dv.getFloat32(o + f.x.offset, le), y = dv.getFloat32(o + f.y.offset, le), z = dv.getFloat32(o + f.z.offset, le);
      if (Number.isFinite(x) && Number.isFinite(y) && Number.isFinite(z)) xyz.push(x, y, z);
    }
    return [points(THREE, xyz, 0xffffff, 2), xyz.length / 3];
  });
}

// RViz's "map" scheme for maps, "costmap" scheme for topics with costmap in the name
export function occupancyGrid(THREE, topic) {
  const costmap = /costmap/.test(topic);
  return single(THREE, topic, m => {
    const { width: w, height: h, resolution: res } = m.info;
    const rgba = new Uint8Array(w * h * 4);
    m.data.forEach((v, i) => {
      let c;
      if (costmap) c = v <= 0 ? [0, 0, 0, 0] : v >= 100 ? [255, 0, 255, 200] : v === 99 ? [0, 255, 255, 200] : [255 * v / 98, 0, 255 * (1 - v / 98), 160];
      else c = v < 0 ? [112, 137, 134, 255] : [255 - 2.55 * v, 255 - 2.55 * v, 255 - 2.55 * v, 255];
      rgba.set(c, 4 * i);
    });
    const tex = new THREE.DataTexture(rgba, w, h, THREE.RGBAFormat);
    tex.needsUpdate = true;
    tex.magFilter = THREE.NearestFilter;
    const plane = new THREE.Mesh(new THREE.PlaneGeometry(w * res, h * res),
      new THREE.MeshBasicMaterial({ map: tex, transparent: true, depthWrite: !costmap, side: THREE.DoubleSide }));
    plane.position.set(w * res / 2, h * res / 2, costmap ? 0.01 : 0);
    const o = m.info.origin, g = new THREE.Group();
    g.position.set(o.position.x, o.position.y, o.position.z);
    g.quaternion.set(o.orientation.x, o.orientation.y, o.orientation.z, o.orientation.w);
    g.add(plane);
    return [g, w * h];
  });
}

export function path(THREE, topic) {
  return single(THREE, topic, m => {
    const xyz = m.poses.flatMap(p => [p.pose.position.x, p.pose.position.y, p.pose.position.z]);
    const g = new THREE.BufferGeometry();
    g.setAttribute('position', new THREE.Float32BufferAttribute(xyz, 3));
    return [new THREE.Line(g, new THREE.LineBasicMaterial({ color: 0x19ff00 })), m.poses.length];
  });
}

function arrowSegments(p, q, len) {
  // an arrow along the pose's x axis: shaft and two head strokes, as line segments
  const rot = v => {   // rotate v by quaternion q
    const [x, y, z] = v, { x: qx, y: qy, z: qz, w: qw } = q;
    const ix = qw * x + qy * z - qz * y, iy = qw * y + qz * x - qx * z, iz = qw * z + qx * y - qy * x, iw = -qx * x - qy * y - qz * z;
    return [ix * qw + iw * -qx + iy * -qz - iz * -qy, iy * qw + iw * -qy + iz * -qx - ix * -qz, iz * qw + iw * -qz + ix * -qy - iy * -qx];
  };
  const at = v => { const r = rot(v); return [p.x + r[0], p.y + r[1], p.z + r[2]]; };
  const tip = at([len, 0, 0]);
  return [...at([0, 0, 0]), ...tip, ...tip, ...at([0.7 * len, 0.15 * len, 0]), ...tip, ...at([0.7 * len, -0.15 * len, 0])];
}

export function poseArray(THREE, topic) {
  return single(THREE, topic, m => {
    const xyz = m.poses.flatMap(p => arrowSegments(p.position, p.orientation, 0.3));
    const g = new THREE.BufferGeometry();
    g.setAttribute('position', new THREE.Float32BufferAttribute(xyz, 3));
    return [new THREE.LineSegments(g, new THREE.LineBasicMaterial({ color: 0xff3030 })), m.poses.length];
  });
}

// visualization_msgs/Marker and MarkerArray: ADD/MODIFY, DELETE, DELETEALL, keyed by ns/id
export function markers(THREE, topic) {
  const object = new THREE.Group();
  object.name = topic;
  const live = new Map();   // ns/id -> {obj, frame}
  const remove = k => { const e = live.get(k); if (e) { object.remove(e.obj); e.obj.traverse(o => o.geometry && o.geometry.dispose()); live.delete(k); } };
  const color = c => new THREE.Color(c.r, c.g, c.b);
  const mat = (m, kind = THREE.MeshLambertMaterial) => new kind({ color: color(m.color), transparent: m.color.a < 1, opacity: m.color.a,
    vertexColors: false, side: THREE.DoubleSide });
  const pts = m => m.points.flatMap(p => [p.x, p.y, p.z]);
  const build = m => {
    const s = m.scale;
    switch (m.type) {
      case 0: { const seg = m.points.length === 2 ? pts(m) : arrowSegments({ x: 0, y: 0, z: 0 }, { x: 0, y: 0, z: 0, w: 1 }, s.x);
        const g = new THREE.BufferGeometry(); g.setAttribute('position', new THREE.Float32BufferAttribute(seg.slice(0, 6), 3));
        return new THREE.Line(g, new THREE.LineBasicMaterial({ color: color(m.color) })); }
      case 1: return new THREE.Mesh(new THREE.BoxGeometry(s.x, s.y, s.z), mat(m));
      case 2: { const o = new THREE.Mesh(new THREE.SphereGeometry(0.5, 16, 12), mat(m)); o.scale.set(s.x, s.y, s.z); return o; }
      case 3: { const o = new THREE.Mesh(new THREE.CylinderGeometry(0.5, 0.5, 1, 24), mat(m)); o.rotation.x = Math.PI / 2;
        const g = new THREE.Group(); g.scale.set(s.x, s.y, s.z); g.add(o); return g; }
      case 4: case 5: { const g = new THREE.BufferGeometry(); g.setAttribute('position', new THREE.Float32BufferAttribute(pts(m), 3));
        const lm = new THREE.LineBasicMaterial({ color: color(m.color) });
        return m.type === 4 ? new THREE.Line(g, lm) : new THREE.LineSegments(g, lm); }
      case 6: case 7: { const g = new THREE.Group();
        const geom = m.type === 6 ? new THREE.BoxGeometry(s.x, s.y, s.z) : new THREE.SphereGeometry(s.x / 2, 10, 8);
        m.points.forEach((p, i) => { const c = m.colors[i] ? { ...m.colors[i] } : m.color;
          const o = new THREE.Mesh(geom, mat({ color: c })); o.position.set(p.x, p.y, p.z); g.add(o); }); return g; }
      case 8: { const g = new THREE.BufferGeometry(); g.setAttribute('position', new THREE.Float32BufferAttribute(pts(m), 3));
        return new THREE.Points(g, new THREE.PointsMaterial({ color: color(m.color), size: Math.max(s.x, 0.01), sizeAttenuation: true })); }
      case 11: { const g = new THREE.BufferGeometry(); g.setAttribute('position', new THREE.Float32BufferAttribute(pts(m), 3));
        g.computeVertexNormals(); const o = new THREE.Mesh(g, mat(m)); o.scale.set(s.x || 1, s.y || 1, s.z || 1); return o; }
      default: return null;   // TEXT_VIEW_FACING and MESH_RESOURCE are not drawn
    }
  };
  const one = m => {
    const k = `${m.ns}/${m.id}`;
    if (m.action === 3) { [...live.keys()].forEach(remove); return; }
    remove(k);
    if (m.action === 2) return;
    const inner = build(m);
    if (!inner) return;
    const o = new THREE.Group();
    o.add(inner);
    const pose = new THREE.Group();   // the marker's pose in its frame
    const p = m.pose.position, q = m.pose.orientation;
    pose.position.set(p.x, p.y, p.z);
    if (q.x || q.y || q.z || q.w) pose.quaternion.set(q.x, q.y, q.z, q.w);
    pose.add(o);
    const framed = new THREE.Group();   // placed by TF
    framed.add(pose);
    framed.userData.ns = m.ns;          // the 3D panel's editor picks models by it
    object.add(framed);
    live.set(k, { obj: framed, frame: m.header.frame_id, ns: m.ns, pose: m.pose, stamp: m.header.stamp });
  };
  return {
    object,
    update(msg) { (msg.markers || [msg]).forEach(one); },
    place(setPose) { live.forEach(e => setPose(e.obj, e.frame)); },
    // the markers of one namespace (all with null): [{obj, frame, ns, pose, stamp}], for the 3D
    // panel's editor
    entries: ns => [...live.values()].filter(e => ns === null || e.ns === ns),
    stats: () => ({ count: live.size }),
  };
}
