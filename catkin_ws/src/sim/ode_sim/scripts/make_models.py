#!/usr/bin/env python3
"""Generate ode_sim's model library (models/NAME/{model.config,model.sdf,meshes/*.stl} and
models/README.md) from the definitions below. Deterministic: running it again gives
byte-identical files.

    python3 scripts/make_models.py            # writes into the package's models/
    python3 scripts/make_models.py --out DIR  # writes somewhere else (tests compare)

Every object's origin is at the centre of its footprint on the floor (z = 0 at its bottom),
its front faces +x. Sizes in metres, masses in kg.
"""
import argparse
import math
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
PKG = os.path.dirname(HERE)
sys.path.insert(0, os.path.join(PKG, 'src'))

from ode_sim.description import meshgen as mg  # noqa: E402
from ode_sim.description.meshgen import box, box_between, combine, cylinder, ellipsoid, lathe, ring  # noqa

SDF_VERSION = '1.6'
AUTHOR = 'ode_sim authors'
PI = math.pi

# colours (RGBA)
WOOD = (0.55, 0.36, 0.2, 1.0)
DARK_WOOD = (0.36, 0.22, 0.12, 1.0)
LIGHT_WOOD = (0.78, 0.62, 0.42, 1.0)
OAK = (0.72, 0.56, 0.36, 1.0)
BLACK = (0.08, 0.08, 0.08, 1.0)
DARK_GREY = (0.25, 0.25, 0.27, 1.0)
METAL = (0.6, 0.62, 0.65, 1.0)
LIGHT_GREY = (0.78, 0.79, 0.8, 1.0)
WHITE = (0.92, 0.92, 0.9, 1.0)
NAVY = (0.15, 0.2, 0.4, 1.0)
FABRIC = (0.35, 0.45, 0.42, 1.0)
CUSHION = (0.45, 0.56, 0.52, 1.0)
ORANGE = (1.0, 0.4, 0.0, 1.0)
BLUE = (0.1, 0.25, 0.6, 1.0)
CARDBOARD = (0.66, 0.5, 0.32, 1.0)
TAPE = (0.82, 0.72, 0.55, 1.0)
TERRACOTTA = (0.72, 0.36, 0.22, 1.0)
SOIL = (0.25, 0.17, 0.1, 1.0)
LEAF = (0.18, 0.48, 0.16, 1.0)
LEAF_LIGHT = (0.3, 0.6, 0.22, 1.0)
RED = (0.8, 0.05, 0.05, 1.0)
BOOK_RED = (0.6, 0.12, 0.1, 1.0)
BOOK_BLUE = (0.15, 0.3, 0.55, 1.0)
BOOK_GREEN = (0.2, 0.45, 0.3, 1.0)
WALL = (0.85, 0.82, 0.75, 1.0)
MAZE_WALL = (0.6, 0.65, 0.75, 1.0)


def fmt(v, digits=6):
    s = ('%.*f' % (digits, v)).rstrip('0').rstrip('.')
    return '0' if s in ('-0', '') else s


def vec(values, digits=6):
    return ' '.join(fmt(v, digits) for v in values)


class Obj:
    """A real-world object: visuals are meshes (one per colour), collisions are primitives
    (kind, dims, xyz, rpy, weight) that also give the inertia."""

    def __init__(self, name, title, size, mass, static=False):
        self.name, self.title, self.size, self.mass, self.static = name, title, size, mass, static
        self.visuals = []      # (name, rgba, Part)
        self.collisions = []   # (name, kind, dims, xyz, rpy, weight)

    def visual(self, name, rgba, parts):
        self.visuals.append((name, rgba, combine(parts) if isinstance(parts, list) else parts))

    def coll_box(self, name, lo, hi, weight=1.0):
        lo, hi = [float(v) for v in lo], [float(v) for v in hi]
        self.collisions.append((name, 'box', tuple(h - l for l, h in zip(lo, hi)),
                                tuple((l + h) / 2 for l, h in zip(lo, hi)), (0.0, 0.0, 0.0),
                                weight))

    def coll_cyl(self, name, r, z0, z1, xy=(0.0, 0.0), weight=1.0):
        self.collisions.append((name, 'cylinder', (r, z1 - z0), (xy[0], xy[1], (z0 + z1) / 2),
                                (0.0, 0.0, 0.0), weight))

    def coll_sphere(self, name, r, xyz, weight=1.0):
        self.collisions.append((name, 'sphere', (r,), tuple(xyz), (0.0, 0.0, 0.0), weight))

    def mesh_uri(self, vname):
        return 'model://%s/meshes/%s.stl' % (self.name, vname)


# ------------------------------------------------------------------------- objects

