"""Test and bench helper shared by the navigation packages and the demo: the occupancy grid of an
SDF world (box, cylinder and sphere collisions cut at the robot's height band), read from the
world file and the model library (`model://` from ode_sim's models/ and GAZEBO_MODEL_PATH), no
simulator code involved.

Values: 100 occupied, 0 free (the whole area is known), as map_server serves a saved map.
"""
import math
import os
import xml.etree.ElementTree as ET

import numpy as np


def _pose(text):
    v = [float(t) for t in (text or '').split()] + [0.0] * 6
    return v[:6]


def _compose(a, b):
    """Planar composition of 6-vector poses (x, y, z, roll, pitch, yaw); roll/pitch ignored."""
    c, s = math.cos(a[5]), math.sin(a[5])
    return [a[0] + c * b[0] - s * b[1], a[1] + s * b[0] + c * b[1], a[2] + b[2], 0.0, 0.0,
            a[5] + b[5]]


def model_dirs():
    dirs = []
    for d in os.environ.get('GAZEBO_MODEL_PATH', '').split(':'):
        if d:
            dirs.append(d)
    try:
        import rospkg
        dirs.append(os.path.join(rospkg.RosPack().get_path('ode_sim'), 'models'))
    except Exception:
        here = os.path.dirname(os.path.abspath(__file__))
        dirs.append(os.path.normpath(os.path.join(here, '../../../sim/ode_sim/models')))
    return dirs


def _find_model(uri):
    name = uri.replace('model://', '').strip('/')
    for d in model_dirs():
        p = os.path.join(d, name, 'model.sdf')
        if os.path.exists(p):
            return p
    raise FileNotFoundError('model %s not found in %s' % (uri, model_dirs()))


def _collisions(model_el, model_pose):
    out = []
    for link in model_el.findall('link'):
        lp = _compose(model_pose, _pose(link.findtext('pose')))
        for col in link.findall('collision'):
            cp = _compose(lp, _pose(col.findtext('pose')))
            geom = col.find('geometry')
            if geom is None or len(geom) == 0:
                continue
            g = geom[0]
            if g.tag == 'box':
                sx, sy, sz = (float(t) for t in g.findtext('size').split())
                out.append(('box', cp, (sx, sy, sz)))
            elif g.tag == 'cylinder':
                out.append(('cylinder', cp, (float(g.findtext('radius')),
                                             float(g.findtext('length')))))
            elif g.tag == 'sphere':
                out.append(('sphere', cp, (float(g.findtext('radius')),)))
    return out


def world_collisions(world_file):
    root = ET.parse(world_file).getroot()
    world = root.find('world')
    out = []
    for inc in world.findall('include'):
        uri = inc.findtext('uri')
        if uri in ('model://sun', 'model://ground_plane'):
            continue
        model = ET.parse(_find_model(uri)).getroot().find('model')
        pose = _compose(_pose(inc.findtext('pose')), _pose(model.findtext('pose')))
        out.extend(_collisions(model, pose))
    for model in world.findall('model'):
        if model.get('name') == 'ground_plane':
            continue
        out.extend(_collisions(model, _pose(model.findtext('pose'))))
    return out


def rasterize(collisions, resolution=0.05, z_band=(0.02, 0.4), margin=0.5):
    """-> (values int8 [ny, nx], origin_x, origin_y)."""
    shapes = []
    for kind, p, dims in collisions:
        if kind == 'box':
            z0, z1 = p[2] - dims[2] / 2, p[2] + dims[2] / 2
            c, sn = abs(math.cos(p[5])), abs(math.sin(p[5]))
            r = (c * dims[0] / 2 + sn * dims[1] / 2, sn * dims[0] / 2 + c * dims[1] / 2)
        elif kind == 'cylinder':
            z0, z1 = p[2] - dims[1] / 2, p[2] + dims[1] / 2
            r = (dims[0], dims[0])
        else:
            z0, z1 = p[2] - dims[0], p[2] + dims[0]
            r = (dims[0], dims[0])
        if z1 < z_band[0] or z0 > z_band[1]:
            continue
        shapes.append((kind, p, dims, r))
    xs = [s[1][0] - s[3][0] for s in shapes] + [s[1][0] + s[3][0] for s in shapes]
    ys = [s[1][1] - s[3][1] for s in shapes] + [s[1][1] + s[3][1] for s in shapes]
    ox = math.floor((min(xs) - margin) / resolution) * resolution
    oy = math.floor((min(ys) - margin) / resolution) * resolution
    nx = int(math.ceil((max(xs) + margin - ox) / resolution))
    ny = int(math.ceil((max(ys) + margin - oy) / resolution))
    gx, gy = np.meshgrid(ox + (np.arange(nx) + 0.5) * resolution,
                         oy + (np.arange(ny) + 0.5) * resolution)
    occ = np.zeros((ny, nx), dtype=bool)
    half = resolution / 2
    for kind, p, dims, r in shapes:
        dx, dy = gx - p[0], gy - p[1]
        if kind == 'box':
            c, s = math.cos(p[5]), math.sin(p[5])
            lx = c * dx + s * dy
            ly = -s * dx + c * dy
            occ |= (np.abs(lx) <= dims[0] / 2 + half) & (np.abs(ly) <= dims[1] / 2 + half)
        else:
            occ |= np.hypot(dx, dy) <= dims[0] + half
    return np.where(occ, 100, 0).astype(np.int8), ox, oy


