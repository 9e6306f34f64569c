"""The compiled MapGrid wavefront (src_cpp/map_grid.cpp) through ctypes."""
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
            ctypes.c_int64, ctypes.c_int64, ctypes.c_void_p])})
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
