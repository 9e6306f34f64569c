// The compiled core's ray casting (engine/core/raycast.cpp) on its own, without Python: the
// distances of each shape kind, rays from inside, min/max range, exclusion, a moving shape,
// the tie rule and bad input. test/test_raycast_core.py compares it with the NumPy caster.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

#include "raycast.h"

using ode_sim::RayScene;

namespace {

const double kInf = std::numeric_limits<double>::infinity();
const std::vector<double> kEye = {1, 0, 0, 0, 1, 0, 0, 0, 1};

struct Hits {
  std::vector<double> t;
  std::vector<int64_t> who;
};

// rays along +x, -x, +y, -y, +z, -z from one origin
Hits castAxes(const RayScene& s, const double o[3], double tmin, double tmax,
              const std::vector<uint8_t>& excluded = {}, const std::vector<double>& q = {},
              const std::vector<double>& p = {}) {
  const double d[18] = {1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1};
  Hits h{std::vector<double>(6), std::vector<int64_t>(6)};
  s.cast(o, d, 6, true, tmin, tmax, q.data(), p.data(),
         excluded.empty() ? nullptr : excluded.data(), h.t.data(), h.who.data());
  return h;
}

// shape 0: box 1 x 2 x 4 at (3, 0, 0); 1: sphere r 0.5 at (0, 3, 0); 2: cylinder r 0.5,
// length 2 along z at (-3, 0, 0); 3: the plane z = -1 (normal +z)
RayScene solids() {
  RayScene s(4);
  std::vector<double> rot;
  for (int i = 0; i < 3; ++i) rot.insert(rot.end(), kEye.begin(), kEye.end());
  s.setItems({0, 1, 2}, {0, 1, 2}, {0.5, 1, 2, 0.5, 0, 0, 0.5, 1, 0}, {-1, -1, -1}, rot,
             {3, 0, 0, 0, 3, 0, -3, 0, 0});
  s.setPlanes({3}, {0, 0, 1}, {-1}, kEye, {0, 0, -1});
  return s;
}

}  // namespace

TEST(RayScene, DistancesToEachKind) {
  const RayScene s = solids();
  const double o[3] = {0, 0, 0};
  const Hits h = castAxes(s, o, 0.0, 10.0);
  EXPECT_DOUBLE_EQ(h.t[0], 2.5);  // box face at x = 2.5
  EXPECT_EQ(h.who[0], 0);
  EXPECT_DOUBLE_EQ(h.t[1], 2.5);  // cylinder side at x = -2.5
  EXPECT_EQ(h.who[1], 2);
  EXPECT_DOUBLE_EQ(h.t[2], 2.5);  // sphere at y = 2.5
  EXPECT_EQ(h.who[2], 1);
  EXPECT_EQ(h.t[3], kInf);  // nothing towards -y
  EXPECT_EQ(h.who[3], -1);
  EXPECT_EQ(h.t[4], kInf);
  EXPECT_DOUBLE_EQ(h.t[5], 1.0);  // the plane below
  EXPECT_EQ(h.who[5], 3);
}

TEST(RayScene, InsideReportsTheExitAndRangesBound) {
  const RayScene s = solids();
  const double in_box[3] = {3, 0, 0};
  Hits h = castAxes(s, in_box, 0.0, 10.0);
  EXPECT_DOUBLE_EQ(h.t[0], 0.5);
  EXPECT_DOUBLE_EQ(h.t[2], 1.0);
  EXPECT_DOUBLE_EQ(h.t[4], 2.0);
  const double in_can[3] = {-3, 0, 0};
  h = castAxes(s, in_can, 0.0, 10.0);
  EXPECT_DOUBLE_EQ(h.t[4], 1.0);  // the top cap
  EXPECT_DOUBLE_EQ(h.t[0], 0.5);  // the side
  const double o[3] = {0, 0, 0};
  h = castAxes(s, o, 2.6, 10.0);  // min range past the box's near face: its far face
  EXPECT_DOUBLE_EQ(h.t[0], 3.5);
  h = castAxes(s, o, 0.0, 2.5);  // a hit at max range does not count
  EXPECT_EQ(h.who[0], -1);
  EXPECT_EQ(h.t[0], kInf);
}

TEST(RayScene, ExcludedShapesAreNotSeen) {
  const RayScene s = solids();
  const double o[3] = {0, 0, 0};
  const Hits h = castAxes(s, o, 0.0, 10.0, {1, 0, 0, 1});
  EXPECT_EQ(h.who[0], -1);
  EXPECT_EQ(h.who[5], -1);
  EXPECT_EQ(h.who[2], 1);
}

TEST(RayScene, MeshAndTheLowestTriangleWinsATie) {
  // two triangles in the plane x = 2 sharing the edge y = z (a square split along it)
  RayScene s(2);
  s.setForest({2, -1, -1}, {2, 1, 1}, {0}, {2}, {1}, {2, -1, -1, 2, -1, -1}, {0, 2, 0, 0, 2, 2},
              {0, 2, 2, 0, 0, 2}, {1, 0});
  s.setMeshes(0, {}, {}, {});
  const double o[3] = {0, 0.5, 0.5};  // through the shared edge: both triangles at t = 2
  const double d[3] = {1, 0, 0};
  double t;
  int64_t who;
  s.cast(o, d, 1, true, 0.0, 10.0, nullptr, nullptr, nullptr, &t, &who);
  EXPECT_DOUBLE_EQ(t, 2.0);
  EXPECT_EQ(who, 1);  // triangle 0 belongs to shape 1
  const double miss[3] = {0, 1.5, 0};
  s.cast(miss, d, 1, true, 0.0, 10.0, nullptr, nullptr, nullptr, &t, &who);
  EXPECT_EQ(who, -1);
}

