"""ctypes binding of the C++ hot loops (libgmapping_grid_core.so, include/gmapping/grid_core.h)."""
import ctypes

import numpy as np
from nav_core import native

LIBRARY = 'libgmapping_grid_core.so'

_d = ctypes.POINTER(ctypes.c_double)


# GmCell: one grid cell, 12 bytes (include/gmapping/grid_core.h)
CELL = np.dtype([('hits', '<u2'), ('visits', '<u2'), ('mx', '<f4'), ('my', '<f4')])
assert CELL.itemsize == 12


class GmGrids(ctypes.Structure):
    _fields_ = [('n', ctypes.c_int), ('h', ctypes.c_int), ('w', ctypes.c_int),
                ('ox', ctypes.c_double), ('oy', ctypes.c_double), ('delta', ctypes.c_double),
                ('cells', ctypes.POINTER(ctypes.c_void_p))]


class GmScan(ctypes.Structure):
    _fields_ = [('beams', ctypes.c_int), ('ranges', _d), ('angles', _d), ('cos_a', _d), ('sin_a', _d),
                ('max_range', ctypes.c_double), ('max_urange', ctypes.c_double)]


class GmMatcherParams(ctypes.Structure):
    _fields_ = [('sigma', ctypes.c_double), ('kernel', ctypes.c_int), ('lsigma', ctypes.c_double),
                ('lskip', ctypes.c_int), ('lstep', ctypes.c_double), ('astep', ctypes.c_double),
                ('iterations', ctypes.c_int), ('fullness', ctypes.c_double),
                ('null_likelihood', ctypes.c_double), ('minimum_score', ctypes.c_double)]


def _load():
    g, s, m = ctypes.POINTER(GmGrids), ctypes.POINTER(GmScan), ctypes.POINTER(GmMatcherParams)
    return native.load_library(LIBRARY, 'gmapping', {
        'gm_integrate': (ctypes.c_int, [g, _d, s]),
        'gm_score': (ctypes.c_double, [g, ctypes.c_int, _d, s, m]),
        'gm_optimize': (None, [g, _d, s, m, _d, _d, _d]),
        'gm_likelihood_and_score': (None, [g, ctypes.c_int, _d, s, m, _d, _d]),
    })


_lib = _load()


def _dptr(a):
    return a.ctypes.data_as(_d)


class _Field(object):
    """grids.hits[i] / grids.visits[i] / grids.mx[i] / grids.my[i]: that field of particle i's
    cells, an (h, w) view."""

    def __init__(self, grids, name):
        self.grids, self.name = grids, name

    def __getitem__(self, i):
        return self.grids.cells[i][self.name]

    def __len__(self):
        return len(self.grids.cells)


class Grids(object):
    """n particle grids, each its own C-contiguous (h, w) array of CELL (hits, visits: uint16
    counts; mx, my: float32 mean endpoint offsets); origin (x, y) of cell (0, 0); delta [m].
    Particles may share an array only between a select() and the next write (see select)."""

    def __init__(self, n, h, w, origin, delta, cells=None):
        self.cells = [np.zeros((h, w), dtype=CELL) for _ in range(n)] if cells is None else cells
        self.origin = (float(origin[0]), float(origin[1]))
        self.delta = float(delta)
        self._c = None

    @property
    def shape(self):
        h, w = self.cells[0].shape
        return (len(self.cells), h, w)

    hits = property(lambda self: _Field(self, 'hits'))
    visits = property(lambda self: _Field(self, 'visits'))
    mx = property(lambda self: _Field(self, 'mx'))
    my = property(lambda self: _Field(self, 'my'))

    def select(self, idx):
        """The grids of particles idx (resampling). A particle drawn once keeps its array (no
        copy); each further draw of it gets a copy. The old Grids must not be used afterwards."""
        taken = set()
        cells = []
        for j in idx:
            j = int(j)
            cells.append(self.cells[j].copy() if j in taken else self.cells[j])
            taken.add(j)
        return Grids(len(cells), 0, 0, self.origin, self.delta, cells=cells)

    def c(self):
        if self._c is None:
            n, h, w = self.shape
            self._ptrs = (ctypes.c_void_p * n)(*[a.ctypes.data for a in self.cells])
            self._c = GmGrids(n, h, w, self.origin[0], self.origin[1], self.delta,
                              ctypes.cast(self._ptrs, ctypes.POINTER(ctypes.c_void_p)))
        return self._c


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