def world_map(world_file, resolution=0.05):
    return rasterize(world_collisions(world_file), resolution)


def occupancy_grid(world_file, resolution=0.05, frame='map'):
    """nav_msgs/OccupancyGrid of the world (imports rospy messages lazily)."""
    import rospy
    from course_runtime.occupancy import occupancy_grid as build
    values, ox, oy = world_map(world_file, resolution)
    return build(values, resolution, (ox, oy), frame, rospy.Time.now())


if __name__ == '__main__':
    import sys
    v, ox, oy = world_map(sys.argv[1])
    for row in v[::-4, ::2]:
        print(''.join('#' if c else '.' for c in row))
    print(v.shape, ox, oy)


def rasterize_slice(collisions, height, origin, size, resolution=0.05, supersample=4, free_box=None):
    """The world cut by the horizontal plane at `height` (a lidar's scan plane) as a map_server
    image: uint8 rows top = max y, 0 occupied, 254 free (inside free_box = (x0, y0, x1, y1)),
    205 unknown. Each cell is occupied if any of supersample² sub-cells is inside a shape."""
    w, h = int(round(size[0] / resolution)), int(round(size[1] / resolution))
    n = supersample
    X, Y = np.meshgrid(origin[0] + (np.arange(w * n) + 0.5) * resolution / n,
                       origin[1] + (np.arange(h * n) + 0.5) * resolution / n)
    occ = np.zeros(X.shape, dtype=bool)
    for kind, p, dims in collisions:
        dx, dy = X - p[0], Y - p[1]
        if kind == 'box':
            sx, sy, sz = dims
            if not (p[2] - sz / 2 <= height <= p[2] + sz / 2):
                continue
            c, s = math.cos(p[5]), math.sin(p[5])
            occ |= (np.abs(c * dx + s * dy) <= sx / 2) & (np.abs(-s * dx + c * dy) <= sy / 2)
        elif kind == 'cylinder':
            r, length = dims
            if p[2] - length / 2 <= height <= p[2] + length / 2:
                occ |= dx * dx + dy * dy <= r * r
        else:
            r = dims[0]
            if abs(height - p[2]) < r:
                occ |= dx * dx + dy * dy <= r * r - (height - p[2]) ** 2
    occ = occ.reshape(h, n, w, n).any(axis=(1, 3))
    img = np.full((h, w), 205, dtype=np.uint8)
    if free_box is not None:
        cx, cy = np.meshgrid(origin[0] + (np.arange(w) + 0.5) * resolution,
                             origin[1] + (np.arange(h) + 0.5) * resolution)
        img[(cx > free_box[0]) & (cx < free_box[2]) & (cy > free_box[1]) & (cy < free_box[3])] = 254
    img[occ] = 0
    return img[::-1]


def write_map_files(img, base, origin, resolution, comment):
    """base.pgm + base.yaml in map_server's format (trinary thresholds 0.65 / 0.196)."""
    with open(base + '.pgm', 'wb') as f:
        f.write(b'P5\n# %s\n%d %d\n255\n' % (comment.encode(), img.shape[1], img.shape[0]))
        f.write(img.tobytes())
    with open(base + '.yaml', 'w') as f:
        f.write('image: %s.pgm\nresolution: %.3f\norigin: [%.3f, %.3f, 0.0]\nnegate: 0\n'
                'occupied_thresh: 0.65\nfree_thresh: 0.196\n' % (
                    os.path.basename(base), resolution, origin[0], origin[1]))