TEST(RayScene, MovingShapeFollowsItsLink) {
  RayScene s(1);
  s.setItems({0}, {0}, {0.5, 0.5, 0.5}, {0}, kEye, {0, 0, 0});
  s.setSlots({0}, kEye, {1, 0, 0}, 1);  // 1 m ahead of its link
  const double o[3] = {0, 0, 0};
  Hits h = castAxes(s, o, 0.0, 10.0, {}, {0, 0, 0, 1}, {2, 0, 0});
  EXPECT_DOUBLE_EQ(h.t[0], 2.5);
  const double s2 = std::sqrt(0.5);  // the link turned 90 degrees left: the box is at +y
  h = castAxes(s, o, 0.0, 10.0, {}, {0, 0, s2, s2}, {0, 0, 0});
  EXPECT_EQ(h.who[0], -1);
  EXPECT_NEAR(h.t[2], 0.5, 1e-12);
}

TEST(RayScene, BadInputIsRefused) {
  RayScene s(1);
  EXPECT_THROW(s.setItems({0}, {3}, {1, 1, 1}, {-1}, kEye, {0, 0, 0}), std::invalid_argument);
  EXPECT_THROW(s.setItems({5}, {0}, {1, 1, 1}, {-1}, kEye, {0, 0, 0}), std::invalid_argument);
  EXPECT_THROW(s.setItems({0}, {0}, {1, 1}, {-1}, kEye, {0, 0, 0}), std::invalid_argument);
  EXPECT_THROW(s.setPlanes({0}, {0, 0, 1}, {-2}, kEye, {0, 0, 0}), std::invalid_argument);
  EXPECT_THROW(s.setSlots({1}, kEye, {0, 0, 0}, 1), std::invalid_argument);
  EXPECT_THROW(s.setMeshes(0, {}, {}, {}), std::invalid_argument);  // no forest yet
}

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}

// A one-origin scan looks only at the items in each ray's azimuth bin: the same hits as the
// same rays cast one origin per ray (every item tested; to rounding), with boxes around the origin,
// behind it across the +-pi seam, at a bin's edge, tilted, and rays straight up and down.
TEST(RayScene, AzimuthBinsChangeNoHit) {
  const int kItems = 40;
  RayScene s(kItems);
  std::vector<int> code, slot;
  std::vector<int64_t> shape;
  std::vector<double> p, rot, pos;
  unsigned seed = 7;
  auto rnd = [&seed]() {  // a small LCG: the same scene on every platform
    seed = seed * 1103515245u + 12345u;
    return ((seed >> 8) & 0xffff) / 65535.0;
  };
  for (int k = 0; k < kItems; ++k) {
    code.push_back(k % 3);
    shape.push_back(k);
    slot.push_back(-1);
    p.insert(p.end(), {0.1 + 0.5 * rnd(), 0.1 + 0.5 * rnd(), 0.1 + 0.5 * rnd()});
    const double a = 6.283185307179586 * rnd();
    const double c = std::cos(a), sn = std::sin(a);
    rot.insert(rot.end(), {c, -sn, 0, sn, c, 0, 0, 0, 1});
    // item 0 right above the origin (its rectangle holds it), item 1 across the seam
    const double r = k == 0 ? 0.0 : (k == 1 ? 0.8 : 2.0 + 6.0 * rnd());
    const double b = k == 1 ? 3.141592653589793 : 6.283185307179586 * rnd();
    pos.insert(pos.end(), {r * std::cos(b), r * std::sin(b), k == 0 ? 2.0 : -0.3 + 0.6 * rnd()});
  }
  s.setItems(code, shape, p, slot, rot, pos);
  const int n = 2000;
  std::vector<double> o(3 * n, 0.0), d;
  for (int r = 0; r < n; ++r) {
    const double a = -3.141592653589793 + 6.283185307179586 * r / (n - 1);
    const double up = r == 5 ? 1.0 : (r == 6 ? -1.0 : 0.2 * (rnd() - 0.5));
    const double h = std::sqrt(1.0 - up * up);
    d.insert(d.end(), {h * std::cos(a), h * std::sin(a), up});
  }
  std::vector<double> t1(n), t2(n);
  std::vector<int64_t> w1(n), w2(n);
  s.cast(o.data(), d.data(), n, true, 0.05, 20.0, nullptr, nullptr, nullptr, t1.data(), w1.data());
  s.cast(o.data(), d.data(), n, false, 0.05, 20.0, nullptr, nullptr, nullptr, t2.data(), w2.data());
  int hits = 0;
  std::vector<int> seen(kItems, 0);
  for (int r = 0; r < n; ++r) {
    EXPECT_EQ(w1[r], w2[r]) << "ray " << r;
    if (w2[r] >= 0) {
      EXPECT_NEAR(t1[r], t2[r], 1e-12) << "ray " << r;  // the two paths round differently
      ++hits;
      seen[w2[r]] = 1;
    }
  }
  EXPECT_GT(hits, n / 3);
  EXPECT_EQ(w2[5], 0);  // straight up: the item above
  EXPECT_EQ(seen[1], 1);
  int distinct = 0;
  for (int v : seen) distinct += v;
  EXPECT_GT(distinct, 15);
}
