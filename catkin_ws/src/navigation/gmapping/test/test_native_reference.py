"""The C++ core (through gmapping.native) against a plain Python transcription of the matcher as
it was before the speed work (cell-by-cell fullness tests on the grid, every one of the six moves
scored in every round): registration, score, likelihood and the hill climbing must agree bit for
bit on small synthetic cases, on the field's fast path (kernelSize 1), its generic window
(kernelSize 2) and its fallback at the grid's edge. Also resampling's sharing of grids."""
import math

import numpy as np
import pytest

import segment_lidar
from gmapping import native
from gmapping.params import SlamParams

# a 3 x 2.4 m room with a pillar, walls off the cell borders
SEGMENTS = np.array([
    (-1.5, -1.2, 1.5, -1.2), (1.5, -1.2, 1.5, 1.2), (1.5, 1.2, -1.5, 1.2), (-1.5, 1.2, -1.5, -1.2),
    (0.3, -0.3, 0.6, -0.3), (0.6, -0.3, 0.6, 0.1), (0.6, 0.1, 0.3, 0.1), (0.3, 0.1, 0.3, -0.3),
], dtype=float) + 0.0137
BEAMS = 90
ANGLES = np.linspace(-math.pi, math.pi, BEAMS, endpoint=False)


def raycast(pose, max_range=8.0):
    return segment_lidar.raycast(SEGMENTS, ANGLES, pose, max_range)


# --- the reference: the previous core, transcribed (doubles as in C, float32 for the means) ---
def cell_of(v, o, d):
    return int(math.floor((v - o) / d))


def ref_integrate(grid, origin, delta, pose, scan):
    """grid: dict of (h, w) arrays hits, visits (int), mx, my (float32); one particle."""
    hits, visits, mx, my = grid['hits'], grid['visits'], grid['mx'], grid['my']
    h, w = hits.shape
    ox, oy = origin
    x0, y0 = cell_of(pose[0], ox, delta), cell_of(pose[1], oy, delta)
    ct, st = math.cos(pose[2]), math.sin(pose[2])
    for b in range(scan.c.beams):
        r = float(scan.ranges[b])
        if not r > 0.0 or r > scan.c.max_range or math.isnan(r):
            continue
        cropped = r > scan.c.max_urange
        if cropped:
            r = scan.c.max_urange
        ex = pose[0] + r * (ct * scan.cos_a[b] - st * scan.sin_a[b])
        ey = pose[1] + r * (st * scan.cos_a[b] + ct * scan.sin_a[b])
        x1, y1 = cell_of(ex, ox, delta), cell_of(ey, oy, delta)
        assert 0 <= x1 < w and 0 <= y1 < h
        dx, dy = abs(x1 - x0), -abs(y1 - y0)
        sx, sy = (1 if x0 < x1 else -1), (1 if y0 < y1 else -1)
        err, cx, cy = dx + dy, x0, y0
        while not (cx == x1 and cy == y1):
            visits[cy, cx] = min(visits[cy, cx] + 1, 65535)
            e2 = 2 * err
            if e2 >= dy:
                err += dy
                cx += sx
            if e2 <= dx:
                err += dx
                cy += sy
        visits[y1, x1] = min(visits[y1, x1] + 1, 65535)
        if not cropped and hits[y1, x1] < 65535:
            hits[y1, x1] += 1
            n = np.float32(hits[y1, x1])
            fx = np.float32(ex - (ox + x1 * delta))
            fy = np.float32(ey - (oy + y1 * delta))
            mx[y1, x1] = np.float32(mx[y1, x1] + np.float32(np.float32(fx - mx[y1, x1]) / n))
            my[y1, x1] = np.float32(my[y1, x1] + np.float32(np.float32(fy - my[y1, x1]) / n))


def ref_best_mu2(grid, origin, delta, hx, hy, p):
    hits, visits, mx, my = grid['hits'], grid['visits'], grid['mx'], grid['my']
    h, w = hits.shape
    ihx, ihy = cell_of(hx, origin[0], delta), cell_of(hy, origin[1], delta)
    best = -1.0
    for xx in range(-p.kernel, p.kernel + 1):
        for yy in range(-p.kernel, p.kernel + 1):
            cx, cy = ihx + xx, ihy + yy
            if not (0 <= cx < w and 0 <= cy < h):
                continue
            v = int(visits[cy, cx])
            if v and float(hits[cy, cx]) > p.fullness * v:
                dx = origin[0] + cx * delta + float(mx[cy, cx]) - hx
                dy = origin[1] + cy * delta + float(my[cy, cx]) - hy
                mu2 = dx * dx + dy * dy
                if best < 0.0 or mu2 < best:
                    best = mu2
    return best


