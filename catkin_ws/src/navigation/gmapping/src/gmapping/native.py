"""ctypes binding of the C++ hot loops (libgmapping_grid_core.so, include/gmapping/grid_core.h)."""
import ctypes
import os

import numpy as np

LIBRARY = 'libgmapping_grid_core.so'

_d = ctypes.POINTER(ctypes.c_double)
_u16 = ctypes.POINTER(ctypes.c_uint16)
_f32 = ctypes.POINTER(ctypes.c_float)


class GmGrids(ctypes.Structure):
    _fields_ = [('n', ctypes.c_int), ('h', ctypes.c_int), ('w', ctypes.c_int),
                ('ox', ctypes.c_double), ('oy', ctypes.c_double), ('delta', ctypes.c_double),
                ('hits', _u16), ('visits', _u16), ('mx', _f32), ('my', _f32)]


class GmScan(ctypes.Structure):
    _fields_ = [('beams', ctypes.c_int), ('ranges', _d), ('angles', _d), ('cos_a', _d), ('sin_a', _d),
                ('max_range', ctypes.c_double), ('max_urange', ctypes.c_double)]


class GmMatcherParams(ctypes.Structure):
    _fields_ = [('sigma', ctypes.c_double), ('kernel', ctypes.c_int), ('lsigma', ctypes.c_double),
                ('lskip', ctypes.c_int), ('lstep', ctypes.c_double), ('astep', ctypes.c_double),
                ('iterations', ctypes.c_int), ('fullness', ctypes.c_double),
                ('null_likelihood', ctypes.c_double), ('minimum_score', ctypes.c_double)]


def _candidates():
    yield LIBRARY                                   # LD_LIBRARY_PATH (catkin devel/lib, install lib)
    here = os.path.dirname(os.path.abspath(__file__))
    # source tree: catkin_ws/src/navigation/gmapping/src/gmapping -> catkin_ws/devel/lib
    for up in range(3, 7):
        root = os.path.abspath(os.path.join(here, *['..'] * up))
        yield os.path.join(root, 'devel', 'lib', LIBRARY)


def _load():
    errors = []
    for path in _candidates():
        try:
            lib = ctypes.CDLL(path)
            break
        except OSError as e:
            errors.append(str(e))
    else:
        raise ImportError('gmapping: cannot load %s (build the workspace: scripts/build.sh): %s'
                          % (LIBRARY, errors[0]))
    lib.gm_integrate.argtypes = [ctypes.POINTER(GmGrids), _d, ctypes.POINTER(GmScan)]
    lib.gm_integrate.restype = ctypes.c_int
    lib.gm_score.argtypes = [ctypes.POINTER(GmGrids), ctypes.c_int, _d, ctypes.POINTER(GmScan),
                             ctypes.POINTER(GmMatcherParams)]
    lib.gm_score.restype = ctypes.c_double
    lib.gm_optimize.argtypes = [ctypes.POINTER(GmGrids), _d, ctypes.POINTER(GmScan),
                                ctypes.POINTER(GmMatcherParams), _d, _d, _d]
    lib.gm_optimize.restype = None
    lib.gm_likelihood_and_score.argtypes = [ctypes.POINTER(GmGrids), ctypes.c_int, _d, ctypes.POINTER(GmScan),
                                            ctypes.POINTER(GmMatcherParams), _d, _d]
    lib.gm_likelihood_and_score.restype = None
    return lib


_lib = _load()


def _dptr(a):
    return a.ctypes.data_as(_d)


class Grids(object):
    """n particle grids: hits, visits (uint16) and the mean endpoint offsets mx, my (float32),
    each (n, h, w) C-contiguous; origin (x, y) of cell (0, 0); delta [m]."""

    def __init__(self, n, h, w, origin, delta):
        self.hits = np.zeros((n, h, w), dtype=np.uint16)
        self.visits = np.zeros((n, h, w), dtype=np.uint16)
        self.mx = np.zeros((n, h, w), dtype=np.float32)
        self.my = np.zeros((n, h, w), dtype=np.float32)
        self.origin = (float(origin[0]), float(origin[1]))
        self.delta = float(delta)

    @property
    def shape(self):
        return self.hits.shape

    def arrays(self):
        return (self.hits, self.visits, self.mx, self.my)

    def select(self, idx):
        """Copy of the grids of particles idx (resampling)."""
        out = Grids.__new__(Grids)
        out.hits, out.visits, out.mx, out.my = (np.ascontiguousarray(a[idx]) for a in self.arrays())
        out.origin, out.delta = self.origin, self.delta
        return out

    def c(self):
        n, h, w = self.hits.shape
        return GmGrids(n, h, w, self.origin[0], self.origin[1], self.delta, self.hits.ctypes.data_as(_u16),
                       self.visits.ctypes.data_as(_u16), self.mx.ctypes.data_as(_f32), self.my.ctypes.data_as(_f32))


class Scan(object):
    """One laser scan in C layout (keeps the arrays alive while C reads them)."""

    def __init__(self, ranges, angles, max_range, max_urange):
        self.ranges = np.ascontiguousarray(ranges, dtype=np.float64)
        self.angles = np.ascontiguousarray(angles, dtype=np.float64)
        self.cos_a, self.sin_a = np.cos(self.angles), np.sin(self.angles)
        self.c = GmScan(len(self.ranges), _dptr(self.ranges), _dptr(self.angles), _dptr(self.cos_a),
                        _dptr(self.sin_a), max_range, max_urange)


def integrate(grids, poses, scan):
    poses = np.ascontiguousarray(poses, dtype=np.float64)
    g = grids.c()
    return _lib.gm_integrate(ctypes.byref(g), _dptr(poses), ctypes.byref(scan.c))


def score(grids, i, pose, scan, params):
    pose = np.ascontiguousarray(pose, dtype=np.float64)
    g = grids.c()
    return _lib.gm_score(ctypes.byref(g), i, _dptr(pose), ctypes.byref(scan.c), ctypes.byref(params))


def likelihood_and_score(grids, i, pose, scan, params):
    pose = np.ascontiguousarray(pose, dtype=np.float64)
    g = grids.c()
    l, s = ctypes.c_double(), ctypes.c_double()
    _lib.gm_likelihood_and_score(ctypes.byref(g), i, _dptr(pose), ctypes.byref(scan.c), ctypes.byref(params),
                                 ctypes.byref(l), ctypes.byref(s))
    return l.value, s.value


def optimize(grids, poses, scan, params):
    """-> (accepted poses (n, 3), scores (n), log likelihoods (n))."""
    poses = np.ascontiguousarray(poses, dtype=np.float64)
    n = poses.shape[0]
    out = np.empty((n, 3))
    scores, lik = np.empty(n), np.empty(n)
    g = grids.c()
    _lib.gm_optimize(ctypes.byref(g), _dptr(poses), ctypes.byref(scan.c), ctypes.byref(params),
                     _dptr(out), _dptr(scores), _dptr(lik))
    return out, scores, lik
