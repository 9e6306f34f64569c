// CostmapModel::footprintCost over whole trajectories, the rollout's hot loop: at every pose
// the footprint polygon is laid down on the costmap and its edges rasterized between the
// vertices' cells (Bresenham, both ends included, as base_local_planner's LineIterator);
// a pose costs -1 when its centre or a vertex is off the map or an edge cell is lethal or
// unknown, else the highest cell cost on the outline. A footprint of fewer than 3 points is a
// circle: the centre cell alone, inscribed cells illegal too. Plain C ABI through ctypes
// (base_local_planner/native.py), no ROS.
#include <algorithm>
#include <cmath>
#include <cstdint>

namespace {

const uint8_t LETHAL = 254;
const uint8_t INSCRIBED = 253;
const uint8_t NO_INFORMATION = 255;

struct Grid {
  const uint8_t* data;
  int nx, ny;
  double ox, oy, res;

  bool toMap(double wx, double wy, int& mx, int& my) const {
    if (wx < ox || wy < oy) {
      return false;
    }
    mx = static_cast<int>((wx - ox) / res);
    my = static_cast<int>((wy - oy) / res);
    return mx < nx && my < ny;
  }
  uint8_t cost(int mx, int my) const { return data[static_cast<long>(my) * nx + mx]; }
};

double lineCost(const Grid& g, int x0, int y0, int x1, int y1) {
  const int dx = std::abs(x1 - x0), dy = std::abs(y1 - y0);
  const int sx = x1 >= x0 ? 1 : -1, sy = y1 >= y0 ? 1 : -1;
  int xinc1 = sx, xinc2 = sx, yinc1 = sy, yinc2 = sy, den, num, numadd, numpixels;
  if (dx >= dy) {
    xinc1 = 0;
    yinc2 = 0;
    den = dx;
    num = dx / 2;
    numadd = dy;
    numpixels = dx;
  } else {
    xinc2 = 0;
    yinc1 = 0;
    den = dy;
    num = dy / 2;
    numadd = dx;
    numpixels = dy;
  }
  double line = 0.0;
  int x = x0, y = y0;
  for (int k = 0; k <= numpixels; ++k) {
    const uint8_t c = g.cost(x, y);
    if (c == LETHAL || c == NO_INFORMATION) {
      return -1.0;
    }
    line = std::max(line, static_cast<double>(c));
    num += numadd;
    if (num >= den) {
      num -= den;
      x += xinc1;
      y += yinc1;
    }
    x += xinc2;
    y += yinc2;
  }
  return line;
}

// The cells the segment (x0, y0) -> (x1, y1) (world) really crosses (a grid traversal,
// Amanatides & Woo), both ends' cells included; -1 on a lethal or unknown cell, else the
// highest cost. The vertices' cells are on the map (checked by the caller).
double segmentCost(const Grid& g, double x0, double y0, double x1, double y1) {
  const double fx0 = (x0 - g.ox) / g.res, fy0 = (y0 - g.oy) / g.res;
  const double fx1 = (x1 - g.ox) / g.res, fy1 = (y1 - g.oy) / g.res;
  int cx = static_cast<int>(fx0), cy = static_cast<int>(fy0);
  const int ex = static_cast<int>(fx1), ey = static_cast<int>(fy1);
  const double dx = fx1 - fx0, dy = fy1 - fy0;
  const int sx = dx > 0 ? 1 : -1, sy = dy > 0 ? 1 : -1;
  const double inf = 1e30;
  const double tdx = dx != 0 ? std::abs(1.0 / dx) : inf, tdy = dy != 0 ? std::abs(1.0 / dy) : inf;
  double tmx = dx != 0 ? (dx > 0 ? (cx + 1 - fx0) : (fx0 - cx)) * tdx : inf;
  double tmy = dy != 0 ? (dy > 0 ? (cy + 1 - fy0) : (fy0 - cy)) * tdy : inf;
  double line = 0.0;
  const int max_steps = std::abs(ex - cx) + std::abs(ey - cy) + 2;
  for (int k = 0; k < max_steps; ++k) {
    if (cx < 0 || cy < 0 || cx >= g.nx || cy >= g.ny) {
      return -1.0;
    }
    const uint8_t c = g.cost(cx, cy);
    if (c == LETHAL || c == NO_INFORMATION) {
      return -1.0;
    }
    line = std::max(line, static_cast<double>(c));
    if (cx == ex && cy == ey) {
      break;
    }
    if (tmx < tmy) {
      tmx += tdx;
      cx += sx;
    } else {
      tmy += tdy;
      cy += sy;
    }
  }
  return line;
}

double footprintCost(const Grid& g, double x, double y, double th, const double* fp, int nfp,
                     int* vx, int* vy, bool exact) {
  int cx, cy;
  if (!g.toMap(x, y, cx, cy)) {
    return -1.0;
  }
  if (nfp < 3) {
    const uint8_t c = g.cost(cx, cy);
    if (c == LETHAL || c == INSCRIBED || c == NO_INFORMATION) {
      return -1.0;
    }
    return c;
  }
  const double c = std::cos(th), s = std::sin(th);
  for (int i = 0; i < nfp; ++i) {
    const double px = fp[2 * i], py = fp[2 * i + 1];
    if (!g.toMap(x + px * c - py * s, y + px * s + py * c, vx[i], vy[i])) {
      return -1.0;
    }
  }
  double cost = 0.0;
  for (int i = 0; i < nfp; ++i) {
    const int j = (i + 1) % nfp;
    double line;
    if (exact) {
      const double ax = x + fp[2 * i] * c - fp[2 * i + 1] * s;
      const double ay = y + fp[2 * i] * s + fp[2 * i + 1] * c;
      const double bx = x + fp[2 * j] * c - fp[2 * j + 1] * s;
      const double by = y + fp[2 * j] * s + fp[2 * j + 1] * c;
      line = segmentCost(g, ax, ay, bx, by);
    } else {
      line = lineCost(g, vx[i], vy[i], vx[j], vy[j]);
    }
    if (line < 0) {
      return -1.0;
    }
    cost = std::max(cost, line);
  }
  return cost;
}

}  // namespace

extern "C" {

// grid: nx*ny costs; fp: nfp (x, y) pairs (robot frame); xs/ys/ths: n*T poses, trajectory i
// at [i*T, i*T + T). out[i]: -1 when some pose's footprint is illegal, else the highest
// footprint cost over its poses.
// exact != 0: the outline's cells are those its edges really cross (segmentCost) instead of
// the Bresenham line between the vertices' cells, which can pass a cell beside the edge.
void blp_footprint_costs(const uint8_t* grid, int nx, int ny, double ox, double oy, double res,
                         const double* fp, int nfp, const double* xs, const double* ys,
                         const double* ths, int n, int T, int exact, double* out) {
  const Grid g{grid, nx, ny, ox, oy, res};
  int vx[64], vy[64];
  nfp = std::min(nfp, 64);
  for (int i = 0; i < n; ++i) {
    double worst = 0.0;
    for (int t = 0; t < T; ++t) {
      const long k = static_cast<long>(i) * T + t;
      const double c = footprintCost(g, xs[k], ys[k], ths[k], fp, nfp, vx, vy, exact != 0);
      if (c < 0) {
        worst = -1.0;
        break;
      }
      worst = std::max(worst, c);
    }
    out[i] = worst;
  }
}

}  // extern "C"
