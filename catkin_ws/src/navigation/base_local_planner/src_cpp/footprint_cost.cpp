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

  bool toMap(double wx, double wy, int& mx, int& my) const
  {
    if (wx < ox || wy < oy) {
      return false;
    }
    mx = static_cast<int>((wx - ox) / res);
    my = static_cast<int>((wy - oy) / res);
    return mx < nx && my < ny;
  }
  uint8_t cost(int mx, int my) const { return data[static_cast<long>(my) * nx + mx]; }
};

double lineCost(const Grid& g, int x0, int y0, int x1, int y1)
{
  const int dx = std::abs(x1 - x0), dy = std::abs(y1 - y0);
  const int sx = x1 >= x0 ? 1 : -1, sy = y1 >= y0 ? 1 : -1;
  int xinc1 = sx, xinc2 = sx, yinc1 = sy, yinc2 = sy, den, num, numadd, numpixels;
  if (dx >= dy) {
    xinc1 = 0; yinc2 = 0; den = dx; num = dx / 2; numadd = dy; numpixels = dx;
  } else {
    xinc2 = 0; yinc1 = 0; den = dy; num = dy / 2; numadd = dx; numpixels = dy;
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

double footprintCost(const Grid& g, double x, double y, double th, const double* fp, int nfp,
                     int* vx, int* vy)
{
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
    const double line = lineCost(g, vx[i], vy[i], vx[j], vy[j]);
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
void blp_footprint_costs(const uint8_t* grid, int nx, int ny, double ox, double oy, double res,
                         const double* fp, int nfp, const double* xs, const double* ys,
                         const double* ths, int n, int T, double* out)
{
  const Grid g{grid, nx, ny, ox, oy, res};
  int vx[64], vy[64];
  nfp = std::min(nfp, 64);
  for (int i = 0; i < n; ++i) {
    double worst = 0.0;
    for (int t = 0; t < T; ++t) {
      const long k = static_cast<long>(i) * T + t;
      const double c = footprintCost(g, xs[k], ys[k], ths[k], fp, nfp, vx, vy);
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