def table():
    o = Obj('table', 'Dining table of wood, 4 legs', (1.2, 0.8, 0.75), 25.0)
    o.visual('top', WOOD, box_between((-0.6, -0.4, 0.71), (0.6, 0.4, 0.75)))
    legs = [box_between((sx * 0.56 - 0.03, sy * 0.36 - 0.03, 0), (sx * 0.56 + 0.03,
                                                                   sy * 0.36 + 0.03, 0.71))
            for sx in (-1, 1) for sy in (-1, 1)]
    apron = [box_between((-0.53, -0.35, 0.63), (0.53, -0.33, 0.71)),
             box_between((-0.53, 0.33, 0.63), (0.53, 0.35, 0.71)),
             box_between((-0.55, -0.33, 0.63), (-0.53, 0.33, 0.71)),
             box_between((0.53, -0.33, 0.63), (0.55, 0.33, 0.71))]
    o.visual('frame', DARK_WOOD, legs + apron)
    o.coll_box('top', (-0.6, -0.4, 0.63), (0.6, 0.4, 0.75))
    for i, (sx, sy) in enumerate((sx, sy) for sx in (-1, 1) for sy in (-1, 1)):
        o.coll_box('leg%d' % i, (sx * 0.56 - 0.03, sy * 0.36 - 0.03, 0),
                   (sx * 0.56 + 0.03, sy * 0.36 + 0.03, 0.63))
    return o


def chair():
    o = Obj('chair', 'Chair: padded seat and backrest on a black metal frame', (0.48, 0.44, 0.9),
            6.0)
    frame = []
    for sx in (-1, 1):
        for sy in (-1, 1):
            top = 0.9 if sx < 0 else 0.42
            frame.append(box_between((sx * 0.22 - 0.02, sy * 0.2 - 0.02, 0),
                                     (sx * 0.22 + 0.02, sy * 0.2 + 0.02, top)))
    frame.append(box_between((-0.2, -0.2, 0.38), (0.2, -0.18, 0.41)))   # side rails
    frame.append(box_between((-0.2, 0.18, 0.38), (0.2, 0.2, 0.41)))
    o.visual('frame', BLACK, frame)
    o.visual('seat', NAVY, [box_between((-0.21, -0.22, 0.42), (0.24, 0.22, 0.47)),
                            box_between((-0.2, -0.18, 0.6), (-0.17, 0.18, 0.88))])
    o.coll_box('seat', (-0.24, -0.22, 0.38), (0.24, 0.22, 0.47))
    o.coll_box('back', (-0.24, -0.22, 0.47), (-0.17, 0.22, 0.9), weight=0.5)
    for i, (sx, sy) in enumerate((sx, sy) for sx in (-1, 1) for sy in (-1, 1)):
        o.coll_box('leg%d' % i, (sx * 0.22 - 0.02, sy * 0.2 - 0.02, 0),
                   (sx * 0.22 + 0.02, sy * 0.2 + 0.02, 0.38))
    return o


def bookshelf():
    o = Obj('bookshelf', 'Bookshelf with four shelves of books', (0.3, 0.8, 1.8), 35.0,
            static=True)
    w, d, h, t = 0.4, 0.15, 1.8, 0.02
    shelves_z = [0.08, 0.5, 0.92, 1.34]
    body = [box_between((-d, -w, 0), (d, -w + t, h)), box_between((-d, w - t, 0), (d, w, h)),
            box_between((-d, -w + t, h - t), (d, w - t, h)),
            box_between((-d, -w + t, 0), (-d + 0.01, w - t, h - t)),
            box_between((-d + 0.01, -w + t, 0), (d, w - t, 0.08 - t))]
    body += [box_between((-d + 0.01, -w + t, z - t), (d - 0.005, w - t, z)) for z in shelves_z[1:]]
    o.visual('case', WOOD, body)
    # books: deterministic widths/heights, three colours taking turns
    books = {0: [], 1: [], 2: []}
    pattern = [(0.035, 0.30), (0.05, 0.26), (0.03, 0.33), (0.045, 0.24), (0.04, 0.28),
               (0.06, 0.31), (0.025, 0.22), (0.04, 0.34)]
    for s, z in enumerate(shelves_z):
        y, i = -w + t + 0.01, s * 3
        limit = w - t - (0.15 if s % 2 else 0.04)
        while True:
            bw, bh = pattern[i % len(pattern)]
            if y + bw > limit:
                break
            bh = min(bh, 0.38)
            books[i % 3].append(box_between((-d + 0.03, y, z), (d - 0.02, y + bw - 0.002, z + bh)))
            y += bw
            i += 1
    o.visual('books_red', BOOK_RED, books[0])
    o.visual('books_blue', BOOK_BLUE, books[1])
    o.visual('books_green', BOOK_GREEN, books[2])
    o.coll_box('left', (-d, -w, 0), (d, -w + t, h))
    o.coll_box('right', (-d, w - t, 0), (d, w, h))
    o.coll_box('back', (-d, -w + t, 0), (-d + 0.01, w - t, h))
    o.coll_box('top', (-d + 0.01, -w + t, h - t), (d, w - t, h))
    for k, z in enumerate(shelves_z):
        o.coll_box('shelf%d' % k, (-d + 0.01, -w + t, 0 if k == 0 else z - t), (d, w - t, z),
                   weight=1.0)
    return o


