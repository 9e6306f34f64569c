// The compiled core's mesh import (engine/core/meshimport.cpp, libassimp) on its own: a COLLADA
// file in Gazebo's model layout (centimetres, a node hierarchy, two geometries, a phong colour
// and a texture), an OBJ with its MTL, and files assimp cannot read. description/mesh.py turns
// the up axis and builds the collision arrays (test_gazebo_meshes.py).
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <stdexcept>
#include <string>

#include "meshimport.h"

using ode_sim::ImportedScene;
using ode_sim::importScene;

namespace {

const std::string kModels = std::string(ODE_SIM_TEST_DIR) + "/fixtures/gazebo_models/";

// min / max of one coordinate over a mesh's positions
std::pair<double, double> range(const ode_sim::ImportedMesh& m, int axis) {
  double lo = 1e300, hi = -1e300;
  for (size_t i = axis; i < m.positions.size(); i += 3) {
    lo = std::min(lo, m.positions[i]);
    hi = std::max(hi, m.positions[i]);
  }
  return {lo, hi};
}

TEST(MeshImport, ColladaNodesUnitsAndMaterials) {
  const ImportedScene s = importScene(kModels + "step_block/meshes/step_block.dae");
  ASSERT_EQ(s.meshes.size(), 2u);
  EXPECT_EQ(s.meshes[0].node, "lower");
  EXPECT_EQ(s.meshes[1].node, "upper");
  for (const auto& m : s.meshes) {
    EXPECT_EQ(m.faces.size(), 36u);  // 12 triangles
    EXPECT_EQ(m.normals.size(), m.positions.size());
    EXPECT_EQ(m.uvs.size() / 2, m.positions.size() / 3);
  }
  // centimetres -> metres (assimp applies <unit>); the file's Y is still up here
  auto y = range(s.meshes[1], 1);
  EXPECT_NEAR(y.first, 0.0, 1e-6);
  EXPECT_NEAR(y.second, 0.6, 1e-6);
  auto x = range(s.meshes[0], 0);  // block translate + node translate
  EXPECT_NEAR(x.first, -0.5, 1e-6);
  EXPECT_NEAR(x.second, 0.0, 1e-6);
  const auto& red = s.materials.at(s.meshes[0].material);
  EXPECT_EQ(red.name, "red");
  EXPECT_TRUE(red.has_diffuse);
  EXPECT_NEAR(red.diffuse[0], 0.8, 1e-6);
  EXPECT_EQ(s.materials.at(s.meshes[1].material).texture, "../materials/textures/split.png");
}

TEST(MeshImport, ObjWithMtl) {
  const ImportedScene s = importScene(kModels + "prism/meshes/prism.obj");
  ASSERT_EQ(s.meshes.size(), 1u);
  EXPECT_EQ(s.meshes[0].faces.size(), 24u);  // 2 caps + 3 quads as 8 triangles
  const auto& m = s.materials.at(s.meshes[0].material);
  EXPECT_EQ(m.name, "orange");
  EXPECT_EQ(m.texture, "orange.png");
}

TEST(MeshImport, UnreadableFilesThrowOneLine) {
  const std::string path = testing::TempDir() + "broken.dae";
  {
    std::ofstream f(path);
    f << "<?xml version=\"1.0\"?><COLLADA xmlns=\"http://www.collada.org/2005/11/"
         "COLLADASchema\" version=\"1.4.1\"><library_geometries><geometry id=\"g\"><mesh>";
  }
  try {
    importScene(path);
    FAIL() << "a truncated COLLADA file was read";
  } catch (const std::runtime_error& e) {
    const std::string what = e.what();
    EXPECT_FALSE(what.empty());
    EXPECT_EQ(what.find('\n'), std::string::npos) << what;
  }
  EXPECT_THROW(importScene(kModels + "no/such/file.dae"), std::runtime_error);
}

}  // namespace

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
