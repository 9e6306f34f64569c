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
  s.cast(o, d, 6, true, tmin, tmax, q.data(), p.data(), excluded.empty() ? nullptr : excluded.data(),
         h.t.data(), h.who.data());
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
  EXPECT_EQ(h.t[3], kInf);        // nothing towards -y
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
  h = castAxes(s, o, 0.0, 2.5);   // a hit at max range does not count
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
  s.setForest({2, -1, -1}, {2, 1, 1}, {0}, {2}, {1}, {2, -1, -1, 2, -1, -1},
              {0, 2, 0, 0, 2, 2}, {0, 2, 2, 0, 0, 2}, {1, 0});
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