def ref_beams(pose, scan, p):
    ct, st = math.cos(pose[2]), math.sin(pose[2])
    for b in range(0, scan.c.beams, p.lskip + 1):
        r = float(scan.ranges[b])
        if not r > 0.0 or r > scan.c.max_urange or math.isnan(r):
            continue
        c = ct * scan.cos_a[b] - st * scan.sin_a[b]
        s = st * scan.cos_a[b] + ct * scan.sin_a[b]
        yield pose[0] + r * c, pose[1] + r * s


def ref_likelihood_and_score(grid, origin, delta, pose, scan, p):
    l = s = 0.0
    for hx, hy in ref_beams(pose, scan, p):
        mu2 = ref_best_mu2(grid, origin, delta, hx, hy, p)
        if mu2 >= 0.0:
            l += -mu2 / p.lsigma
            s += math.exp(-mu2 / p.sigma)
        else:
            l += p.null_likelihood / p.lsigma
    return l, s


def ref_score(grid, origin, delta, pose, scan, p):
    return ref_likelihood_and_score(grid, origin, delta, pose, scan, p)[1]


def ref_optimize(grid, origin, delta, pose, scan, p):
    moves = [(1, 0, 0), (-1, 0, 0), (0, -1, 0), (0, 1, 0), (0, 0, 1), (0, 0, -1)]
    current = [float(v) for v in pose]
    current_score = ref_score(grid, origin, delta, current, scan, p)
    best_score = current_score
    ldelta, adelta, refinement = p.lstep, p.astep, 0
    while True:
        if best_score >= current_score:
            refinement += 1
            ldelta *= 0.5
            adelta *= 0.5
        best_score = current_score
        best_local = list(current)
        for m in moves:
            local = [current[0] + m[0] * ldelta, current[1] + m[1] * ldelta, current[2] + m[2] * adelta]
            local_score = ref_score(grid, origin, delta, local, scan, p)
            if local_score > current_score:
                current_score = local_score
                best_local = local
        current = best_local
        if not (current_score > best_score or refinement < p.iterations):
            break
    accepted = current if best_score > p.minimum_score else [float(v) for v in pose]
    lik, _ = ref_likelihood_and_score(grid, origin, delta, accepted, scan, p)
    return accepted, best_score, lik


# --- cases -------------------------------------------------------------------------------------
def matcher(kernel=1):
    q = SlamParams(kernelSize=kernel)
    return native.GmMatcherParams(q.sigma, q.kernelSize, q.lsigma, q.lskip, q.lstep, q.astep, q.iterations,
                                  0.1, -0.5, q.minimumScore)


def mapped(poses, shape=(60, 76), origin=(-1.9, -1.5), delta=0.05, noise=0.0):
    """Native grids (one per pose) and reference grids after registering scans from each pose at
    poses and a second scan 3 cm / 0.02 rad away (cells with a few hits and visits)."""
    n = len(poses)
    grids = native.Grids(n, shape[0], shape[1], origin, delta)
    refs = [dict(hits=np.zeros(shape, np.int64), visits=np.zeros(shape, np.int64),
                 mx=np.zeros(shape, np.float32), my=np.zeros(shape, np.float32)) for _ in range(n)]
    rng = np.random.default_rng(5)
    for shift in (np.zeros(3), np.array([0.03, -0.02, 0.02])):
        ps = np.array(poses, float) + shift
        for i in range(n):
            ranges = raycast(ps[i]) + rng.normal(0, noise, BEAMS) if noise else raycast(ps[i])
            scan = native.Scan(ranges, ANGLES, 7.99, 3.0)     # beams beyond 3 m mark free space only
            one = np.ascontiguousarray(ps[i:i + 1])
            sub = native.Grids(1, 0, 0, origin, delta, cells=[grids.cells[i]])
            assert native.integrate(sub, one, scan) == 0
            ref_integrate(refs[i], origin, delta, ps[i], scan)
    return grids, refs