def sofa():
    o = Obj('sofa', 'Two-seat fabric sofa on wooden feet', (0.9, 2.0, 0.85), 60.0)
    o.visual('body', FABRIC, [box_between((-0.45, -0.85, 0.1), (0.45, 0.85, 0.4)),
                              box_between((-0.45, -0.85, 0.4), (-0.25, 0.85, 0.85)),
                              box_between((-0.45, -1.0, 0.1), (0.45, -0.85, 0.65)),
                              box_between((-0.45, 0.85, 0.1), (0.45, 1.0, 0.65))])
    o.visual('cushions', CUSHION, [box_between((-0.25, -0.84, 0.4), (0.44, -0.01, 0.52)),
                                   box_between((-0.25, 0.01, 0.4), (0.44, 0.84, 0.52)),
                                   box_between((-0.25, -0.82, 0.52), (-0.13, -0.02, 0.8)),
                                   box_between((-0.25, 0.02, 0.52), (-0.13, 0.82, 0.8))])
    o.visual('feet', DARK_WOOD, [cylinder(0.03, 0.1, (sx * 0.38, sy * 0.92, 0.05), segments=12)
                                 for sx in (-1, 1) for sy in (-1, 1)])
    o.coll_box('seat', (-0.45, -0.85, 0.0), (0.45, 0.85, 0.52))
    o.coll_box('back', (-0.45, -0.85, 0.52), (-0.25, 0.85, 0.85))
    o.coll_box('arm_right', (-0.45, -1.0, 0.0), (0.45, -0.85, 0.65))
    o.coll_box('arm_left', (-0.45, 0.85, 0.0), (0.45, 1.0, 0.65))
    return o


def door_frame():
    o = Obj('door_frame', 'Door frame with a 0.9 m x 2.0 m opening', (0.17, 1.14, 2.12),
            30.0, static=True)
    frame = [box_between((-0.075, -0.55, 0), (0.075, -0.45, 2.0)),
             box_between((-0.075, 0.45, 0), (0.075, 0.55, 2.0)),
             box_between((-0.075, -0.55, 2.0), (0.075, 0.55, 2.1))]
    trim = []
    for sx in (-1, 1):
        x0, x1 = sorted((sx * 0.075, sx * 0.085))
        trim += [box_between((x0, -0.57, 0), (x1, -0.45, 2.0)),
                 box_between((x0, 0.45, 0), (x1, 0.57, 2.0)),
                 box_between((x0, -0.57, 2.0), (x1, 0.57, 2.12))]
    o.visual('frame', WHITE, frame)
    o.visual('trim', LIGHT_WOOD, trim)
    o.coll_box('jamb_right', (-0.085, -0.57, 0), (0.085, -0.45, 2.0))
    o.coll_box('jamb_left', (-0.085, 0.45, 0), (0.085, 0.57, 2.0))
    o.coll_box('header', (-0.085, -0.57, 2.0), (0.085, 0.57, 2.12))
    return o


def trash_bin():
    o = Obj('trash_bin', 'Plastic waste bin, tapered, open top', (0.38, 0.38, 0.45), 2.0)
    o.visual('bin', DARK_GREY, lathe([(0.0, 0.0), (0.15, 0.0), (0.18, 0.43), (0.19, 0.43),
                                      (0.19, 0.45), (0.172, 0.45), (0.142, 0.012), (0.0, 0.012)],
                                     32))
    o.visual('bag', BLACK, lathe([(0.0, 0.012), (0.141, 0.012), (0.152, 0.18), (0.0, 0.18)], 32))
    o.coll_cyl('body', 0.17, 0.0, 0.45)
    return o


def traffic_cone():
    o = Obj('traffic_cone', 'Traffic cone, 0.7 m, orange with reflective bands',
            (0.38, 0.38, 0.7), 3.0)

    def r(z):
        return 0.13 - 0.1 * (z - 0.03) / 0.67

    o.visual('base', BLACK, box_between((-0.19, -0.19, 0), (0.19, 0.19, 0.03)))
    o.visual('cone', ORANGE, lathe([(0.0, 0.03), (0.13, 0.03), (0.03, 0.7), (0.0, 0.7)], 24))
    bands = [lathe([(r(z0) - 0.004, z0), (r(z0) + 0.002, z0), (r(z1) + 0.002, z1),
                    (r(z1) - 0.004, z1)], 24) for z0, z1 in ((0.3, 0.4), (0.48, 0.55))]
    o.visual('bands', WHITE, bands)
    o.coll_box('base', (-0.19, -0.19, 0), (0.19, 0.19, 0.03), weight=3.0)
    o.coll_cyl('lower', 0.105, 0.03, 0.36)
    o.coll_cyl('upper', 0.055, 0.36, 0.7)
    return o


def barrel():
    o = Obj('barrel', 'Steel drum, 200 l (55 gal), empty', (0.585, 0.585, 0.88), 20.0)
    R, r = 0.2925, 0.2875
    o.visual('drum', BLUE, lathe([(0.0, 0.0), (0.28, 0.0), (R, 0.015), (r, 0.03), (r, 0.28),
                                  (R, 0.29), (r, 0.3), (r, 0.58), (R, 0.59), (r, 0.6),
                                  (r, 0.85), (R, 0.865), (0.28, 0.88), (0.27, 0.88),
                                  (0.27, 0.87), (0.0, 0.87)], 32))
    o.visual('bungs', BLACK, [cylinder(0.025, 0.01, (0.19, 0.0, 0.875), segments=12),
                              cylinder(0.015, 0.01, (-0.19, 0.0, 0.875), segments=12)])
    o.coll_cyl('drum', R, 0.0, 0.88)
    return o


