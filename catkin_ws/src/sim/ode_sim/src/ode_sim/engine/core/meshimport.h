// Mesh files through Debian's assimp (libassimp-dev): COLLADA, Wavefront OBJ + MTL and the
// other formats assimp reads. The scene is flattened: every mesh instance of every node comes
// out with its node's accumulated transform applied (COLLADA's <unit> is in the root node's
// transform; the up axis is left as written, description/mesh.py turns it to Z up as Gazebo
// does), triangles only (points and lines dropped), with its material's colours and diffuse
// texture.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace ode_sim {

struct ImportedMaterial {
  std::string name;
  // RGBA; has_* says whether the file gave the colour (assimp fills defaults otherwise)
  std::array<double, 4> diffuse{0.6, 0.6, 0.6, 1.0}, ambient{0, 0, 0, 1}, emissive{0, 0, 0, 1},
      specular{0, 0, 0, 1};
  bool has_diffuse = false, has_ambient = false, has_emissive = false, has_specular = false;
  double opacity = 1.0;  // 1 opaque
  double shininess = 0.0;
  std::string texture;  // diffuse texture as written in the file ('' none; '*N' embedded)
};

struct ImportedMesh {
  std::string node;  // the node's name (COLLADA <node name> or id)
  std::string name;  // the mesh's name (COLLADA <geometry name> or id)
  int material = -1;
  std::vector<double> positions;  // 3 per vertex, transformed by the node
  std::vector<float> normals;     // 3 per vertex (unit), transformed by the node
  std::vector<float> uvs;         // 2 per vertex, or empty
  std::vector<int32_t> faces;     // 3 per triangle
};

struct ImportedScene {
  std::vector<ImportedMesh> meshes;
  std::vector<ImportedMaterial> materials;
};

/// Reads `path`; throws std::runtime_error with assimp's one-line reason when it cannot.
ImportedScene importScene(const std::string& path);

}  // namespace ode_sim
