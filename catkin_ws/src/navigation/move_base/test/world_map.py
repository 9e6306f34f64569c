"""Test and bench helper: the occupancy grid of an SDF world (box, cylinder and sphere
collisions cut at the robot's height band), read from the world file and the model library
(`model://` from ode_sim's models/ and GAZEBO_MODEL_PATH), no simulator code involved.

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
    from nav_msgs.msg import OccupancyGrid
    import rospy
    values, ox, oy = world_map(world_file, resolution)
    msg = OccupancyGrid()
    msg.header.frame_id = frame
    msg.header.stamp = rospy.Time.now()
    msg.info.resolution = resolution
    msg.info.height, msg.info.width = values.shape
    msg.info.origin.position.x = ox
    msg.info.origin.position.y = oy
    msg.info.origin.orientation.w = 1.0
    msg.data = values.ravel().tolist()
    return msg


if __name__ == '__main__':
    import sys
    v, ox, oy = world_map(sys.argv[1])
    for row in v[::-4, ::2]:
        print(''.join('#' if c else '.' for c in row))
    print(v.shape, ox, oy)
