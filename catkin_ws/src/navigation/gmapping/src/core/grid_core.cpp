// Hot loops of slam_gmapping (see include/gmapping/grid_core.h). Algorithm after openslam
// gmapping's ScanMatcher::registerScan / score / likelihoodAndScore / optimize, written anew:
// a cell's correspondence point is the mean of the endpoints registered in it.
#include "gmapping/grid_core.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <vector>
#ifdef __SSE2__
#include <emmintrin.h>
#endif

namespace {

// One particle's grid.
struct Grid {
  const GmCell* cells;
  int w, h;
  double ox, oy, delta;
  Grid(const GmGrids* g, int i)
      : cells(g->cells[i]), w(g->w), h(g->h), ox(g->ox), oy(g->oy), delta(g->delta) {}
};

// Added to a full / not full cell's distance or coordinate: x + 0.0 is x, x + inf is inf.
const double kNotFull[2] = {HUGE_VAL, 0.0};

inline int cellOf(double v, double o, double d) {
  return static_cast<int>(std::floor((v - o) / d));
}

// cellOf without the division where that cannot change the result: (v - o) * (1 / d) is within a
// few ulps (< 1e-12 cells on any grid that fits in memory) of the quotient, so both have the same
// floor unless the product is that close to a cell border; there the quotient decides.
inline int cellOfFast(double v, double o, double d, double inv_d) {
  const double t = (v - o) * inv_d;
  const double f = std::floor(t);
  const double frac = t - f;
  if (frac > 1e-9 && frac < 1.0 - 1e-9) return static_cast<int>(f);
  return cellOf(v, o, d);
}

// Cells the matcher's field reaches beyond the endpoints of the unmatched pose (the hill climbing
// moves a pose by a few centimetres and turns it by a few hundredths of a radian).
constexpr int kFieldMargin = 8;

inline void bump(uint16_t& c) {
  if (c < 65535) ++c;
}

// Best squared distance from the endpoint to the mean point of a full cell (hits / visits above
// the fullness threshold; unknown and outside cells are not full) in the kernel window around
// it, or -1 when none. (gmapping also tests a "free" partner cell, but computes its offset with
// world2map() of a relative vector, which lands far outside the scan's area, so the test always
// passes there; it is left out here.) The window is clipped to the grid once and walked row by
// row without branches on the cells (whether a cell is full is unpredictable): every cell's
// distance is computed and a cell that is not full counts as infinitely far. The minimum does not
// depend on the order, so the result is the same as testing cell by cell.
inline double bestMu2(const Grid& g, double hx, double hy, const GmMatcherParams* p) {
  const int ihx = cellOf(hx, g.ox, g.delta), ihy = cellOf(hy, g.oy, g.delta);
  const int x0 = std::max(ihx - p->kernel, 0), x1 = std::min(ihx + p->kernel, g.w - 1);
  const int y0 = std::max(ihy - p->kernel, 0), y1 = std::min(ihy + p->kernel, g.h - 1);
  const double threshold = p->fullness;
  const double inf = HUGE_VAL;
  double best = inf;
  for (int cy = y0; cy <= y1; ++cy) {
    const GmCell* row = g.cells + static_cast<long>(cy) * g.w;
    const double by = g.oy + cy * g.delta;
    for (int cx = x0; cx <= x1; ++cx) {
      const GmCell& c = row[cx];
      // hits <= visits, so an unknown cell (visits 0) is not full either
      const bool full = static_cast<double>(c.hits) > threshold * static_cast<double>(c.visits);
      const double mx = g.ox + cx * g.delta + c.mx - hx, my = by + c.my - hy;
      const double mu2 = mx * mx + my * my;
      const double d = mu2 + kNotFull[full];  // a table, not a branch
      best = d < best ? d : best;
    }
  }
  return best < inf ? best : -1.0;
}

template <typename F>
inline void forEachBeam(const double* pose, const GmScan* scan, const GmMatcherParams* p, F f) {
  const double ct = std::cos(pose[2]), st = std::sin(pose[2]);
  for (int b = 0; b < scan->beams; b += p->lskip + 1) {
    double r = scan->ranges[b];
    if (!(r > 0.0) || r > scan->max_urange || std::isnan(r)) continue;
    double c = ct * scan->cos_a[b] - st * scan->sin_a[b];
    double s = st * scan->cos_a[b] + ct * scan->sin_a[b];
    f(pose[0] + r * c, pose[1] + r * s);
  }
}

// The minimum squared distance from (hx, hy) to the 3 x 3 points (x, y) at rows[0..5],
// rows[stride..], rows[2 stride..] (kernelSize 1, the default), or -1 if all are infinitely far.
// With SSE2 two cells at a time: the same IEEE operations per lane, so the same result.
inline double window3(const double* rows, long stride, double hx, double hy) {
#ifdef __SSE2__
  const __m128d h = _mm_set_pd(hy, hx);
  __m128d best = _mm_set1_pd(HUGE_VAL);
  const double* row = rows;
  for (int r = 0; r < 3; ++r, row += stride) {
    const __m128d a = _mm_sub_pd(_mm_loadu_pd(row), h);      // (ax, ay)
    const __m128d b = _mm_sub_pd(_mm_loadu_pd(row + 2), h);  // (bx, by)
    const __m128d a2 = _mm_mul_pd(a, a), b2 = _mm_mul_pd(b, b);
    // (ax^2 + ay^2, bx^2 + by^2)
    const __m128d d = _mm_add_pd(_mm_unpacklo_pd(a2, b2), _mm_unpackhi_pd(a2, b2));
    best = _mm_min_pd(d, best);
  }
  // the third column: rows 0 and 1 together, row 2 alone
  const __m128d c0 = _mm_sub_pd(_mm_loadu_pd(rows + 4), h),
                c1 = _mm_sub_pd(_mm_loadu_pd(rows + stride + 4), h);
  const __m128d c02 = _mm_mul_pd(c0, c0), c12 = _mm_mul_pd(c1, c1);
  best = _mm_min_pd(_mm_add_pd(_mm_unpacklo_pd(c02, c12), _mm_unpackhi_pd(c02, c12)), best);
  const double* c2 = rows + 2 * stride + 4;
  const double ex = c2[0] - hx, ey = c2[1] - hy;
  double out = ex * ex + ey * ey;
  const double lo = _mm_cvtsd_f64(best), hi = _mm_cvtsd_f64(_mm_unpackhi_pd(best, best));
  out = lo < out ? lo : out;
  out = hi < out ? hi : out;
  return out < HUGE_VAL ? out : -1.0;
#else
  double best = HUGE_VAL;
  for (int r = 0; r < 3; ++r, rows += stride) {
    const double ax = rows[0] - hx, ay = rows[1] - hy;
    const double bx = rows[2] - hx, by = rows[3] - hy;
    const double cx = rows[4] - hx, cy = rows[5] - hy;
    const double a = ax * ax + ay * ay, b = bx * bx + by * by, c = cx * cx + cy * cy;
    best = a < best ? a : best;
    best = b < best ? b : best;
    best = c < best ? c : best;
  }
  return best < HUGE_VAL ? best : -1.0;
#endif
}

// bestMu2 straight on the grid.
struct GridLookup {
  const Grid& g;
  const GmMatcherParams* p;
  double mu2(double hx, double hy) const { return bestMu2(g, hx, hy, p); }
};

// The matcher's view of one particle's grid over a box of cells, built once per particle and
// scan and read by every pose the hill climbing tries: per cell the mean endpoint's absolute
// coordinates (ox + cx * delta + mx, oy + cy * delta + my, the same doubles bestMu2 computes), or
// (inf, finite) for a cell that is not full, so that a window is a few loads and multiplications
// with no fullness test. The box is filled in tiles of 8 x 8 cells when a window first reads
// them (a scan's endpoints lie on walls: most of its bounding box is never read). Windows
// reaching outside the box fall back to bestMu2 on the grid; either way the result is bestMu2's,
// bit for bit.
struct FieldLookup {
  static constexpr int kTileBits = 3;
  const Grid& g;
  const GmMatcherParams* p;
  int x0 = 0, y0 = 0, w = 0, h = 0;  // the box in grid cells
  int tw = 0, th = 0;                // the box in tiles
  double* pts = nullptr;             // w * h * 2 doubles
  uint8_t* built = nullptr;          // tw * th flags
  double inv_delta = 1.0 / g.delta;