def box_pallet():
    o = Obj('box_pallet', 'EUR pallet (1.2 x 0.8 m) loaded with cardboard boxes',
            (1.2, 0.8, 0.844), 70.0)
    wood = []
    for y in (-0.3275, 0.0, 0.3275):
        wood.append(box_between((-0.6, y - 0.0725, 0), (0.6, y + 0.0725, 0.022)))
        for x in (-0.5275, 0.0, 0.5275):
            wood.append(box_between((x - 0.0725, y - 0.05, 0.022), (x + 0.0725, y + 0.05, 0.1)))
    for x in (-0.5275, 0.0, 0.5275):
        wood.append(box_between((x - 0.0725, -0.4, 0.1), (x + 0.0725, 0.4, 0.122)))
    for y in (-0.35, -0.175, 0.0, 0.175, 0.35):
        wood.append(box_between((-0.6, y - 0.05, 0.122), (0.6, y + 0.05, 0.144)))
    o.visual('pallet', LIGHT_WOOD, wood)
    z0 = 0.144
    boxes, tape = [], []
    cartons = [((sx * 0.3, sy * 0.2, z0), (0.59, 0.39, 0.4)) for sx in (-1, 1) for sy in (-1, 1)]
    z1 = z0 + 0.4
    cartons += [((-0.3, -0.2, z1), (0.59, 0.39, 0.3)), ((-0.3, 0.2, z1), (0.59, 0.39, 0.3)),
                ((0.25, 0.0, z1), (0.4, 0.3, 0.25))]
    for (cx, cy, cz), (sx, sy, sz) in cartons:
        boxes.append(box_between((cx - sx / 2, cy - sy / 2, cz), (cx + sx / 2, cy + sy / 2,
                                                                  cz + sz)))
        tape.append(box_between((cx - sx / 2 - 0.001, cy - 0.025, cz + sz - 0.08),
                                (cx + sx / 2 + 0.001, cy + 0.025, cz + sz)))
    o.visual('cartons', CARDBOARD, boxes)
    o.visual('tape', TAPE, tape)
    o.coll_box('pallet', (-0.6, -0.4, 0), (0.6, 0.4, 0.144), weight=0.4)
    o.coll_box('layer1', (-0.595, -0.395, z0), (0.595, 0.395, z1), weight=0.12)
    o.coll_box('layer2', (-0.595, -0.395, z1), (-0.005, 0.395, z1 + 0.3), weight=0.12)
    o.coll_box('carton', (0.05, -0.15, z1), (0.45, 0.15, z1 + 0.25), weight=0.12)
    return o


def potted_plant():
    o = Obj('potted_plant', 'Indoor plant in a terracotta pot', (0.48, 0.44, 1.1), 9.0)
    o.visual('pot', TERRACOTTA, lathe([(0.0, 0.0), (0.12, 0.0), (0.15, 0.27), (0.16, 0.27),
                                       (0.16, 0.3), (0.145, 0.3), (0.112, 0.015), (0.0, 0.015)],
                                      24))
    o.visual('soil', SOIL, [lathe([(0.0, 0.015), (0.111, 0.015), (0.14, 0.26), (0.0, 0.26)], 24),
                            cylinder(0.02, 0.3, (0.0, 0.0, 0.4), segments=8)])
    o.visual('leaves', LEAF, [ellipsoid((0.24, 0.22, 0.3), (0.0, 0.0, 0.75)),
                              ellipsoid((0.15, 0.14, 0.15), (-0.08, -0.06, 0.95))])
    o.visual('leaves_light', LEAF_LIGHT, [ellipsoid((0.16, 0.16, 0.18), (0.08, 0.06, 0.62)),
                                          ellipsoid((0.12, 0.12, 0.12), (-0.12, 0.1, 0.7))])
    o.coll_cyl('pot', 0.15, 0.0, 0.3)
    o.coll_cyl('stem', 0.02, 0.3, 0.45, weight=0.5)
    o.coll_sphere('foliage', 0.22, (0.0, 0.0, 0.75), weight=0.02)
    return o


def office_desk():
    o = Obj('office_desk', 'Office desk with a three-drawer pedestal', (0.8, 1.6, 0.75), 45.0)
    o.visual('top', OAK, box_between((-0.4, -0.8, 0.72), (0.4, 0.8, 0.75)))
    o.visual('body', LIGHT_GREY, [box_between((-0.38, -0.8, 0), (0.38, -0.77, 0.72)),
                                  box_between((-0.38, 0.35, 0), (0.365, 0.8, 0.72)),
                                  box_between((-0.38, -0.77, 0.3), (-0.36, 0.35, 0.72))])
    fronts, handles = [], []
    for z0, z1 in ((0.02, 0.3), (0.31, 0.5), (0.51, 0.7)):
        fronts.append(box_between((0.365, 0.36, z0), (0.38, 0.79, z1)))
        handles.append(box_between((0.38, 0.505, z1 - 0.05), (0.395, 0.645, z1 - 0.035)))
    o.visual('drawers', OAK, fronts)
    o.visual('handles', METAL, handles)
    o.coll_box('top', (-0.4, -0.8, 0.72), (0.4, 0.8, 0.75))
    o.coll_box('side', (-0.38, -0.8, 0), (0.38, -0.77, 0.72))
    o.coll_box('pedestal', (-0.38, 0.35, 0), (0.395, 0.8, 0.72))
    o.coll_box('modesty', (-0.38, -0.77, 0.3), (-0.36, 0.35, 0.72))
    return o


