#include "trimesh.h"

#include <limits>
#include <stdexcept>
#include <string>

namespace ode_sim {

TriMesh::TriMesh(const std::vector<double>& vertices, const std::vector<int64_t>& faces)
    : vert_(vertices), data_(nullptr) {
  if (vert_.empty() || vert_.size() % 3 != 0)
    throw std::invalid_argument("TriMesh: vertices must be (N, 3) with N > 0");
  if (faces.empty() || faces.size() % 3 != 0)
    throw std::invalid_argument("TriMesh: faces must be (M, 3) with M > 0");
  const int64_t n = static_cast<int64_t>(vert_.size() / 3);
  if (n > static_cast<int64_t>(std::numeric_limits<dTriIndex>::max()))
    throw std::invalid_argument("TriMesh: too many vertices for ODE's index type");
  index_.reserve(faces.size());
  for (int64_t f : faces) {
    if (f < 0 || f >= n)
      throw std::invalid_argument("TriMesh: face index " + std::to_string(f) + " outside the " +
                                  std::to_string(n) + " vertices");
    index_.push_back(static_cast<dTriIndex>(f));
  }
  ensureThreadData();
  data_ = dGeomTriMeshDataCreate();
  dGeomTriMeshDataBuildDouble(data_, vert_.data(), 3 * sizeof(double), static_cast<int>(n),
                              index_.data(), static_cast<int>(index_.size()),
                              3 * sizeof(dTriIndex));
}

TriMesh::~TriMesh() {
  if (data_) dGeomTriMeshDataDestroy(data_);
}

dGeomID TriMesh::create(dSpaceID space) const {
  ensureThreadData();
  return dCreateTriMesh(space, data_, nullptr, nullptr, nullptr);
}

void ensureThreadData() {
  thread_local bool done = false;
  if (!done) done = dAllocateODEDataForThread(dAllocateMaskAll) != 0;
}

}  // namespace ode_sim