  // The box around the endpoints of the scan at pose, margin cells wider on every side.
  void fit(const double* pose, const GmScan* scan, int margin) {
    int ax = g.w, ay = g.h, bx = -1, by = -1;
    forEachBeam(pose, scan, p, [&](double hx, double hy) {
      const int cx = cellOf(hx, g.ox, g.delta), cy = cellOf(hy, g.oy, g.delta);
      ax = std::min(ax, cx);
      bx = std::max(bx, cx);
      ay = std::min(ay, cy);
      by = std::max(by, cy);
    });
    w = h = tw = th = 0;
    if (bx < ax || by < ay) return;
    const int m = margin + p->kernel;
    x0 = std::max(ax - m, 0);
    y0 = std::max(ay - m, 0);
    w = std::max(std::min(bx + m, g.w - 1) - x0 + 1, 0);
    h = std::max(std::min(by + m, g.h - 1) - y0 + 1, 0);
    tw = (w + (1 << kTileBits) - 1) >> kTileBits;
    th = (h + (1 << kTileBits) - 1) >> kTileBits;
  }

  // Uses points (w * h * 2 doubles) and flags (tw * th bytes); no tile is filled yet.
  void attach(double* points, uint8_t* flags) {
    pts = points;
    built = flags;
    std::fill(built, built + static_cast<long>(tw) * th, uint8_t(0));
  }

