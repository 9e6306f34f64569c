// Triangle meshes for collision: libode's trimesh collider (dCreateTriMesh) on the vertices and
// faces the description layer loaded (description/mesh.py, already scaled). The data is copied
// once per loaded mesh (ODE keeps pointers to it) and shared by every geom made from it; the
// lidar's ray caster (raycore.py) builds its BVH from the same arrays.
#pragma once

#include <ode/ode.h>

#include <cstdint>
#include <vector>

namespace ode_sim {

class TriMesh {
 public:
  /// vertices: 3 per vertex; faces: 3 vertex indices per triangle. Throws std::invalid_argument
  /// on an empty mesh or an index outside the vertices.
  TriMesh(const std::vector<double>& vertices, const std::vector<int64_t>& faces);
  ~TriMesh();
  TriMesh(const TriMesh&) = delete;
  TriMesh& operator=(const TriMesh&) = delete;

  /// a trimesh geom in `space` (may be nullptr); it must be destroyed before this data
  dGeomID create(dSpaceID space) const;
  size_t triangles() const { return index_.size() / 3; }

 private:
  std::vector<double> vert_;
  std::vector<dTriIndex> index_;
  dTriMeshDataID data_;
};

/// this thread's ODE data (the trimesh collider's caches): once per thread before colliding
void ensureThreadData();

}  // namespace ode_sim
