"""The compiled MapGrid wavefront (src_cpp/map_grid.cpp) through ctypes."""
import ctypes
import os

import numpy as np

_LIB_NAME = 'libbase_local_planner_native.so'
_lib = None


def _find():
    dirs = []
    for prefix in os.environ.get('CMAKE_PREFIX_PATH', '').split(':'):
        if prefix:
            dirs += [os.path.join(prefix, 'lib'), os.path.join(prefix, 'lib', 'base_local_planner')]
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
        _lib.blp_wavefront.restype = None
        _lib.blp_wavefront.argtypes = [
            ctypes.c_void_p, ctypes.c_int, ctypes.c_int, ctypes.c_void_p, ctypes.c_int,
            ctypes.c_int64, ctypes.c_int64, ctypes.c_void_p]
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