  void fillTile(int tx, int ty) {
    const double threshold = p->fullness;
    const int r0 = ty << kTileBits, r1 = std::min(r0 + (1 << kTileBits), h);
    const int k0 = tx << kTileBits, k1 = std::min(k0 + (1 << kTileBits), w);
    // the tile's rows are far apart in the grid: ask for all of them before reading any
    for (int r = r0; r < r1; ++r) {
      const GmCell* row = g.cells + static_cast<long>(y0 + r) * g.w + x0;
      __builtin_prefetch(row + k0);
      __builtin_prefetch(row + k1 - 1);
    }
    for (int r = r0; r < r1; ++r) {
      const int cy = y0 + r;
      const GmCell* row = g.cells + static_cast<long>(cy) * g.w;
      const double by = g.oy + cy * g.delta;
      double* out = pts + 2L * r * w;
      for (int k = k0; k < k1; ++k) {
        const int cx = x0 + k;
        const GmCell& c = row[cx];
        // x + 0.0 is x, x + inf is inf: a table, not a branch (fullness is unpredictable)
        const bool full = static_cast<double>(c.hits) > threshold * static_cast<double>(c.visits);
        out[2 * k] = (g.ox + cx * g.delta + c.mx) + kNotFull[full];
        out[2 * k + 1] = by + c.my;
      }
    }
    built[ty * tw + tx] = 1;
  }

  // Fills the tiles of the window of cells (fx .. fx + span, fy .. fy + span) of the box.
  inline void need(int fx, int fy, int span) {
    const int tx0 = fx >> kTileBits, tx1 = (fx + span) >> kTileBits;
    const int ty0 = fy >> kTileBits, ty1 = (fy + span) >> kTileBits;
    if (built[ty0 * tw + tx0] & built[ty0 * tw + tx1] & built[ty1 * tw + tx0] &
        built[ty1 * tw + tx1])
      return;
    for (int ty = ty0; ty <= ty1; ++ty)
      for (int tx = tx0; tx <= tx1; ++tx)
        if (!built[ty * tw + tx]) fillTile(tx, ty);
  }

