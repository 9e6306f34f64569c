"""The compiled MapGrid wavefront (src_cpp/map_grid.cpp) and footprint costs
(src_cpp/footprint_cost.cpp) through ctypes."""
import ctypes

import numpy as np
from nav_core import native

_LIB_NAME = 'libbase_local_planner_native.so'
_lib = None


def lib():
    global _lib
    if _lib is None:
        _lib = native.load_library(_LIB_NAME, 'base_local_planner', {'blp_wavefront': (None, [
            ctypes.c_void_p, ctypes.c_int, ctypes.c_int, ctypes.c_void_p, ctypes.c_int,
            ctypes.c_int64, ctypes.c_int64, ctypes.c_void_p]),
            'blp_footprint_costs': (None, [
                ctypes.c_void_p, ctypes.c_int, ctypes.c_int, ctypes.c_double, ctypes.c_double,
                ctypes.c_double, ctypes.c_void_p, ctypes.c_int, ctypes.c_void_p, ctypes.c_void_p,
                ctypes.c_void_p, ctypes.c_int, ctypes.c_int, ctypes.c_int, ctypes.c_void_p])})
    return _lib


def wavefront(blocked, seeds, obstacle_value, unreachable):
    """blocked: bool [ny, nx]; seeds: iterable of flat cell indices -> int64 [ny, nx]."""
    ny, nx = blocked.shape
    b = np.ascontiguousarray(blocked, dtype=np.uint8)
    s = np.ascontiguousarray(np.fromiter(seeds, dtype=np.int32))
    out = np.empty((ny, nx), dtype=np.int64)
    lib().blp_wavefront(b.ctypes.data, nx, ny, s.ctypes.data, len(s), int(obstacle_value),
                        int(unreachable), out.ctypes.data)
    return out


def footprint_costs(data, origin_x, origin_y, resolution, footprint, xs, ys, ths, exact=False):
    """data: uint8 [ny, nx] costs; footprint: (K, 2); xs/ys/ths: [N, T] poses -> float [N]:
    -1 where some pose's footprint is illegal, else the highest footprint cost. exact: the
    cells the outline's edges cross, not CostmapModel's lines between the vertices' cells."""
    ny, nx = data.shape
    d = np.ascontiguousarray(data, dtype=np.uint8)
    fp = np.ascontiguousarray(np.asarray(footprint, dtype=float).reshape(-1, 2))
    x = np.ascontiguousarray(xs, dtype=float)
    y = np.ascontiguousarray(ys, dtype=float)
    t = np.ascontiguousarray(ths, dtype=float)
    n, steps = x.shape
    out = np.empty(n, dtype=float)
    lib().blp_footprint_costs(d.ctypes.data, nx, ny, float(origin_x), float(origin_y),
                              float(resolution), fp.ctypes.data, len(fp), x.ctypes.data,
                              y.ctypes.data, t.ctypes.data, n, steps, int(bool(exact)),
                              out.ctypes.data)
    return out
