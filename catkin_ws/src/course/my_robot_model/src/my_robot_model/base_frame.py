"""The base frame mesh of the diff-drive robot: a tray with chamfered corners.

One closed solid: an octagonal (chamfered rectangle) prism with a pocket cut from the top,
leaving walls of `wall` thickness and a floor of `floor` thickness. Coordinates are metres in
base_link's frame (centred, z from -height/2 to +height/2), so the URDF uses scale 1.0.
"""
import math

import numpy as np

HEADER = b'my_robot_model base_frame.stl (scripts/make_base_frame_stl.py)'

#: default dimensions, the same as the properties of urdf/diff_robot_model.urdf.xacro (m)
LENGTH, WIDTH, HEIGHT = 0.30, 0.20, 0.05
CHAMFER, WALL, FLOOR = 0.04, 0.012, 0.008


def octagon(length, width, chamfer):
    """Counter-clockwise (seen from +z) corners of a centred rectangle with 45-degree chamfers."""
    hx, hy, c = length / 2.0, width / 2.0, chamfer
    return [(hx, -hy + c), (hx, hy - c), (hx - c, hy), (-hx + c, hy),
            (-hx, hy - c), (-hx, -hy + c), (-hx + c, -hy), (hx - c, -hy)]


def _cap(poly, z, up):
    """Fan triangles of a convex polygon at height z, facing +z when `up`."""
    tris = []
    for i in range(1, len(poly) - 1):
        a, b, c = (poly[0] + (z,)), (poly[i] + (z,)), (poly[i + 1] + (z,))
        tris.append((a, b, c) if up else (a, c, b))
    return tris


def _walls(poly, z0, z1, outward):
    """Side quads of a CCW polygon between z0 and z1, normals pointing out of the polygon
    when `outward`, into it otherwise."""
    tris = []
    n = len(poly)
    for i in range(n):
        a, b = poly[i], poly[(i + 1) % n]
        a0, b0, a1, b1 = a + (z0,), b + (z0,), a + (z1,), b + (z1,)
        tris += [(a0, b0, b1), (a0, b1, a1)] if outward else [(a0, b1, b0), (a0, a1, b1)]
    return tris


def _ring(outer, inner, z):
    """Top face between two CCW polygons with matching corners, facing +z."""
    tris = []
    n = len(outer)
    for i in range(n):
        j = (i + 1) % n
        o0, o1, i0, i1 = outer[i] + (z,), outer[j] + (z,), inner[i] + (z,), inner[j] + (z,)
        tris += [(o0, o1, i1), (o0, i1, i0)]
    return tris


def tray_triangles(length=LENGTH, width=WIDTH, height=HEIGHT, chamfer=CHAMFER, wall=WALL,
                   floor=FLOOR):
    """Triangles (each three (x, y, z) vertices, counter-clockwise seen from outside)."""
    for name, value in (('length', length), ('width', width), ('height', height),
                        ('chamfer', chamfer), ('wall', wall), ('floor', floor)):
        if not value > 0:
            raise ValueError('base frame: %s must be > 0, got %r' % (name, value))
    if 2 * wall >= min(length, width) or floor >= height:
        raise ValueError('base frame: walls (%g) or floor (%g) leave no pocket in %gx%gx%g'
                         % (wall, floor, length, width, height))
    inner_chamfer = chamfer - wall * (2.0 - math.sqrt(2.0))   # a uniform inward offset
    if not 0 < inner_chamfer < min(length, width) / 2.0 - wall:
        raise ValueError('base frame: chamfer %g does not fit walls of %g' % (chamfer, wall))
    outer = octagon(length, width, chamfer)
    inner = octagon(length - 2 * wall, width - 2 * wall, inner_chamfer)
    z0, z1, zf = -height / 2.0, height / 2.0, -height / 2.0 + floor
    return (_cap(outer, z0, up=False) + _walls(outer, z0, z1, outward=True)
            + _ring(outer, inner, z1) + _walls(inner, zf, z1, outward=False)
            + _cap(inner, zf, up=True))


def tray_mesh(**dims):
    """A numpy-stl Mesh of the tray (normals computed)."""
    from stl import mesh
    tris = np.array(tray_triangles(**dims), dtype=np.float32)
    m = mesh.Mesh(np.zeros(len(tris), dtype=mesh.Mesh.dtype))
    m.vectors[:] = tris
    m.update_normals()
    return m


def stl_bytes(**dims):
    """Binary STL of the tray: a fixed 80-byte header (numpy-stl's own writer puts the date
    there, so the same dimensions would not give the same bytes), the triangle count and
    numpy-stl's record array of normals, vertices and attribute words."""
    import struct
    m = tray_mesh(**dims)
    return HEADER.ljust(80, b' ') + struct.pack('<I', len(m.data)) + m.data.tobytes()


def polygon_area(poly):
    """Shoelace area of a simple polygon."""
    return 0.5 * abs(sum(x0 * y1 - x1 * y0 for (x0, y0), (x1, y1) in zip(poly, poly[1:] + poly[:1])))