  double mu2(double hx, double hy) {
    const int k = p->kernel;
    const int fx = cellOfFast(hx, g.ox, g.delta, inv_delta) - k - x0;
    const int fy = cellOfFast(hy, g.oy, g.delta, inv_delta) - k - y0;
    if (fx < 0 || fy < 0 || fx + 2 * k >= w || fy + 2 * k >= h) return bestMu2(g, hx, hy, p);
    need(fx, fy, 2 * k);
    const double* cell0 = pts + 2 * (static_cast<long>(fy) * w + fx);
    if (k == 1) return window3(cell0, 2L * w, hx, hy);
    double best = HUGE_VAL;
    for (int r = 0; r <= 2 * k; ++r) {
      const double* cell = cell0 + 2L * r * w;
      for (int c = 0; c <= 2 * k; ++c, cell += 2) {
        const double mx = cell[0] - hx, my = cell[1] - hy;
        const double d = mx * mx + my * my;  // inf for a cell that is not full
        best = d < best ? d : best;
      }
    }
    return best < HUGE_VAL ? best : -1.0;
  }
};

template <typename L>
double score(L& lookup, const double* pose, const GmScan* scan, const GmMatcherParams* p) {
  double s = 0.0;
  forEachBeam(pose, scan, p, [&](double hx, double hy) {
    double mu2 = lookup.mu2(hx, hy);
    if (mu2 >= 0.0) s += std::exp(-mu2 / p->sigma);
  });
  return s;
}

template <typename L>
void likelihoodAndScore(L& lookup, const double* pose, const GmScan* scan, const GmMatcherParams* p,
                        double* likelihood, double* score) {
  double l = 0.0, s = 0.0;
  const double no_hit = p->null_likelihood / p->lsigma;
  forEachBeam(pose, scan, p, [&](double hx, double hy) {
    double mu2 = lookup.mu2(hx, hy);
    if (mu2 >= 0.0) {
      l += -mu2 / p->lsigma;
      s += std::exp(-mu2 / p->sigma);
    } else {
      l += no_hit;
    }
  });
  *likelihood = l;
  *score = s;
}

}  // namespace

extern "C" int gm_integrate(GmGrids* g, const double* poses, const GmScan* scan) {
  int status = 0;
  const long w = g->w;
  for (int i = 0; i < g->n; ++i) {
    GmCell* cells = g->cells[i];
    const double* pose = poses + 3 * i;
    auto inside = [g](int cx, int cy) { return cx >= 0 && cy >= 0 && cx < g->w && cy < g->h; };
    int x0 = cellOf(pose[0], g->ox, g->delta), y0 = cellOf(pose[1], g->oy, g->delta);
    const double ct = std::cos(pose[2]), st = std::sin(pose[2]);
    for (int b = 0; b < scan->beams; ++b) {
      double r = scan->ranges[b];
      if (!(r > 0.0) || r > scan->max_range || std::isnan(r)) continue;
      bool cropped = false;
      if (r > scan->max_urange) {
        r = scan->max_urange;
        cropped = true;
      }
      double ex = pose[0] + r * (ct * scan->cos_a[b] - st * scan->sin_a[b]);
      double ey = pose[1] + r * (st * scan->cos_a[b] + ct * scan->sin_a[b]);
      int x1 = cellOf(ex, g->ox, g->delta), y1 = cellOf(ey, g->oy, g->delta);
      if (!inside(x1, y1) || !inside(x0, y0)) {
        status = -1;
        continue;
      }
      // Bresenham from the laser cell to the endpoint cell: free cells before the endpoint
      int dx = std::abs(x1 - x0), dy = -std::abs(y1 - y0);
      int sx = x0 < x1 ? 1 : -1, sy = y0 < y1 ? 1 : -1, err = dx + dy;
      const long srow = sy * w;
      int cx = x0, cy = y0;
      GmCell* c = cells + y0 * w + x0;
      while (!(cx == x1 && cy == y1)) {
        bump(c->visits);
        int e2 = 2 * err;
        if (e2 >= dy) {
          err += dy;
          cx += sx;
          c += sx;
        }
        if (e2 <= dx) {
          err += dx;
          cy += sy;
          c += srow;
        }
      }
      GmCell& end = cells[y1 * w + x1];
      bump(end.visits);
      if (!cropped && end.hits < 65535) {
        uint16_t n = ++end.hits;
        float fx = static_cast<float>(ex - (g->ox + x1 * g->delta));
        float fy = static_cast<float>(ey - (g->oy + y1 * g->delta));
        end.mx += (fx - end.mx) / n;
        end.my += (fy - end.my) / n;
      }
    }
  }
  return status;
}

