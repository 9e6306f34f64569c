"""The model library's objects (scripts/make_models.py writes them): each function builds one
Obj, a real-world object whose visuals are meshes (one per colour) and whose collisions are a
few primitives that also give its inertia. Every object's origin is at the centre of its
footprint on the floor (z = 0 at its bottom), its front faces +x. Sizes in metres, masses in
kg."""
import math

from ode_sim.description.meshgen import box, box_between, combine, cylinder, ellipsoid, lathe, ring  # noqa

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
        self.collisions.append((name, 'box', tuple(b - a for a, b in zip(lo, hi)),
                                tuple((a + b) / 2 for a, b in zip(lo, hi)), (0.0, 0.0, 0.0),
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
    legs = [box_between((sx * 0.56 - 0.03, sy * 0.36 - 0.03, 0),
                        (sx * 0.56 + 0.03, sy * 0.36 + 0.03, 0.71))
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


def objects():
    return [f() for f in OBJECTS]
