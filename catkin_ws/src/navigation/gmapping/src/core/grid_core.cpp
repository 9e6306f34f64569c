// Hot loops of slam_gmapping (see include/gmapping/grid_core.h). Algorithm after openslam
// gmapping's ScanMatcher::registerScan / score / likelihoodAndScore / optimize, written anew:
// a cell's correspondence point is the mean of the endpoints registered in it.
#include "gmapping/grid_core.h"

#include <cmath>
#include <cstdlib>

namespace {

struct CellRef {
  const GmGrids* g;
  int i;
  inline bool inside(int cx, int cy) const { return cx >= 0 && cy >= 0 && cx < g->w && cy < g->h; }
  inline long index(int cx, int cy) const { return (static_cast<long>(i) * g->h + cy) * g->w + cx; }
  // fullness hits / visits above threshold (unknown and outside cells are not full)
  inline bool full(int cx, int cy, double threshold) const {
    if (!inside(cx, cy)) return false;
    long k = index(cx, cy);
    uint16_t v = g->visits[k];
    return v && g->hits[k] > threshold * v;
  }
};

inline int cellOf(double v, double o, double d) { return static_cast<int>(std::floor((v - o) / d)); }

inline void bump(uint16_t& c) { if (c < 65535) ++c; }

// Best squared distance from the endpoint to the mean point of an occupied cell in the kernel
// window around it, or -1 when none. (gmapping also tests a "free" partner cell, but computes its
// offset with world2map() of a relative vector, which lands far outside the scan's area, so the
// test always passes there; it is left out here.)
double bestMu2(const CellRef& ref, double hx, double hy, const GmMatcherParams* p) {
  const GmGrids* g = ref.g;
  int ihx = cellOf(hx, g->ox, g->delta), ihy = cellOf(hy, g->oy, g->delta);
  double best = -1.0;
  for (int xx = -p->kernel; xx <= p->kernel; ++xx) {
    for (int yy = -p->kernel; yy <= p->kernel; ++yy) {
      int cx = ihx + xx, cy = ihy + yy;
      if (ref.full(cx, cy, p->fullness)) {
        long k = ref.index(cx, cy);
        double mx = g->ox + cx * g->delta + g->mx[k] - hx, my = g->oy + cy * g->delta + g->my[k] - hy;
        double mu2 = mx * mx + my * my;
        if (best < 0.0 || mu2 < best) best = mu2;
      }
    }
  }
  return best;
}

template <typename F>
void forEachBeam(const double* pose, const GmScan* scan, const GmMatcherParams* p, F f) {
  const double ct = std::cos(pose[2]), st = std::sin(pose[2]);
  for (int b = 0; b < scan->beams; b += p->lskip + 1) {
    double r = scan->ranges[b];
    if (!(r > 0.0) || r > scan->max_urange || std::isnan(r)) continue;
    double c = ct * scan->cos_a[b] - st * scan->sin_a[b];
    double s = st * scan->cos_a[b] + ct * scan->sin_a[b];
    f(pose[0] + r * c, pose[1] + r * s);
  }
}

}  // namespace

