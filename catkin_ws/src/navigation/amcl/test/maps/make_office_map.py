#!/usr/bin/env python3
"""Writes office.pgm + office.yaml (map_server's format): the space scanner's office world
(space_scanner_simulation/worlds/office.world with ode_sim's models) rasterised at the lidar's
scan plane. Reads the SDF files as data; every collision shape (box, cylinder, sphere) that
crosses the scan plane is drawn occupied, the floor inside the outer walls free, the rest
unknown.

    python3 make_office_map.py [WORLD] [MODELS_DIR]   (defaults: found with rospkg)"""
import math
import os
import re
import sys
import xml.etree.ElementTree as ET

import numpy as np

SCAN_HEIGHT = 0.12        # m above the floor: the laser frame of chassi_bot (top deck)
RESOLUTION = 0.05
ORIGIN = (-6.5, -4.5)
SIZE = (13.0, 9.0)
FREE_BOX = (-6.0, -4.0, 6.0, 4.0)
SUPERSAMPLE = 4


def floats(text, n=6):
    v = [float(x) for x in (text or '').split()]
    return (v + [0.0] * n)[:n]


def pose_of(el):
    p = el.find('pose')
    return floats(p.text) if p is not None else [0.0] * 6


def compose(a, b):
    """(x, y, z, yaw) compositions; roll and pitch are ignored (all shapes stand upright)."""
    c, s = math.cos(a[5]), math.sin(a[5])
    return [a[0] + c * b[0] - s * b[1], a[1] + s * b[0] + c * b[1], a[2] + b[2], 0.0, 0.0, a[5] + b[5]]


def shapes(world, models_dir):
    out = []
    root = ET.parse(world).getroot()
    for inc in root.iter('include'):
        uri = inc.find('uri').text.strip()
        name = uri.split('model://', 1)[1]
        mpose = pose_of(inc)
        mroot = ET.parse(os.path.join(models_dir, name, 'model.sdf')).getroot()
        for link in mroot.iter('link'):
            lpose = compose(mpose, pose_of(link))
            for col in link.iter('collision'):
                cpose = compose(lpose, pose_of(col))
                geo = col.find('geometry')
                box, cyl, sph = geo.find('box'), geo.find('cylinder'), geo.find('sphere')
                if box is not None:
                    sx, sy, sz = floats(box.find('size').text, 3)
                    out.append(('box', cpose, (sx, sy, sz)))
                elif cyl is not None:
                    out.append(('cylinder', cpose, (float(cyl.find('radius').text), float(cyl.find('length').text))))
                elif sph is not None:
                    out.append(('sphere', cpose, (float(sph.find('radius').text),)))
    return out


def rasterise(shape_list, h=SCAN_HEIGHT):
    w, hgt = int(round(SIZE[0] / RESOLUTION)), int(round(SIZE[1] / RESOLUTION))
    n = SUPERSAMPLE
    xs = ORIGIN[0] + (np.arange(w * n) + 0.5) * RESOLUTION / n
    ys = ORIGIN[1] + (np.arange(hgt * n) + 0.5) * RESOLUTION / n
    X, Y = np.meshgrid(xs, ys)
    occ = np.zeros(X.shape, dtype=bool)
    for kind, p, dims in shape_list:
        dx, dy = X - p[0], Y - p[1]
        if kind == 'box':
            sx, sy, sz = dims
            if not (p[2] - sz / 2 <= h <= p[2] + sz / 2):
                continue
            c, s = math.cos(p[5]), math.sin(p[5])
            lx, ly = c * dx + s * dy, -s * dx + c * dy
            occ |= (np.abs(lx) <= sx / 2) & (np.abs(ly) <= sy / 2)
        elif kind == 'cylinder':
            r, length = dims
            if not (p[2] - length / 2 <= h <= p[2] + length / 2):
                continue
            occ |= dx * dx + dy * dy <= r * r
        else:
            r = dims[0]
            if abs(h - p[2]) >= r:
                continue
            rr = r * r - (h - p[2]) ** 2
            occ |= dx * dx + dy * dy <= rr
    occ = occ.reshape(hgt, n, w, n).any(axis=(1, 3))
    cx = ORIGIN[0] + (np.arange(w) + 0.5) * RESOLUTION
    cy = ORIGIN[1] + (np.arange(hgt) + 0.5) * RESOLUTION
    CX, CY = np.meshgrid(cx, cy)
    inside = (CX > FREE_BOX[0]) & (CX < FREE_BOX[2]) & (CY > FREE_BOX[1]) & (CY < FREE_BOX[3])
    img = np.full((hgt, w), 205, dtype=np.uint8)      # unknown
    img[inside] = 254
    img[occ] = 0
    return img[::-1]                                   # image row 0 = top (max y)


def main(argv):
    if len(argv) > 2:
        world, models = argv[1], argv[2]
    else:
        import rospkg
        rp = rospkg.RosPack()
        world = os.path.join(rp.get_path('space_scanner_simulation'), 'worlds', 'office.world')
        models = os.path.join(rp.get_path('ode_sim'), 'models')
    img = rasterise(shapes(world, models))
    here = os.path.dirname(os.path.abspath(__file__))
    with open(os.path.join(here, 'office.pgm'), 'wb') as f:
        f.write(b'P5\n# office.world at z %.2f m (make_office_map.py)\n%d %d\n255\n' % (SCAN_HEIGHT, img.shape[1], img.shape[0]))
        f.write(img.tobytes())
    with open(os.path.join(here, 'office.yaml'), 'w') as f:
        f.write('image: office.pgm\nresolution: %.3f\norigin: [%.3f, %.3f, 0.0]\nnegate: 0\n'
                'occupied_thresh: 0.65\nfree_thresh: 0.196\n' % (RESOLUTION, ORIGIN[0], ORIGIN[1]))
    print('office.pgm: %d x %d, %d occupied cells' % (img.shape[1], img.shape[0], int((img == 0).sum())))


if __name__ == '__main__':
    main(sys.argv)