def cabinet():
    o = Obj('cabinet', 'Steel filing cabinet with four drawers', (0.62, 0.47, 1.32), 50.0)
    o.visual('body', LIGHT_GREY, [box_between((-0.31, -0.235, 0), (0.29, 0.235, 1.32))])
    fronts, handles = [], []
    for k in range(4):
        z0 = 0.03 + k * 0.3225
        fronts.append(box_between((0.29, -0.225, z0), (0.3, 0.225, z0 + 0.31)))
        handles.append(box_between((0.3, -0.07, z0 + 0.22), (0.31, 0.07, z0 + 0.24)))
        handles.append(box_between((0.3, -0.04, z0 + 0.26), (0.303, 0.04, z0 + 0.29)))
    o.visual('drawers', METAL, fronts)
    o.visual('handles', DARK_GREY, handles)
    o.coll_box('body', (-0.31, -0.235, 0), (0.31, 0.235, 1.32))
    return o


def fire_extinguisher():
    o = Obj('fire_extinguisher', 'Fire extinguisher, 6 kg powder', (0.184, 0.16, 0.545), 9.0)
    o.visual('body', RED, lathe([(0.0, 0.0), (0.075, 0.0), (0.08, 0.01), (0.08, 0.42),
                                 (0.06, 0.46), (0.02, 0.48), (0.0, 0.48)], 24))
    o.visual('valve', BLACK, [cylinder(0.018, 0.05, (0.0, 0.0, 0.505), segments=12),
                              box_between((-0.03, -0.012, 0.53), (0.09, 0.012, 0.545)),
                              box_between((-0.05, -0.01, 0.51), (0.0, 0.01, 0.52)),
                              cylinder(0.01, 0.33, (0.09, 0.0, 0.365), segments=12),
                              cylinder(0.014, 0.05, (0.09, 0.0, 0.175), segments=12)])
    o.coll_cyl('body', 0.08, 0.0, 0.48)
    return o


def bench():
    o = Obj('bench', 'Park bench: wooden slats on cast-iron sides', (0.6, 1.5, 0.789), 30.0)
    iron = []
    for y in (-0.68, 0.68):
        y0, y1 = y - 0.02, y + 0.02
        iron += [box_between((0.2, y0, 0), (0.25, y1, 0.42)),
                 box_between((-0.25, y0, 0), (-0.2, y1, 0.42)),
                 box_between((-0.25, y0, 0.38), (0.25, y1, 0.42)),
                 box_between((0.2, y0, 0.42), (0.24, y1, 0.62)),
                 box_between((-0.3, y0, 0.62), (0.3, y1, 0.66)),
                 box((0.04, 0.04, 0.4), (-0.215, y, 0.59), (0.0, -0.25, 0.0))]
    o.visual('sides', BLACK, iron)
    slats = [box_between((x - 0.04, -0.75, 0.42), (x + 0.04, 0.75, 0.45))
             for x in (-0.15, -0.05, 0.05, 0.15)]
    slats += [box((0.025, 1.5, 0.08), (-0.185 - 0.04 * k, 0.0, 0.51 + 0.1 * k),
                  (0.0, -0.25, 0.0)) for k in range(3)]
    o.visual('slats', WOOD, slats)
    o.coll_box('seat', (-0.25, -0.75, 0.38), (0.25, 0.75, 0.45))
    o.coll_box('side_right', (-0.25, -0.7, 0), (0.25, -0.66, 0.38), weight=4.0)
    o.coll_box('side_left', (-0.25, 0.66, 0), (0.25, 0.7, 0.38), weight=4.0)
    o.collisions.append(('back', 'box', (0.03, 1.5, 0.3), (-0.225, 0.0, 0.61),
                         (0.0, -0.25, 0.0), 1.0))
    return o


OBJECTS = [table, chair, bookshelf, sofa, door_frame, trash_bin, traffic_cone, barrel,
           box_pallet, potted_plant, office_desk, cabinet, fire_extinguisher, bench]


# ------------------------------------------------------------------------- rooms

WALL_T = 0.1


def wall_runs(x0, y0, x1, y1, gaps=()):
    """Axis-aligned wall centre line from (x0, y0) to (x1, y1) minus doorway gaps
    [(centre along the line, width)]: the list of remaining (x0, y0, x1, y1) pieces."""
    horizontal = y0 == y1
    a, b = (x0, x1) if horizontal else (y0, y1)
    a, b = min(a, b), max(a, b)
    pieces, start = [], a
    for c, w in sorted(gaps):
        pieces.append((start, c - w / 2))
        start = c + w / 2
    pieces.append((start, b))
    out = []
    for p, q in pieces:
        if q - p > 1e-9:
            out.append((p, y0, q, y0) if horizontal else (x0, p, x0, q))
    return out


