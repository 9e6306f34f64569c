// The lidar's ray casting in the compiled core: the same shapes, mesh hierarchy and nearest-hit
// rules as the NumPy ray caster (engine/raycast.py, rayprims.py, bvh.py, the reference), one
// ray at a time. No ODE, no Python, no ROS: plain arrays in, distances and shape indices out.
//
// Rules (raycast.py's docstring has their origin in ODE's ray colliders):
//  * a ray hits a shape at its first surface crossing at t >= tmin (a ray starting inside a
//    solid reports where it leaves it); a hit counts while t < the best so far, which starts
//    at max_range, so the nearest hit below max_range wins and the first one in the caster's
//    order wins a tie (raycast.py's: boxes, spheres and cylinders in its item order, then
//    planes, then meshes, the lowest triangle of a hierarchy first);
//  * boxes (half extents), spheres (radius), cylinders (radius, half length along local Z, flat
//    caps), two-sided infinite planes, triangle meshes (Moller-Trumbore, both faces count) in
//    the wide BVH forest bvh.py builds (its flat arrays are handed over as they are);
//  * shapes whose `excluded` flag is set are ignored.
// The arithmetic of every exact test is raycast.py's, operation for operation, so the two
// casters agree to rounding (test/test_raycast_core.py).
#pragma once

#include <cstdint>
#include <vector>

namespace ode_sim {

class RayScene {
 public:
  /// A scene over `shapes` shapes: every shape index given below must be below it.
  explicit RayScene(int64_t shapes) : nshapes_(shapes) {}

  /// Boxes (code 0, p = half extents), spheres (1, p[0] = radius) and cylinders (2, p[0] =
  /// radius, p[1] = half length). shape: index in the caster's shape list; slot: -1 for a
  /// static item posed by rot (row-major 3x3) / pos, else its dynamic slot (setSlots).
  /// Items are given in the NumPy caster's item order (static ones first).
  void setItems(const std::vector<int>& code, const std::vector<int64_t>& shape,
                const std::vector<double>& p, const std::vector<int>& slot,
                const std::vector<double>& rot, const std::vector<double>& pos);
  /// Planes: unit local normals (3 per plane), posed like the items.
  void setPlanes(const std::vector<int64_t>& shape, const std::vector<double>& local_normal,
                 const std::vector<int>& slot, const std::vector<double>& rot,
                 const std::vector<double>& pos);
  /// bvh.py's BVHForest after freeze(): per node lo, hi (3 each), first, count, leaf; per
  /// triangle v0, e1, e2 (3 each) and the shape it belongs to.
  void setForest(const std::vector<double>& lo, const std::vector<double>& hi,
                 const std::vector<int64_t>& first, const std::vector<int64_t>& count,
                 const std::vector<uint8_t>& leaf, const std::vector<double>& v0,
                 const std::vector<double>& e1, const std::vector<double>& e2,
                 const std::vector<int64_t>& owner);
  /// The hierarchy of all static meshes (world frame), -1 for none; dynamic meshes: their
  /// shape, root and slot (each in its own frame).
  void setMeshes(int64_t static_root, const std::vector<int64_t>& shape,
                 const std::vector<int64_t>& root, const std::vector<int>& slot);
  /// The dynamic slots' poses relative to their link rows (rayprims.Posing): slot j is
  /// posed as link row[j] (given to cast()) times local_rot[j] / local_pos[j]; `links` rows.
  void setSlots(const std::vector<int64_t>& row, const std::vector<double>& local_rot,
                const std::vector<double>& local_pos, int64_t links);
  /// Number of dynamic slots the shapes refer to, and of link rows cast() needs.
  int dynamicSlots() const { return nslots_; }
  int64_t linkRows() const { return nlinks_; }
  /// Whether every slot the shapes refer to has its row (setSlots after the shapes).
  bool ready() const { return static_cast<int64_t>(slot_row_.size()) >= nslots_; }
  /// Number of shapes (the length of cast()'s excluded flags).
  int64_t shapes() const { return nshapes_; }

  /// n rays: origins o and unit directions d (3 per ray; `common`: all origins equal, the
  /// first row is used), nearest hit with tmin <= t < max_range. link_q / link_p: the link
  /// rows' world poses now (unit quaternion x y z w, position); excluded: one flag per
  /// shape, or nullptr. Writes t (inf for none) and the shape index hit (-1 for none). Const
  /// and self-contained: safe to run without the GIL.
  void cast(const double* o, const double* d, int64_t n, bool common, double tmin, double max_range,
            const double* link_q, const double* link_p, const uint8_t* excluded, double* t_out,
            int64_t* who_out) const;

 private:
  struct Item {
    int code;
    int64_t shape;
    int slot;
    double p[3];
    double rot[9];
    double pos[3];
    double lo[3], hi[3];  // padded world bounds
  };
  struct Plane {
    int64_t shape;
    int slot;
    double local[3];
    double n[3];
    double offset;
  };
  struct DynMesh {
    int64_t shape, root;
    int slot;
  };
  void checkShape(int64_t shape) const;
  static void poseItem(Item& it, const double* rot, const double* pos);
  static void posePlane(Plane& pl, const double* rot, const double* pos);
  void walk(int64_t root, const double o[3], const double d[3], const double inv[3], double tmin,
            const uint8_t* excluded, double& best, int64_t& who) const;

  std::vector<Item> items_;
  std::vector<int> group_order_;  // boxes, spheres, cylinders by shape index (dense path)
  std::vector<Plane> planes_;
  std::vector<double> lo_, hi_, v0_, e1_, e2_;
  std::vector<int64_t> first_, count_, owner_;
  std::vector<uint8_t> leaf_;
  int64_t static_root_ = -1;
  std::vector<DynMesh> dyn_meshes_;
  int nslots_ = 0;
  int64_t nlinks_ = 0;
  std::vector<int64_t> slot_row_;
  std::vector<double> slot_rot_, slot_pos_;  // the slots' poses in their rows' frames
  int64_t nshapes_;
};

}  // namespace ode_sim