extern "C" int gm_integrate(GmGrids* g, const double* poses, const GmScan* scan) {
  int status = 0;
  for (int i = 0; i < g->n; ++i) {
    const double* pose = poses + 3 * i;
    CellRef ref{g, i};
    int x0 = cellOf(pose[0], g->ox, g->delta), y0 = cellOf(pose[1], g->oy, g->delta);
    const double ct = std::cos(pose[2]), st = std::sin(pose[2]);
    for (int b = 0; b < scan->beams; ++b) {
      double r = scan->ranges[b];
      if (!(r > 0.0) || r > scan->max_range || std::isnan(r)) continue;
      bool cropped = false;
      if (r > scan->max_urange) { r = scan->max_urange; cropped = true; }
      double ex = pose[0] + r * (ct * scan->cos_a[b] - st * scan->sin_a[b]);
      double ey = pose[1] + r * (st * scan->cos_a[b] + ct * scan->sin_a[b]);
      int x1 = cellOf(ex, g->ox, g->delta), y1 = cellOf(ey, g->oy, g->delta);
      if (!ref.inside(x1, y1) || !ref.inside(x0, y0)) { status = -1; continue; }
      // Bresenham from the laser cell to the endpoint cell: free cells before the endpoint
      int dx = std::abs(x1 - x0), dy = -std::abs(y1 - y0);
      int sx = x0 < x1 ? 1 : -1, sy = y0 < y1 ? 1 : -1, err = dx + dy;
      int cx = x0, cy = y0;
      while (!(cx == x1 && cy == y1)) {
        bump(g->visits[ref.index(cx, cy)]);
        int e2 = 2 * err;
        if (e2 >= dy) { err += dy; cx += sx; }
        if (e2 <= dx) { err += dx; cy += sy; }
      }
      long k = ref.index(x1, y1);
      bump(g->visits[k]);
      if (!cropped && g->hits[k] < 65535) {
        uint16_t n = ++g->hits[k];
        float fx = static_cast<float>(ex - (g->ox + x1 * g->delta));
        float fy = static_cast<float>(ey - (g->oy + y1 * g->delta));
        g->mx[k] += (fx - g->mx[k]) / n;
        g->my[k] += (fy - g->my[k]) / n;
      }
    }
  }
  return status;
}

extern "C" double gm_score(const GmGrids* g, int i, const double* pose, const GmScan* scan,
                           const GmMatcherParams* p) {
  CellRef ref{g, i};
  double s = 0.0;
  forEachBeam(pose, scan, p, [&](double hx, double hy) {
    double mu2 = bestMu2(ref, hx, hy, p);
    if (mu2 >= 0.0) s += std::exp(-mu2 / p->sigma);
  });
  return s;
}

extern "C" void gm_likelihood_and_score(const GmGrids* g, int i, const double* pose, const GmScan* scan,
                                        const GmMatcherParams* p, double* likelihood, double* score) {
  CellRef ref{g, i};
  double l = 0.0, s = 0.0;
  const double no_hit = p->null_likelihood / p->lsigma;
  forEachBeam(pose, scan, p, [&](double hx, double hy) {
    double mu2 = bestMu2(ref, hx, hy, p);
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

extern "C" void gm_optimize(const GmGrids* g, const double* poses, const GmScan* scan, const GmMatcherParams* p,
                            double* out_poses, double* out_scores, double* out_likelihood) {
  for (int i = 0; i < g->n; ++i) {
    double current[3] = {poses[3 * i], poses[3 * i + 1], poses[3 * i + 2]};
    double current_score = gm_score(g, i, current, scan, p);
    double best_score = current_score;
    double ldelta = p->lstep, adelta = p->astep;
    int refinement = 0;
    do {
      if (best_score >= current_score) {  // no move improved: refine
        ++refinement;
        ldelta *= 0.5;
        adelta *= 0.5;
      }
      best_score = current_score;
      double best_local[3] = {current[0], current[1], current[2]};
      static const int kMoves[6][3] = {{1, 0, 0}, {-1, 0, 0}, {0, -1, 0}, {0, 1, 0}, {0, 0, 1}, {0, 0, -1}};
      for (const auto& m : kMoves) {
        double local[3] = {current[0] + m[0] * ldelta, current[1] + m[1] * ldelta, current[2] + m[2] * adelta};
        double local_score = gm_score(g, i, local, scan, p);
        if (local_score > current_score) {
          current_score = local_score;
          best_local[0] = local[0];
          best_local[1] = local[1];
          best_local[2] = local[2];
        }
      }
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
    gm_likelihood_and_score(g, i, accepted, scan, p, &l, &s);
    out_likelihood[i] = l;
  }
}