class Room:
    def __init__(self, name, title, height, color, walls, doorways=()):
        self.name, self.title, self.height, self.color = name, title, height, color
        self.walls = walls          # centre lines (x0, y0, x1, y1)
        self.doorways = list(doorways)   # (name, (x, y), 'x'|'y' passage direction, width)

    def boxes(self):
        """(name, (sx, sy, sz), (cx, cy, cz)) for every wall, ends extended by half the
        thickness so that corners close."""
        out = []
        for i, (x0, y0, x1, y1) in enumerate(self.walls):
            length = abs(x1 - x0) + abs(y1 - y0) + WALL_T
            size = (length, WALL_T, self.height) if y0 == y1 else (WALL_T, length, self.height)
            out.append(('wall_%d' % i, size, ((x0 + x1) / 2, (y0 + y1) / 2, self.height / 2)))
        return out


def empty_room():
    h = 3.0
    walls = [(-h, -h, h, -h), (h, -h, h, h), (h, h, -h, h), (-h, h, -h, -h)]
    return Room('empty_room', 'Empty room 6 x 6 m inside, walls 1 m high', 1.0, WALL, walls)


OFFICE_DOORWAYS = [
    ('entrance', (-6.0, 3.0), 'x', 1.0),
    ('room_a', (-4.0, 2.0), 'y', 1.0),
    ('room_b', (0.0, 2.0), 'y', 1.0),
    ('room_c', (2.8, 2.0), 'y', 1.0),
    ('room_d', (3.5, 3.0), 'x', 1.0),
    ('a_b', (-2.0, -1.5), 'x', 1.0),
    ('b_c', (2.0, -1.5), 'x', 1.0),
]


def office():
    walls = []
    walls += wall_runs(-6, -4, 6, -4)
    walls += wall_runs(-6, 4, 6, 4)
    walls += wall_runs(-6, -4, -6, 4, gaps=[(3.0, 1.0)])
    walls += wall_runs(6, -4, 6, 4)
    walls += wall_runs(-6, 2, 6, 2, gaps=[(-4.0, 1.0), (0.0, 1.0), (2.8, 1.0)])
    walls += wall_runs(-2, -4, -2, 2, gaps=[(-1.5, 1.0)])
    walls += wall_runs(2, -4, 2, 2, gaps=[(-1.5, 1.0)])
    walls += wall_runs(3.5, 2, 3.5, 4, gaps=[(3.0, 1.0)])
    return Room('office', 'Office floor 12 x 8 m: rooms A, B (around the origin), C, a store '
                'room D and a corridor with an entrance; walls 1 m high', 1.0, WALL, walls,
                OFFICE_DOORWAYS)


# 5 x 5 cells of 1 m; north is the first line. Entrance on the west of the middle row (the
# maze frame's origin is the middle of that opening), exit on the east of the same row.
MAZE = [
    '###########',
    '#.....#...#',
    '#.###.#.#.#',
    '#.#...#.#.#',
    '#.#.###.#.#',
    '..#.....#..',
    '###.#####.#',
    '#...#...#.#',
    '#.###.#.#.#',
    '#.....#...#',
    '###########',
]