POSES = [(-0.6, -0.4, 0.3), (0.9, 0.5, -1.2), (-1.1, 0.8, 2.5)]


def test_registration_matches_the_reference():
    grids, refs = mapped(POSES, noise=0.01)
    for i, ref in enumerate(refs):
        for name in ('hits', 'visits', 'mx', 'my'):
            assert np.array_equal(grids.cells[i][name], ref[name]), 'particle %d: %s differs' % (i, name)
        assert (ref['hits'] > 0).sum() > 60 and (ref['visits'] > 0).sum() > 800


@pytest.mark.parametrize('kernel', [1, 2])
def test_score_and_likelihood_match_the_reference(kernel):
    grids, refs = mapped(POSES)
    p = matcher(kernel)
    scan = native.Scan(raycast(np.array(POSES[0])), ANGLES, 7.99, 3.0)
    for off in [(0.0, 0.0, 0.0), (0.021, -0.013, 0.011), (-0.04, 0.03, -0.03)]:
        pose = np.array(POSES[0]) + np.array(off)
        l, s = native.likelihood_and_score(grids, 0, pose, scan, p)
        rl, rs = ref_likelihood_and_score(refs[0], grids.origin, grids.delta, pose, scan, p)
        assert (l, s) == (rl, rs)
        assert native.score(grids, 0, pose, scan, p) == rs


@pytest.mark.parametrize('kernel', [1, 2])
def test_hill_climbing_matches_the_reference(kernel):
    """gm_optimize (field, tiles, SSE2 window, no re-scoring of the pose a move came from) gives the
    reference's poses, scores and likelihoods exactly, from odometry errors of a few cm."""
    grids, refs = mapped(POSES)
    p = matcher(kernel)
    truth = np.array(POSES, float)
    start = truth + np.array([[0.04, -0.03, 0.03], [-0.02, 0.05, -0.04], [0.03, 0.02, 0.05]])
    # each particle sees the scan taken at the first particle's true pose
    scan = native.Scan(raycast(truth[0]), ANGLES, 7.99, 3.0)
    poses, scores, lik = native.optimize(grids, start, scan, p)
    for i in range(len(POSES)):
        rp, rs, rl = ref_optimize(refs[i], grids.origin, grids.delta, start[i], scan, p)
        assert poses[i].tolist() == rp, 'particle %d pose %s, reference %s' % (i, poses[i], rp)
        assert scores[i] == rs and lik[i] == rl
    assert np.hypot(*(poses[0, :2] - truth[0, :2])) < np.hypot(*(start[0, :2] - truth[0, :2]))


def test_hill_climbing_at_the_grid_edge_matches_the_reference():
    """A grid that ends just behind the east wall: windows reach past the grid (the field's box is
    clipped there and those windows fall back to the grid)."""
    grids, refs = mapped([POSES[0]], shape=(60, 69), origin=(-1.9, -1.5))
    assert 1.5137 < grids.origin[0] + 69 * 0.05 < 1.5137 + 0.05     # the wall is in the last column
    p = matcher(1)
    start = np.array([POSES[0]]) + np.array([[0.05, 0.01, -0.02]])
    scan = native.Scan(raycast(np.array(POSES[0])), ANGLES, 7.99, 3.0)
    poses, scores, lik = native.optimize(grids, start, scan, p)
    rp, rs, rl = ref_optimize(refs[0], grids.origin, grids.delta, start[0], scan, p)
    assert poses[0].tolist() == rp and scores[0] == rs and lik[0] == rl


def test_select_shares_survivors_and_copies_duplicates():
    grids = native.Grids(4, 5, 6, (0.0, 0.0), 0.05)
    for i in range(4):
        grids.cells[i]['hits'][:] = i
    old = list(grids.cells)
    sel = grids.select(np.array([1, 1, 3, 0]))
    assert [int(c['hits'][0, 0]) for c in sel.cells] == [1, 1, 3, 0]
    assert sel.cells[0] is old[1] and sel.cells[2] is old[3] and sel.cells[3] is old[0]   # no copy
    assert sel.cells[1] is not old[1] and not np.shares_memory(sel.cells[1], sel.cells[0])
    sel.cells[1]['visits'][2, 2] = 7
    assert sel.cells[0]['visits'][2, 2] == 0
    assert sel.shape == (4, 5, 6) and sel.hits[2][0, 0] == 3