extern "C" double gm_score(const GmGrids* g, int i, const double* pose, const GmScan* scan,
                           const GmMatcherParams* p) {
  const Grid grid(g, i);
  GridLookup lookup{grid, p};
  return score(lookup, pose, scan, p);
}

extern "C" void gm_likelihood_and_score(const GmGrids* g, int i, const double* pose,
                                        const GmScan* scan, const GmMatcherParams* p,
                                        double* likelihood, double* score) {
  const Grid grid(g, i);
  GridLookup lookup{grid, p};
  likelihoodAndScore(lookup, pose, scan, p, likelihood, score);
}

extern "C" void gm_optimize(const GmGrids* g, const double* poses, const GmScan* scan,
                            const GmMatcherParams* p, double* out_poses, double* out_scores,
                            double* out_likelihood) {
  // moves in gmapping's order; move m ^ 1 undoes move m
  static const int kMoves[6][3] = {{1, 0, 0}, {-1, 0, 0}, {0, -1, 0},
                                   {0, 1, 0}, {0, 0, 1},  {0, 0, -1}};
  std::vector<double> points;
  std::vector<uint8_t> flags;
  for (int i = 0; i < g->n; ++i) {
    const Grid grid(g, i);
    FieldLookup field{grid, p};
    field.fit(poses + 3 * i, scan, kFieldMargin);
    points.resize(2 * static_cast<size_t>(field.w) * field.h);
    flags.resize(static_cast<size_t>(field.tw) * field.th);
    field.attach(points.data(), flags.data());
    double current[3] = {poses[3 * i], poses[3 * i + 1], poses[3 * i + 2]};
    double current_score = score(field, current, scan, p);
    double best_score = current_score;
    double ldelta = p->lstep, adelta = p->astep;
    int refinement = 0;
    int came_by = -1;  // the move that led to current in the last round (-1: none)
    do {
      if (best_score >= current_score) {  // no move improved: refine
        ++refinement;
        ldelta *= 0.5;
        adelta *= 0.5;
        came_by = -1;
      }
      best_score = current_score;
      double best_local[3] = {current[0], current[1], current[2]};
      int best_move = -1;
      for (int m = 0; m < 6; ++m) {
        // Undoing the last round's move returns to the pose it left, which scored below
        // current_score: it cannot win, so it is not scored again.
        if (came_by >= 0 && m == (came_by ^ 1)) continue;
        double local[3] = {current[0] + kMoves[m][0] * ldelta, current[1] + kMoves[m][1] * ldelta,
                           current[2] + kMoves[m][2] * adelta};
        double local_score = score(field, local, scan, p);
        if (local_score > current_score) {
          current_score = local_score;
          best_local[0] = local[0];
          best_local[1] = local[1];
          best_local[2] = local[2];
          best_move = m;
        }
      }
      came_by = best_move;
      current[0] = best_local[0];
      current[1] = best_local[1];
      current[2] = best_local[2];
    } while (current_score > best_score || refinement < p->iterations);
    const double* accepted = best_score > p->minimum_score ? current : poses + 3 * i;
    out_poses[3 * i] = accepted[0];
    out_poses[3 * i + 1] = accepted[1];
    out_poses[3 * i + 2] = accepted[2];
    out_scores[i] = best_score;
    double l, s;
    likelihoodAndScore(field, accepted, scan, p, &l, &s);
    out_likelihood[i] = l;
  }
}