def maze_walls(grid=MAZE, cell=1.0):
    n = len(grid)

    def xy(i, j):
        return j / 2 * cell, (n // 2 - i) / 2 * cell

    walls = []
    for i in range(0, n, 2):            # east-west runs on even lines
        j = 0
        while j < n:
            if grid[i][j] == '#':
                k = j
                while k + 1 < n and grid[i][k + 1] == '#':
                    k += 1
                if k > j:
                    walls.append(xy(i, j) + xy(i, k))
                j = k + 1
            else:
                j += 1
    for j in range(0, n, 2):            # north-south runs on even columns
        i = 0
        while i < n:
            if grid[i][j] == '#':
                k = i
                while k + 1 < n and grid[k + 1][j] == '#':
                    k += 1
                if k > i:
                    walls.append(xy(i, j) + xy(k, j))
                i = k + 1
            else:
                i += 1
    return walls


def maze():
    return Room('maze', 'Maze of 5 x 5 cells of 1 m, entrance west and exit east of the middle '
                'row, walls 0.5 m high', 0.5, MAZE_WALL, maze_walls())


ROOMS = [empty_room, office, maze]


# ------------------------------------------------------------------------- writers

def model_config(name, description):
    return ('<?xml version="1.0"?>\n<model>\n  <name>%s</name>\n  <version>1.0</version>\n'
            '  <sdf version="%s">model.sdf</sdf>\n  <author>\n    <name>%s</name>\n'
            '    <email></email>\n  </author>\n  <description>\n    %s\n  </description>\n'
            '</model>\n' % (name, SDF_VERSION, AUTHOR, description))


def material(rgba, indent):
    pad = ' ' * indent
    spec = (0.1, 0.1, 0.1, 1.0)
    return ('%s<material>\n%s  <ambient>%s</ambient>\n%s  <diffuse>%s</diffuse>\n'
            '%s  <specular>%s</specular>\n%s</material>\n'
            % (pad, pad, vec(rgba, 3), pad, vec(rgba, 3), pad, vec(spec, 3), pad))


def geometry_xml(kind, dims, indent, uri=None):
    pad = ' ' * indent
    if kind == 'box':
        inner = '<box><size>%s</size></box>' % vec(dims)
    elif kind == 'cylinder':
        inner = '<cylinder><radius>%s</radius><length>%s</length></cylinder>' % (
            fmt(dims[0]), fmt(dims[1]))
    elif kind == 'sphere':
        inner = '<sphere><radius>%s</radius></sphere>' % fmt(dims[0])
    elif kind == 'mesh':
        inner = '<mesh><uri>%s</uri></mesh>' % uri
    else:
        raise ValueError(kind)
    return '%s<geometry>\n%s  %s\n%s</geometry>\n' % (pad, pad, inner, pad)


def object_sdf(o):
    com, inertia = mg.composite_inertia(o.mass, [c[1:] for c in o.collisions])
    lines = ['<?xml version="1.0"?>\n<sdf version="%s">\n' % SDF_VERSION,
             '  <model name="%s">\n' % o.name,
             '    <static>%s</static>\n' % ('true' if o.static else 'false'),
             '    <link name="link">\n',
             '      <inertial>\n        <pose>%s 0 0 0</pose>\n        <mass>%s</mass>\n'
             % (vec(com, 4), fmt(o.mass)),
             '        <inertia>\n']
    for tag, (a, b) in (('ixx', (0, 0)), ('ixy', (0, 1)), ('ixz', (0, 2)), ('iyy', (1, 1)),
                        ('iyz', (1, 2)), ('izz', (2, 2))):
        lines.append('          <%s>%s</%s>\n' % (tag, fmt(inertia[a, b], 5), tag))
    lines.append('        </inertia>\n      </inertial>\n')
    for name, kind, dims, xyz, rpy, _ in o.collisions:
        lines.append('      <collision name="%s">\n        <pose>%s %s</pose>\n'
                     % (name, vec(xyz), vec(rpy)))
        lines.append(geometry_xml(kind, dims, 8))
        lines.append('      </collision>\n')
    for name, rgba, _ in o.visuals:
        lines.append('      <visual name="%s">\n' % name)
        lines.append(geometry_xml('mesh', None, 8, o.mesh_uri(name)))
        lines.append(material(rgba, 8))
        lines.append('      </visual>\n')
    lines.append('    </link>\n  </model>\n</sdf>\n')
    return ''.join(lines)


def room_sdf(room):
    lines = ['<?xml version="1.0"?>\n<sdf version="%s">\n' % SDF_VERSION,
             '  <model name="%s">\n    <static>true</static>\n    <link name="walls">\n'
             % room.name]
    for name, size, xyz in room.boxes():
        for tag in ('collision', 'visual'):
            lines.append('      <%s name="%s">\n        <pose>%s 0 0 0</pose>\n'
                         % (tag, name, vec(xyz)))
            lines.append(geometry_xml('box', size, 8))
            if tag == 'visual':
                lines.append(material(room.color, 8))
            lines.append('      </%s>\n' % tag)
    lines.append('    </link>\n  </model>\n</sdf>\n')
    return ''.join(lines)


GROUND_PLANE_SDF = '''<?xml version="1.0"?>
<sdf version="1.6">
  <model name="ground_plane">
    <static>true</static>
    <link name="link">
      <collision name="collision">
        <geometry>
          <plane><normal>0 0 1</normal><size>100 100</size></plane>
        </geometry>
        <surface>
          <friction>
            <ode><mu>100</mu><mu2>50</mu2></ode>
          </friction>
        </surface>
      </collision>
      <visual name="visual">
        <cast_shadows>false</cast_shadows>
        <geometry>
          <plane><normal>0 0 1</normal><size>100 100</size></plane>
        </geometry>
        <material>
          <ambient>0.5 0.5 0.5 1</ambient>
          <diffuse>0.5 0.5 0.5 1</diffuse>
          <specular>0.1 0.1 0.1 1</specular>
        </material>
      </visual>
    </link>
  </model>
</sdf>
'''

SUN_SDF = '''<?xml version="1.0"?>
<sdf version="1.6">
  <light type="directional" name="sun">
    <cast_shadows>true</cast_shadows>
    <pose>0 0 10 0 0 0</pose>
    <diffuse>0.8 0.8 0.8 1</diffuse>
    <specular>0.2 0.2 0.2 1</specular>
    <attenuation>
      <range>1000</range>
      <constant>0.9</constant>
      <linear>0.01</linear>
      <quadratic>0.001</quadratic>
    </attenuation>
    <direction>-0.5 0.1 -0.9</direction>
  </light>
</sdf>
'''


def objects():
    return [f() for f in OBJECTS]


def rooms():
    return [f() for f in ROOMS]


def write(path, data):
    os.makedirs(os.path.dirname(path), exist_ok=True)
    mode = 'wb' if isinstance(data, bytes) else 'w'
    with open(path, mode) as f:
        f.write(data)


def readme(objs, rms):
    lines = [
        '# ode_sim model library\n\n',
        'Models of our own making, in the Gazebo layout (`NAME/model.config`, `NAME/model.sdf`,\n',
        'SDF %s, `NAME/meshes/*.stl`), found by `model://NAME` in worlds. Everything here is\n'
        % SDF_VERSION,
        'generated by `scripts/make_models.py`: do not edit by hand, change the script and run\n\n',
        '    python3 scripts/make_models.py            # from catkin_ws/src/sim/ode_sim\n\n',
        'The output is deterministic (regenerating gives byte-identical files; the tests check\n',
        'it). Each object\'s origin is the centre of its footprint on the floor, its front faces\n',
        '+x. Visuals are binary STL meshes, one per colour (`<material>` ambient/diffuse);\n',
        'collisions are a few boxes/cylinders/spheres approximating the shape (cheaper contacts\n',
        'and ray casts), which also give the inertia (mass spread by volume).\n\n',
        '## Environment\n\n',
        '| model | description |\n|---|---|\n',
        '| `ground_plane` | static plane, friction mu 100 / mu2 50, grey 100 x 100 m visual |\n',
        '| `sun` | directional light at 0 0 10, direction -0.5 0.1 -0.9, casts shadows |\n\n',
        '## Objects\n\n',
        '| model | size x × y × z (m) | mass (kg) | triangles | description |\n',
        '|---|---|---|---|---|\n']
    for o in objs:
        tris = sum(len(p) for _, _, p in o.visuals)
        lines.append('| `%s` | %s | %s%s | %d | %s |\n' % (
            o.name, ' × '.join(fmt(s, 3) for s in o.size), fmt(o.mass),
            ' (static)' if o.static else '', tris, o.title))
    lines += ['\n## Rooms (static, walls %s m thick, box collisions)\n\n' % fmt(WALL_T),
              '| model | walls | description |\n|---|---|---|\n']
    for r in rms:
        lines.append('| `%s` | %d | %s |\n' % (r.name, len(r.walls), r.title))
    lines += ['\nOffice doorways (centre x y in the model frame, width):\n\n']
    for name, (x, y), axis, w in OFFICE_DOORWAYS:
        lines.append('- `%s`: %s %s, %s m, passage along %s\n' % (name, fmt(x), fmt(y), fmt(w),
                                                                   axis))
    lines += ['\nThe maze layout (`#` wall, north up, entrance and exit on the middle row):\n\n']
    lines += ['    %s\n' % row for row in MAZE]
    lines += ['\nThe maze frame\'s origin is the middle of the entrance opening; cells span x 0..5,\n',
              'y -2.5..2.5.\n\n',
              '## Worlds (`../worlds/`)\n\n',
              '| world | contents |\n|---|---|\n',
              '| `empty.world` | sun + ground_plane, Gazebo\'s default ODE physics (as Gazebo\'s) |\n',
              '| `empty_room.world` | `empty_room` centred on the origin |\n',
              '| `office.world` | `office` + 13 pieces of furniture; the origin is in room B, '
              '1 m clear |\n',
              '| `maze.world` | `maze` at x = 1: the entrance 1 m ahead of the origin, the exit at '
              'x = 6 |\n',
              '| `objects.world` | 5 objects 2-5 m ahead (+x) of the origin, for camera/lidar '
              'demos |\n',
              '| `textbook.world` | practical work 4 (SDF 1.4): scene, quick solver 150 iters, '
              'SOR 1.4, CFM 1e-5 |\n']
    return ''.join(lines)


def generate(out):
    objs, rms = objects(), rooms()
    write(os.path.join(out, 'ground_plane', 'model.config'),
          model_config('ground_plane', 'A large static ground plane (100 x 100 m).'))
    write(os.path.join(out, 'ground_plane', 'model.sdf'), GROUND_PLANE_SDF)
    write(os.path.join(out, 'sun', 'model.config'),
          model_config('sun', 'A directional light, as the sun.'))
    write(os.path.join(out, 'sun', 'model.sdf'), SUN_SDF)
    for o in objs:
        d = os.path.join(out, o.name)
        write(os.path.join(d, 'model.config'), model_config(o.name, '%s; %s m; %s kg.' % (
            o.title, ' x '.join(fmt(s, 3) for s in o.size), fmt(o.mass))))
        write(os.path.join(d, 'model.sdf'), object_sdf(o))
        for name, _, part in o.visuals:
            write(os.path.join(d, 'meshes', name + '.stl'),
                  mg.stl_bytes(part, '%s/%s' % (o.name, name)))
    for r in rms:
        d = os.path.join(out, r.name)
        write(os.path.join(d, 'model.config'), model_config(r.name, r.title + '.'))
        write(os.path.join(d, 'model.sdf'), room_sdf(r))
    write(os.path.join(out, 'README.md'), readme(objs, rms))
    return objs, rms


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    ap.add_argument('--out', default=os.path.join(PKG, 'models'),
                    help='directory to write the models into (default: the package\'s models/)')
    args = ap.parse_args(argv)
    objs, rms = generate(args.out)
    print('wrote %d objects and %d rooms into %s' % (len(objs), len(rms), args.out))


if __name__ == '__main__':
    main()
