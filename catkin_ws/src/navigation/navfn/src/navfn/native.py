"""The compiled potential propagation (src_cpp/propagate.cpp) through ctypes."""
import ctypes
import os

import numpy as np

_LIB_NAME = 'libnavfn_native.so'
_lib = None


def _find():
    dirs = []
    for prefix in os.environ.get('CMAKE_PREFIX_PATH', '').split(':'):
        if prefix:
            dirs += [os.path.join(prefix, 'lib'), os.path.join(prefix, 'lib', 'navfn')]
    dirs += os.environ.get('LD_LIBRARY_PATH', '').split(':')
    for d in dirs:
        p = os.path.join(d, _LIB_NAME)
        if d and os.path.exists(p):
            return p
    raise ImportError('%s not found in the CMAKE_PREFIX_PATH / LD_LIBRARY_PATH lib '
                      'directories: build the workspace and source devel/setup.bash' % _LIB_NAME)


def lib():
    global _lib
    if _lib is None:
        _lib = ctypes.CDLL(_find())
        _lib.navfn_propagate.restype = None
        _lib.navfn_propagate.argtypes = [
            ctypes.c_void_p, ctypes.c_int, ctypes.c_int, ctypes.c_int, ctypes.c_int,
            ctypes.c_int, ctypes.c_double, ctypes.c_int, ctypes.c_int, ctypes.c_void_p]
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
