#!/usr/bin/python3
"""Writes meshes/base.dae, the diploma's chassis mesh (package://space_scanner_simulation/
meshes/base.dae): the 260 x 150 mm platform of three green decks 32 mm apart (4 mm plates),
four brass standoffs at the corners and the grey battery pack on the bottom deck, in the frame
of base_link (the bottom deck's centre, at the wheel axles: 32.5 mm above the ground, so the
top deck's upper face is at 100 mm). The geometry is written as a Wavefront OBJ + MTL and
converted to COLLADA by assimp (Debian's assimp-utils), the same library RViz loads meshes with;
the file says <up_axis>Z_UP</up_axis> and <unit meter="1"/>, as ROS meshes do.

    rosrun space_scanner_simulation make_base_mesh.py [OUT.dae]"""
import math
import os
import subprocess
import sys
import tempfile

DECK = (0.26, 0.15, 0.004)          # length, width, thickness (m)
DECK_Z = (0.0, 0.032, 0.064)        # deck centres above base_link
STANDOFF_INSET = (0.015, 0.012)     # from the deck's ends and sides
STANDOFF_RADIUS = 0.003
BATTERY = ((-0.04, 0.0, DECK[2] / 2 + 0.0125), (0.08, 0.075, 0.025))   # centre, size

MATERIALS = {                       # the description's colours (materials.xacro)
    'deck_green': (0.1, 0.75, 0.2),
    'brass': (0.8, 0.65, 0.2),
    'battery_grey': (0.35, 0.35, 0.35),
}


def box(centre, size):
    """(vertices, quads) of an axis-aligned box, faces wound counter-clockwise seen from
    outside."""
    cx, cy, cz = centre
    hx, hy, hz = (s / 2 for s in size)
    v = [(cx + sx * hx, cy + sy * hy, cz + sz * hz)
         for sx in (-1, 1) for sy in (-1, 1) for sz in (-1, 1)]
    # index = 4 * (sx > 0) + 2 * (sy > 0) + (sz > 0)
    quads = [(0, 1, 3, 2), (4, 6, 7, 5),      # -x, +x
             (0, 4, 5, 1), (2, 3, 7, 6),      # -y, +y
             (0, 2, 6, 4), (1, 5, 7, 3)]      # -z, +z
    return v, quads


def prism(centre, radius, height, sides=8):
    """(vertices, faces) of an upright regular prism (a cylinder's stand-in)."""
    cx, cy, cz = centre
    v = []
    for k in range(sides):
        a = 2 * math.pi * k / sides
        for z in (cz - height / 2, cz + height / 2):
            v.append((cx + radius * math.cos(a), cy + radius * math.sin(a), z))
    faces = []
    for k in range(sides):
        b0, t0, b1, t1 = 2 * k, 2 * k + 1, 2 * ((k + 1) % sides), 2 * ((k + 1) % sides) + 1
        faces.append((b0, b1, t1, t0))
    faces.append(tuple(2 * k + 1 for k in range(sides)))                 # top
    faces.append(tuple(2 * k for k in reversed(range(sides))))          # bottom
    return v, faces


def parts():
    """[(material, vertices, faces)] of the chassis."""
    out = [('deck_green',) + box((0.0, 0.0, z), DECK) for z in DECK_Z]
    x = DECK[0] / 2 - STANDOFF_INSET[0]
    y = DECK[1] / 2 - STANDOFF_INSET[1]
    z0, z1 = DECK_Z[0] + DECK[2] / 2, DECK_Z[-1] - DECK[2] / 2
    for sx in (1, -1):
        for sy in (1, -1):
            out.append(('brass',) + prism((sx * x, sy * y, (z0 + z1) / 2), STANDOFF_RADIUS, z1 - z0))
    out.append(('battery_grey',) + box(*BATTERY))
    return out


def write_obj(obj_path):
    mtl_path = os.path.splitext(obj_path)[0] + '.mtl'
    with open(mtl_path, 'w') as f:
        for name, (r, g, b) in MATERIALS.items():
            f.write('newmtl %s\nKa 0 0 0\nKd %.4f %.4f %.4f\nKs 0.1 0.1 0.1\nNs 10\nd 1\nillum 2\n\n'
                    % (name, r, g, b))
    with open(obj_path, 'w') as f:
        f.write('# the space scanner chassis (space_scanner_simulation/scripts/make_base_mesh.py)\n')
        f.write('mtllib %s\n' % os.path.basename(mtl_path))
        base = 1
        for k, (mat, verts, faces) in enumerate(parts()):
            f.write('o part_%d\nusemtl %s\n' % (k, mat))
            for p in verts:
                f.write('v %.6f %.6f %.6f\n' % p)
            for face in faces:
                f.write('f %s\n' % ' '.join(str(base + i) for i in face))
            base += len(verts)


def make(dae_path):
    """Write the chassis as COLLADA to dae_path (via OBJ and `assimp export`)."""
    with tempfile.TemporaryDirectory() as tmp:
        obj = os.path.join(tmp, 'base.obj')
        write_obj(obj)
        r = subprocess.run(['assimp', 'export', obj, os.path.abspath(dae_path), '-fcollada'],
                           capture_output=True, text=True)
        if r.returncode != 0 or not os.path.isfile(dae_path):
            raise RuntimeError('assimp export failed (%d): %s' % (r.returncode, (r.stderr or r.stdout)[-2000:]))
    # the vertices are z-up (ROS): say so. assimp's exporter writes Y_UP; Gazebo-like loaders
    # honour the tag, RViz ignores it (it drops the root rotation assimp adds for Z_UP)
    with open(dae_path) as f:
        text = f.read()
    if '<up_axis>Y_UP</up_axis>' not in text:
        raise RuntimeError('%s: assimp wrote no <up_axis>Y_UP</up_axis> to replace' % dae_path)
    with open(dae_path, 'w') as f:
        f.write(text.replace('<up_axis>Y_UP</up_axis>', '<up_axis>Z_UP</up_axis>'))


if __name__ == '__main__':
    here = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    out = sys.argv[1] if len(sys.argv) > 1 else os.path.join(here, 'meshes', 'base.dae')
    os.makedirs(os.path.dirname(os.path.abspath(out)), exist_ok=True)
    make(out)
    print(out)
