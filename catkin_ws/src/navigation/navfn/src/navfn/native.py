"""The compiled potential propagation (src_cpp/propagate.cpp) through ctypes."""
import ctypes

import numpy as np
from nav_core import native

_LIB_NAME = 'libnavfn_native.so'
_lib = None


def lib():
    global _lib
    if _lib is None:
        _lib = native.load_library(_LIB_NAME, 'navfn', {'navfn_propagate': (None, [
            ctypes.c_void_p, ctypes.c_int, ctypes.c_int, ctypes.c_int, ctypes.c_int,
            ctypes.c_int, ctypes.c_double, ctypes.c_int, ctypes.c_int, ctypes.c_void_p])})
    return _lib


def propagate(costs, goal, stop, extra, h_scale, start):
    ny, nx = costs.shape
    c = np.ascontiguousarray(costs, dtype=np.float64)
    pot = np.empty((ny, nx), dtype=np.float64)
    g = goal[1] * nx + goal[0]
    s = -1 if stop is None else stop[1] * nx + stop[0]
    lib().navfn_propagate(c.ctypes.data, nx, ny, g, s, int(extra), float(h_scale),
                          int(start[0]), int(start[1]), pot.ctypes.data)
    return pot
