// See raycast.h. Each exact test below mirrors its NumPy kernel in rayprims.py / bvh.py
// expression for expression (same operations in the same order, IEEE semantics for the
// divisions by zero and the NaNs: fmin/fmax skip a NaN as np.fmin/np.fmax do), so that the
// two casters decide grazing rays alike. This file is compiled without floating-point
// contraction (CMakeLists.txt) for the same reason.
#include "raycast.h"

#include "azimuth_bins.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <string>
#include <utility>

namespace ode_sim {

namespace {

constexpr double kTol = 1e-12;  // rayprims.TOL
constexpr double kInf = std::numeric_limits<double>::infinity();

// np.fmin / np.fmax: a NaN operand is skipped (std::fmin's rule, without the library call)
inline double nfmin(double a, double b) { return (a < b || b != b) ? a : b; }
inline double nfmax(double a, double b) { return (a > b || b != b) ? a : b; }

// first surface crossing at t >= tmin of a box with half extents h (ray in the box frame)
inline bool boxHit(const double o[3], const double d[3], const double h[3], double tmin,
                   double& t) {
  double tn = 0.0, tf = 0.0;
  for (int i = 0; i < 3; ++i) {
    const double inv = 1.0 / d[i];
    const double t1 = (-h[i] - o[i]) * inv;
    const double t2 = (h[i] - o[i]) * inv;
    const double a = nfmin(t1, t2), b = nfmax(t1, t2);
    tn = i == 0 ? a : nfmax(tn, a);
    tf = i == 0 ? b : nfmin(tf, b);
  }
  t = tn >= tmin ? tn : tf;  // start inside: the exit point (as ODE)
  return tn <= tf && t >= tmin;
}

// o relative to the centre
inline bool sphereHit(const double o[3], const double d[3], double r, double tmin, double& t) {
  const double b = o[0] * d[0] + o[1] * d[1] + o[2] * d[2];
  const double c = o[0] * o[0] + o[1] * o[1] + o[2] * o[2] - r * r;
  const double disc = b * b - c;
  const double sq = std::sqrt(std::max(disc, 0.0));
  t = -b - sq;
  if (!(t >= tmin)) t = -b + sq;  // start inside: the far root (as ODE)
  return disc >= 0.0 && t >= tmin;
}

// flat-capped cylinder along local Z (ODE's dCylinder)
inline bool cylinderHit(const double o[3], const double d[3], double r, double hl, double tmin,
                        double& t) {
  const double r2 = r * r;
  const double tol_r = r2 * (1.0 + kTol) + 1e-15;
  const double tol_z = hl * (1.0 + kTol) + 1e-15;
  const double a = d[0] * d[0] + d[1] * d[1];
  const double b = o[0] * d[0] + o[1] * d[1];
  const double c = o[0] * o[0] + o[1] * o[1] - r2;
  const double disc = b * b - a * c;
  const double sq = std::sqrt(std::max(disc, 0.0));
  const bool side_ok = disc >= 0.0 && a > 1e-300;
  double best = kInf;
  const double roots[2] = {(-b - sq) / a, (-b + sq) / a};
  for (double tt : roots) {
    const double z = o[2] + tt * d[2];
    if (side_ok && tt >= tmin && std::fabs(z) <= tol_z && tt < best) best = tt;
  }
  const double caps[2] = {hl, -hl};
  for (double zc : caps) {
    const double tt = (zc - o[2]) / d[2];
    const double x = o[0] + tt * d[0];
    const double y = o[1] + tt * d[1];
    if (tt >= tmin && x * x + y * y <= tol_r && tt < best) best = tt;
  }
  t = best;
  return std::isfinite(best);
}

// bvh.py's slab test of a node's padded bounds
inline bool slab(const double* lo, const double* hi, const double o[3], const double inv[3],
                 double tmin, double limit) {
  double tn = 0.0, tf = 0.0;
  for (int i = 0; i < 3; ++i) {
    const double t1 = (lo[i] - o[i]) * inv[i];
    const double t2 = (hi[i] - o[i]) * inv[i];
    const double a = nfmin(t1, t2), b = nfmax(t1, t2);
    tn = i == 0 ? a : nfmax(tn, a);
    tf = i == 0 ? b : nfmin(tf, b);
  }
  return tn <= tf && tf >= tmin && tn <= limit;
}

// R^T v for a row-major R
inline void rotT(const double* R, const double v[3], double out[3]) {
  for (int i = 0; i < 3; ++i) out[i] = R[i] * v[0] + R[3 + i] * v[1] + R[6 + i] * v[2];
}

template <typename T>
void need(const std::vector<T>& v, size_t n, const std::string& what) {
  if (v.size() != n) throw std::invalid_argument("RayScene: " + what + " has the wrong length");
}

// the slots, rotations and positions of k posed shapes of one kind ("item", "plane")
void needPosed(const std::vector<int>& slot, const std::vector<double>& rot,
               const std::vector<double>& pos, size_t k, const std::string& kind) {
  need(slot, k, kind + " slots");
  need(rot, 9 * k, kind + " rotations");
  need(pos, 3 * k, kind + " positions");
  for (int s : slot)
    if (s < -1) throw std::invalid_argument("RayScene: " + kind + " slot below -1");
}

}  // namespace

void RayScene::checkShape(int64_t shape) const {
  if (shape < 0 || shape >= nshapes_)
    throw std::invalid_argument("RayScene: shape index " + std::to_string(shape) +
                                " outside the scene's " + std::to_string(nshapes_) + " shapes");
}

void RayScene::poseItem(Item& it, const double* rot, const double* pos) {
  std::copy(rot, rot + 9, it.rot);
  std::copy(pos, pos + 3, it.pos);
  double ext[3];
  for (int i = 0; i < 3; ++i) {
    if (it.code == 0) {
      ext[i] = std::fabs(rot[3 * i]) * it.p[0] + std::fabs(rot[3 * i + 1]) * it.p[1] +
               std::fabs(rot[3 * i + 2]) * it.p[2];
    } else if (it.code == 1) {
      ext[i] = it.p[0];
    } else {
      const double axis = rot[3 * i + 2];
      ext[i] = it.p[1] * std::fabs(axis) + it.p[0] * std::sqrt(std::max(1.0 - axis * axis, 0.0));
    }
  }
  const double big =
      std::max({std::fabs(pos[0]), std::fabs(pos[1]), std::fabs(pos[2]), ext[0], ext[1], ext[2]});
  const double pad = 1e-9 * (1.0 + 2.0 * big);
  for (int i = 0; i < 3; ++i) {
    it.lo[i] = pos[i] - ext[i] - pad;
    it.hi[i] = pos[i] + ext[i] + pad;
  }
}

void RayScene::posePlane(Plane& pl, const double* rot, const double* pos) {
  for (int i = 0; i < 3; ++i)
    pl.n[i] =
        rot[3 * i] * pl.local[0] + rot[3 * i + 1] * pl.local[1] + rot[3 * i + 2] * pl.local[2];
  pl.offset = pl.n[0] * pos[0] + pl.n[1] * pos[1] + pl.n[2] * pos[2];
}

void RayScene::setItems(const std::vector<int>& code, const std::vector<int64_t>& shape,
                        const std::vector<double>& p, const std::vector<int>& slot,
                        const std::vector<double>& rot, const std::vector<double>& pos) {
  const size_t k = code.size();
  need(shape, k, "item shapes");
  need(p, 3 * k, "item parameters");
  needPosed(slot, rot, pos, k, "item");
  items_.assign(k, Item{});
  for (size_t j = 0; j < k; ++j) {
    Item& it = items_[j];
    if (code[j] < 0 || code[j] > 2) throw std::invalid_argument("RayScene: item code not 0-2");
    checkShape(shape[j]);
    it.code = code[j];
    it.shape = shape[j];
    it.slot = slot[j];
    std::copy(&p[3 * j], &p[3 * j] + 3, it.p);
    poseItem(it, &rot[9 * j], &pos[3 * j]);
    nslots_ = std::max(nslots_, it.slot + 1);
  }
  group_order_.resize(k);
  std::iota(group_order_.begin(), group_order_.end(), 0);
  std::stable_sort(group_order_.begin(), group_order_.end(), [this](int a, int b) {
    const Item &x = items_[a], &y = items_[b];
    return x.code != y.code ? x.code < y.code : x.shape < y.shape;
  });
}

void RayScene::setPlanes(const std::vector<int64_t>& shape, const std::vector<double>& local_normal,
                         const std::vector<int>& slot, const std::vector<double>& rot,
                         const std::vector<double>& pos) {
  const size_t k = shape.size();
  need(local_normal, 3 * k, "plane normals");
  needPosed(slot, rot, pos, k, "plane");
  planes_.assign(k, Plane{});
  for (size_t j = 0; j < k; ++j) {
    Plane& pl = planes_[j];
    checkShape(shape[j]);
    pl.shape = shape[j];
    pl.slot = slot[j];
    std::copy(&local_normal[3 * j], &local_normal[3 * j] + 3, pl.local);
    posePlane(pl, &rot[9 * j], &pos[3 * j]);
    nslots_ = std::max(nslots_, pl.slot + 1);
  }
}

void RayScene::setForest(const std::vector<double>& lo, const std::vector<double>& hi,
                         const std::vector<int64_t>& first, const std::vector<int64_t>& count,
                         const std::vector<uint8_t>& leaf, const std::vector<double>& v0,
                         const std::vector<double>& e1, const std::vector<double>& e2,
                         const std::vector<int64_t>& owner) {
  const size_t m = first.size(), t = owner.size();
  need(lo, 3 * m, "node bounds");
  need(hi, 3 * m, "node bounds");
  need(count, m, "node counts");
  need(leaf, m, "node leaf flags");
  need(v0, 3 * t, "triangle vertices");
  need(e1, 3 * t, "triangle edges");
  need(e2, 3 * t, "triangle edges");
  for (size_t j = 0; j < m; ++j) {
    const int64_t end = first[j] + count[j];
    if (first[j] < 0 || count[j] < 0 || end > static_cast<int64_t>(leaf[j] ? t : m))
      throw std::invalid_argument("RayScene: BVH node refers outside the forest");
    // children come after their parent (bvh.py builds breadth first): every walk ends
    if (!leaf[j] && first[j] <= static_cast<int64_t>(j))
      throw std::invalid_argument("RayScene: BVH node's children before it");
  }
  for (int64_t s : owner) checkShape(s);
  lo_ = lo;
  hi_ = hi;
  first_ = first;
  count_ = count;
  leaf_ = leaf;
  v0_ = v0;
  e1_ = e1;
  e2_ = e2;
  owner_ = owner;
}

void RayScene::setMeshes(int64_t static_root, const std::vector<int64_t>& shape,
                         const std::vector<int64_t>& root, const std::vector<int>& slot) {
  need(root, shape.size(), "mesh roots");
  need(slot, shape.size(), "mesh slots");
  const int64_t m = static_cast<int64_t>(first_.size());
  if (static_root < -1 || static_root >= m)
    throw std::invalid_argument("RayScene: static mesh root not in forest");
  static_root_ = static_root;
  dyn_meshes_.clear();
  for (size_t j = 0; j < shape.size(); ++j) {
    if (root[j] < 0 || root[j] >= m)
      throw std::invalid_argument("RayScene: mesh root not in forest");
    checkShape(shape[j]);
    if (slot[j] < 0) throw std::invalid_argument("RayScene: dynamic mesh without a slot");
    dyn_meshes_.push_back(DynMesh{shape[j], root[j], slot[j]});
    nslots_ = std::max(nslots_, slot[j] + 1);
  }
}

void RayScene::setSlots(const std::vector<int64_t>& row, const std::vector<double>& local_rot,
                        const std::vector<double>& local_pos, int64_t links) {
  const size_t k = row.size();
  need(local_rot, 9 * k, "slot rotations");
  need(local_pos, 3 * k, "slot positions");
  for (int64_t r : row)
    if (r < 0 || r >= links) throw std::invalid_argument("RayScene: slot row outside the links");
  slot_row_ = row;
  slot_rot_ = local_rot;
  slot_pos_ = local_pos;
  nlinks_ = links;
}

void RayScene::walk(int64_t root, const double o[3], const double d[3], const double inv[3],
                    double tmin, const uint8_t* excluded, double& best, int64_t& who) const {
  int64_t hit_tri = -1;  // the triangle of this walk that holds `best`, if any
  int64_t stack[512];
  std::vector<int64_t> spill;  // only for hierarchies deeper than any mesh needs
  int top = 0;
  stack[top++] = root;
  while (top > 0 || !spill.empty()) {
    int64_t node;
    if (!spill.empty()) {
      node = spill.back();
      spill.pop_back();
    } else {
      node = stack[--top];
    }
    if (!slab(&lo_[3 * node], &hi_[3 * node], o, inv, tmin, best)) continue;
    const int64_t f = first_[node], c = count_[node];
    if (!leaf_[node]) {
      for (int64_t k = 0; k < c; ++k) {
        if (top < 512)
          stack[top++] = f + k;
        else
          spill.push_back(f + k);
      }
      continue;
    }
    for (int64_t tri = f; tri < f + c; ++tri) {
      if (excluded && excluded[owner_[tri]]) continue;
      // bvh.py BVHForest._triangles (Moller-Trumbore)
      const double* v0 = &v0_[3 * tri];
      const double ax = e1_[3 * tri], ay = e1_[3 * tri + 1], az = e1_[3 * tri + 2];
      const double bx = e2_[3 * tri], by = e2_[3 * tri + 1], bz = e2_[3 * tri + 2];
      const double px = d[1] * bz - d[2] * by;
      const double py = d[2] * bx - d[0] * bz;
      const double pz = d[0] * by - d[1] * bx;
      const double det = ax * px + ay * py + az * pz;
      const double tx = o[0] - v0[0];
      const double ty = o[1] - v0[1];
      const double tz = o[2] - v0[2];
      const double qx = ty * az - tz * ay;
      const double qy = tz * ax - tx * az;
      const double qz = tx * ay - ty * ax;
      const double inv_det = 1.0 / det;
      const double u = (tx * px + ty * py + tz * pz) * inv_det;
      const double v = (d[0] * qx + d[1] * qy + d[2] * qz) * inv_det;
      const double t = (bx * qx + by * qy + bz * qz) * inv_det;
      // nearest; on a tie the lowest triangle of this hierarchy (bvh.py's first_per_ray),
      // while a tie with what was hit before the walk keeps that
      if (u >= -kTol && v >= -kTol && u + v <= 1.0 + kTol && det != 0.0 && t >= tmin &&
          (t < best || (t == best && tri < hit_tri))) {
        best = t;
        who = owner_[tri];
        hit_tri = tri;
      }
    }
  }
}

void RayScene::cast(const double* o_all, const double* d_all, int64_t n, bool common, double tmin,
                    double max_range, const double* link_q, const double* link_p,
                    const uint8_t* excluded, double* t_out, int64_t* who_out) const {
  // the dynamic slots' world poses now (rayprims.Posing.__call__, quat_matrices)
  std::vector<double> link_rot(9 * nlinks_);
  for (int64_t l = 0; l < nlinks_; ++l) {
    const double x = link_q[4 * l], y = link_q[4 * l + 1], z = link_q[4 * l + 2],
                 w = link_q[4 * l + 3];
    double* m = &link_rot[9 * l];
    m[0] = 1 - 2 * (y * y + z * z);
    m[1] = 2 * (x * y - z * w);
    m[2] = 2 * (x * z + y * w);
    m[3] = 2 * (x * y + z * w);
    m[4] = 1 - 2 * (x * x + z * z);
    m[5] = 2 * (y * z - x * w);
    m[6] = 2 * (x * z - y * w);
    m[7] = 2 * (y * z + x * w);
    m[8] = 1 - 2 * (x * x + y * y);
  }
  const size_t nslots = slot_row_.size();
  std::vector<double> dyn_rot_v(9 * nslots), dyn_pos_v(3 * nslots);
  for (size_t j = 0; j < nslots; ++j) {
    const double* R = &link_rot[9 * slot_row_[j]];
    const double* p = link_p + 3 * slot_row_[j];
    const double* L = &slot_rot_[9 * j];
    const double* lp = &slot_pos_[3 * j];
    for (int a = 0; a < 3; ++a) {
      for (int b = 0; b < 3; ++b)
        dyn_rot_v[9 * j + 3 * a + b] =
            R[3 * a] * L[b] + R[3 * a + 1] * L[3 + b] + R[3 * a + 2] * L[6 + b];
      dyn_pos_v[3 * j + a] =
          p[a] + (R[3 * a] * lp[0] + R[3 * a + 1] * lp[1] + R[3 * a + 2] * lp[2]);
    }
  }
  const double* dyn_rot = dyn_rot_v.data();
  const double* dyn_pos = dyn_pos_v.data();
  // this cast's poses: static shapes as set, dynamic ones from the slots
  std::vector<Item> items = items_;
  for (Item& it : items)
    if (it.slot >= 0) poseItem(it, dyn_rot + 9 * it.slot, dyn_pos + 3 * it.slot);
  std::vector<Plane> planes = planes_;
  for (Plane& pl : planes)
    if (pl.slot >= 0) posePlane(pl, dyn_rot + 9 * pl.slot, dyn_pos + 3 * pl.slot);
  // one origin (a lidar scan): raycast.py's item order, without the excluded items and those
  // whose bounds lie beyond max_range, and local origins R^T (c - p); rays of their own: its
  // dense groups (boxes, spheres, cylinders by shape index)
  std::vector<int> order;
  order.reserve(items.size());
  std::vector<double> local_o(common ? 3 * items.size() : 0);
  if (common) {
    for (size_t j = 0; j < items.size(); ++j) {
      const Item& it = items[j];
      if (excluded && excluded[it.shape]) continue;
      double g2 = 0.0;
      for (int i = 0; i < 3; ++i) {
        const double g = std::max({it.lo[i] - o_all[i], o_all[i] - it.hi[i], 0.0});
        g2 += g * g;
      }
      if (!(g2 <= max_range * max_range)) continue;
      order.push_back(static_cast<int>(j));
      const double rel[3] = {o_all[0] - it.pos[0], o_all[1] - it.pos[1], o_all[2] - it.pos[2]};
      rotT(it.rot, rel, &local_o[3 * j]);
    }
  } else {
    for (int j : group_order_)
      if (!(excluded && excluded[items[j].shape])) order.push_back(j);
  }

  // one origin: the items each azimuth bin can see (AzimuthBins), so a ray tests the few
  // items in its direction instead of all; the same items in the same order pass the slab
  // test, so the hits are the same
  AzimuthBins bins;
  if (common) bins.build(items, order, o_all);

  for (int64_t r = 0; r < n; ++r) {
    const double* o = common ? o_all : o_all + 3 * r;
    const double* d = d_all + 3 * r;
    const double inv[3] = {1.0 / d[0], 1.0 / d[1], 1.0 / d[2]};
    double best = max_range;
    int64_t who = -1;
    const int* seen = order.data();
    size_t nseen = order.size();
    if (common) bins.lookup(d, order, seen, nseen);
    for (size_t s = 0; s < nseen; ++s) {
      const int j = seen[s];
      const Item& it = items[j];
      if (!slab(it.lo, it.hi, o, inv, tmin, best)) continue;
      double lo[3] = {0.0, 0.0, 0.0}, ld[3], t = kInf;
      rotT(it.rot, d, ld);
      if (common) {
        std::copy(&local_o[3 * j], &local_o[3 * j] + 3, lo);
      } else {
        const double rel[3] = {o[0] - it.pos[0], o[1] - it.pos[1], o[2] - it.pos[2]};
        rotT(it.rot, rel, lo);
      }
      bool ok;
      if (it.code == 0) {
        ok = boxHit(lo, ld, it.p, tmin, t);
      } else if (it.code == 1) {
        if (common) {
          ok = sphereHit(lo, ld, it.p[0], tmin, t);
        } else {  // the dense group works in the world frame
          const double oc[3] = {o[0] - it.pos[0], o[1] - it.pos[1], o[2] - it.pos[2]};
          ok = sphereHit(oc, d, it.p[0], tmin, t);
        }
      } else {
        ok = cylinderHit(lo, ld, it.p[0], it.p[1], tmin, t);
      }
      if (ok && t < best) {
        best = t;
        who = it.shape;
      }
    }
    for (const Plane& pl : planes) {  // rayprims.plane_hits
      if (excluded && excluded[pl.shape]) continue;
      const double den = pl.n[0] * d[0] + pl.n[1] * d[1] + pl.n[2] * d[2];
      const double num = pl.offset - (pl.n[0] * o[0] + pl.n[1] * o[1] + pl.n[2] * o[2]);
      const double t = num / den;
      if (den != 0.0 && t >= tmin && t < best) {
        best = t;
        who = pl.shape;
      }
    }
    if (static_root_ >= 0) walk(static_root_, o, d, inv, tmin, excluded, best, who);
    for (const DynMesh& m : dyn_meshes_) {
      if (excluded && excluded[m.shape]) continue;
      const double* R = dyn_rot + 9 * m.slot;
      const double* p = dyn_pos + 3 * m.slot;
      const double rel[3] = {o[0] - p[0], o[1] - p[1], o[2] - p[2]};
      double lo[3], ld[3];
      rotT(R, rel, lo);  // (o - p) @ R
      rotT(R, d, ld);
      const double linv[3] = {1.0 / ld[0], 1.0 / ld[1], 1.0 / ld[2]};
      walk(m.root, lo, ld, linv, tmin, excluded, best, who);
    }
    t_out[r] = who >= 0 ? best : kInf;
    who_out[r] = who;
  }
}

}  // namespace ode_sim
