// pybind11 module ode_sim.engine._core: the Stepper over raw ODE ids (integers) that
// engine/compiled.py takes from the PyODE objects PhysicsWorld built, and the RayScene of the
// lidar's ray casting (engine/raycore.py), and the Fanout that sends /clock's frames
// (ros/plugins/rosio.py).
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <system_error>
#include <vector>
#include <tuple>

#include "fanout.h"
#include "meshimport.h"
#include "raycast.h"
#include "stepper.h"
#include "trimesh.h"

namespace py = pybind11;
using ode_sim::ActiveJoint;
using ode_sim::Fanout;
using ode_sim::RayScene;
using ode_sim::Stepper;
using ode_sim::Surface;
using ode_sim::TriMesh;

namespace {

template <typename T>
T as(uintptr_t v) {
  return reinterpret_cast<T>(v);
}

template <typename T>
uintptr_t num(T p) {
  return reinterpret_cast<uintptr_t>(p);
}

std::vector<dBodyID> bodies(const std::vector<uintptr_t>& ids) {
  std::vector<dBodyID> out;
  out.reserve(ids.size());
  for (auto v : ids) out.push_back(as<dBodyID>(v));
  return out;
}

template <typename T>
using CArray = py::array_t<T, py::array::c_style | py::array::forcecast>;

// a C-ordered array's elements, checked to number `n` (n < 0: any)
template <typename T>
std::vector<T> flat(const CArray<T>& a, py::ssize_t n, const char* what) {
  if (n >= 0 && a.size() != n)
    throw std::invalid_argument(std::string("RayScene: ") + what + ": expected " +
                                std::to_string(n) + " values, got " + std::to_string(a.size()));
  return std::vector<T>(a.data(), a.data() + a.size());
}

using JointTuple = std::tuple<uintptr_t, bool, std::optional<double>, double, double,
                              std::optional<double>, double>;

using Vec3 = std::tuple<double, double, double>;
using Quat = std::tuple<double, double, double, double>;

// a geom's pose: relative to its body (offset) or in the world
void placeGeom(uintptr_t g, const Vec3& p, const Quat& q, bool offset) {
  dGeomID id = as<dGeomID>(g);
  dQuaternion qq = {std::get<0>(q), std::get<1>(q), std::get<2>(q), std::get<3>(q)};
  if (offset) {
    dGeomSetOffsetPosition(id, std::get<0>(p), std::get<1>(p), std::get<2>(p));
    dGeomSetOffsetQuaternion(id, qq);
  } else {
    dGeomSetPosition(id, std::get<0>(p), std::get<1>(p), std::get<2>(p));
    dGeomSetQuaternion(id, qq);
  }
}

// assimp mesh import
void bind_mesh_import(py::module& m) {
  // mesh files through assimp (description/mesh.py): a list of mesh instances (node and mesh
  // name, material index, positions (N,3) float64, normals (N,3) float32, uvs (N,2) float32 or
  // None, faces (M,3) int32) and a list of materials (dicts); RuntimeError: assimp's reason
  m.def(
      "import_mesh",
      [](const std::string& path) {
        ode_sim::ImportedScene sc;
        {
          py::gil_scoped_release release;
          sc = ode_sim::importScene(path);
        }
        py::list meshes, mats;
        for (auto& im : sc.meshes) {
          const py::ssize_t n = static_cast<py::ssize_t>(im.positions.size() / 3);
          const py::ssize_t f = static_cast<py::ssize_t>(im.faces.size() / 3);
          py::array_t<double> pos({n, py::ssize_t(3)});
          std::copy(im.positions.begin(), im.positions.end(), pos.mutable_data());
          py::array_t<float> nrm({n, py::ssize_t(3)});
          std::copy(im.normals.begin(), im.normals.end(), nrm.mutable_data());
          py::array_t<int32_t> faces({f, py::ssize_t(3)});
          std::copy(im.faces.begin(), im.faces.end(), faces.mutable_data());
          py::object uv = py::none();
          if (!im.uvs.empty()) {
            py::array_t<float> a({n, py::ssize_t(2)});
            std::copy(im.uvs.begin(), im.uvs.end(), a.mutable_data());
            uv = a;
          }
          meshes.append(py::make_tuple(im.node, im.name, im.material, pos, nrm, uv, faces));
        }
        for (auto& m : sc.materials) {
          py::dict d;
          d["name"] = m.name;
          d["diffuse"] = m.has_diffuse ? py::cast(m.diffuse) : py::none();
          d["ambient"] = m.has_ambient ? py::cast(m.ambient) : py::none();
          d["emissive"] = m.has_emissive ? py::cast(m.emissive) : py::none();
          d["specular"] = m.has_specular ? py::cast(m.specular) : py::none();
          d["opacity"] = m.opacity;
          d["shininess"] = m.shininess;
          d["texture"] = m.texture;
          mats.append(d);
        }
        return py::make_tuple(meshes, mats);
      },
      py::arg("path"));
}

// ODE ids, trimesh geoms, the collision probe and TriMesh
void bind_geoms(py::module& m) {
  m.def("body_world", [](uintptr_t b) { return num(dBodyGetWorld(as<dBodyID>(b))); });
  m.def("geom_body", [](uintptr_t g) { return num(dGeomGetBody(as<dGeomID>(g))); });
  m.def("body_joint", [](uintptr_t b, int i) { return num(dBodyGetJoint(as<dBodyID>(b), i)); });
  // ODE's quickStep reorders constraints with its one global random generator: two worlds
  // compared step by step must each start from the same seed
  m.def("set_random_seed", [](unsigned long seed) { dRandSetSeed(seed); });
  // trimesh geoms (engine/compiled.py TriMeshGeom): PyODE 1.2 on Debian has no trimesh, so
  // these geoms are made and placed here, by id
  m.def("geom_set_body",
        [](uintptr_t g, uintptr_t b) { dGeomSetBody(as<dGeomID>(g), as<dBodyID>(b)); });
  m.def(
      "geom_set_offset", [](uintptr_t g, Vec3 p, Quat q) { placeGeom(g, p, q, true); },
      py::arg("geom"), py::arg("position"), py::arg("quaternion_wxyz"));
  m.def(
      "geom_set_pose", [](uintptr_t g, Vec3 p, Quat q) { placeGeom(g, p, q, false); },
      py::arg("geom"), py::arg("position"), py::arg("quaternion_wxyz"));
  m.def("geom_pose", [](uintptr_t g) {
    dGeomID id = as<dGeomID>(g);
    const dReal* p = dGeomGetPosition(id);
    dQuaternion q;
    dGeomGetQuaternion(id, q);
    return py::make_tuple(py::make_tuple(p[0], p[1], p[2]), py::make_tuple(q[0], q[1], q[2], q[3]));
  });
  m.def("geom_space", [](uintptr_t g) { return num(dGeomGetSpace(as<dGeomID>(g))); });
  m.def("geom_aabb", [](uintptr_t g) {
    dReal a[6];
    dGeomGetAABB(as<dGeomID>(g), a);
    return py::make_tuple(a[0], a[1], a[2], a[3], a[4], a[5]);
  });
  m.def("geom_destroy", [](uintptr_t g) { dGeomDestroy(as<dGeomID>(g)); });
  m.def("is_trimesh", [](uintptr_t g) { return dGeomGetClass(as<dGeomID>(g)) == dTriMeshClass; });
  // (a depth probe for tests: contacts of two geoms, as the near callback sees them)
  m.def("collide", [](uintptr_t g1, uintptr_t g2, int max) {
    std::vector<dContactGeom> buf(std::max(1, max));
    ode_sim::ensureThreadData();
    int n = dCollide(as<dGeomID>(g1), as<dGeomID>(g2), static_cast<int>(buf.size()), buf.data(),
                     sizeof(dContactGeom));
    py::list out;
    for (int i = 0; i < n; ++i)
      out.append(py::make_tuple(
          py::make_tuple(buf[i].pos[0], buf[i].pos[1], buf[i].pos[2]),
          py::make_tuple(buf[i].normal[0], buf[i].normal[1], buf[i].normal[2]), buf[i].depth));
    return out;
  });

  py::class_<TriMesh>(m, "TriMesh", "a loaded mesh's triangles as ODE trimesh data")
      .def(py::init([](const CArray<double>& v, const CArray<int64_t>& f) {
             if (v.ndim() != 2 || v.shape(1) != 3)
               throw std::invalid_argument("TriMesh: vertices must be (N, 3)");
             if (f.ndim() != 2 || f.shape(1) != 3)
               throw std::invalid_argument("TriMesh: faces must be (M, 3)");
             return new TriMesh(std::vector<double>(v.data(), v.data() + v.size()),
                                std::vector<int64_t>(f.data(), f.data() + f.size()));
           }),
           py::arg("vertices"), py::arg("faces"))
      .def_property_readonly("triangles", &TriMesh::triangles)
      .def(
          "create",
          [](const TriMesh& t, uintptr_t space) { return num(t.create(as<dSpaceID>(space))); },
          py::arg("space"));
  m.def("ode_config", []() { return std::string(dGetConfiguration()); });
}

// the step loop: set-up, geoms, spaces (bind_stepper_state: joints, tracking, contacts)
py::class_<Stepper> bind_stepper(py::module& m) {
  auto stepper =
      py::class_<Stepper>(m, "Stepper")
          .def(py::init([](uintptr_t world, uintptr_t static_space) {
            return new Stepper(as<dWorldID>(world), as<dSpaceID>(static_space));
          }))
          .def("set_step", &Stepper::setStep, py::arg("dt"), py::arg("use_step"),
               py::arg("max_contacts"))
          .def("add_geom",
               [](Stepper& s, uintptr_t g, uintptr_t body, double mu1, double mu2, double kp,
                  double kd, std::optional<std::tuple<double, double, double>> fdir, double bounce,
                  double bounce_vel) {
                 Surface su{
                     mu1, mu2, kp, kd, false, {0, 0, 0}, bounce, bounce_vel, as<dBodyID>(body)};
                 if (fdir) {
                   su.has_fdir = true;
                   su.fdir[0] = std::get<0>(*fdir);
                   su.fdir[1] = std::get<1>(*fdir);
                   su.fdir[2] = std::get<2>(*fdir);
                 }
                 s.addGeom(as<dGeomID>(g), su);
               })
          .def("remove_geom", [](Stepper& s, uintptr_t g) { s.removeGeom(as<dGeomID>(g)); })
          .def("add_space",
               [](Stepper& s, uintptr_t sp, const std::vector<uintptr_t>& b, bool self_collide) {
                 s.addSpace(as<dSpaceID>(sp), bodies(b), self_collide);
               })
          .def("remove_space", [](Stepper& s, uintptr_t sp) { s.removeSpace(as<dSpaceID>(sp)); })
          .def("rouse", [](Stepper& s, uintptr_t sp) { s.rouse(as<dSpaceID>(sp)); })
          .def("awake", [](const Stepper& s, uintptr_t sp) { return s.awake(as<dSpaceID>(sp)); });
  return stepper;
}

// the step loop: joint commands, tracked links, contacts, body reads
void bind_stepper_state(py::class_<Stepper>& stepper) {
  stepper
      .def("set_joints",
           [](Stepper& s, const std::vector<JointTuple>& joints) {
             std::vector<ActiveJoint> out;
             out.reserve(joints.size());
             for (const auto& t : joints) {
               ActiveJoint j{};
               j.id = as<dJointID>(std::get<0>(t));
               j.hinge = std::get<1>(t);
               j.has_pos_cmd = std::get<2>(t).has_value();
               j.pos_cmd = j.has_pos_cmd ? *std::get<2>(t) : 0.0;
               j.effort_cmd = std::get<3>(t);
               j.damping = std::get<4>(t);
               j.vmax = std::get<5>(t).value_or(0.0);
               j.fmax = std::get<6>(t);
               out.push_back(j);
             }
             s.setJoints(out);
           })
      .def("applied",
           [](const Stepper& s) {
             std::vector<double> out;
             for (const auto& j : s.joints()) out.push_back(j.applied);
             return out;
           })
      .def("set_tracked",
           [](Stepper& s, const std::vector<uintptr_t>& b) { s.setTracked(bodies(b)); })
      .def("accels",
           [](const Stepper& s) {
             const auto& a = s.accels();
             py::array_t<double> out({static_cast<py::ssize_t>(a.size() / 3), py::ssize_t{3}});
             std::copy(a.begin(), a.end(), out.mutable_data());
             return out;
           })
      .def(
          "step",
          [](Stepper& s, int n, int64_t steps) {
            py::gil_scoped_release release;
            s.step(n, steps);
          },
          py::arg("n"), py::arg("steps"))
      .def("contacts", &Stepper::contacts)
      .def("set_watched",
           [](Stepper& s, const std::vector<uintptr_t>& ids) {
             std::vector<dGeomID> g;
             for (auto v : ids) g.push_back(as<dGeomID>(v));
             s.setWatched(g);
           })
      .def("take_contacts",
           [](Stepper& s) {
             // (steps int64 (N,), geom ids uint64 (N, 2): mine, other, values (N, 13):
             // position, normal, depth, force, torque)
             std::vector<ode_sim::ContactRecord> recs = s.takeContacts();
             const auto n = static_cast<py::ssize_t>(recs.size());
             py::array_t<int64_t> steps(n);
             py::array_t<uint64_t> ids({n, py::ssize_t{2}});
             py::array_t<double> vals({n, py::ssize_t{13}});
             auto* st = steps.mutable_data();
             auto* id = ids.mutable_data();
             auto* v = vals.mutable_data();
             for (const auto& r : recs) {
               *st++ = r.step;
               *id++ = num(r.mine);
               *id++ = num(r.other);
               for (double x : r.pos) *v++ = x;
               for (double x : r.normal) *v++ = x;
               *v++ = r.depth;
               for (double x : r.force) *v++ = x;
               for (double x : r.torque) *v++ = x;
             }
             return py::make_tuple(steps, ids, vals);
           })
      .def("read_bodies", [](const Stepper&, const std::vector<uintptr_t>& ids) {
        // one row per body: position (3), quaternion x y z w (4), linear (3), angular (3) velocity
        py::array_t<double> out({static_cast<py::ssize_t>(ids.size()), py::ssize_t{13}});
        double* o = out.mutable_data();
        for (auto v : ids) {
          dBodyID b = as<dBodyID>(v);
          const dReal* p = dBodyGetPosition(b);
          const dReal* q = dBodyGetQuaternion(b);
          const dReal* l = dBodyGetLinearVel(b);
          const dReal* a = dBodyGetAngularVel(b);
          double row[13] = {p[0], p[1], p[2], q[1], q[2], q[3], q[0],
                            l[0], l[1], l[2], a[0], a[1], a[2]};
          std::copy(row, row + 13, o);
          o += 13;
        }
        return out;
      });
}

// the compiled ray caster
void bind_ray_scene(py::module& m) {
  py::class_<RayScene>(m, "RayScene",
                       "The shapes of a RayCaster (engine/raycore.py) in the compiled core")
      .def(py::init<int64_t>(), py::arg("shapes"))
      .def("set_items",
           [](RayScene& r, const CArray<int>& code, const CArray<int64_t>& shape,
              const CArray<double>& p, const CArray<int>& slot, const CArray<double>& rot,
              const CArray<double>& pos) {
             const py::ssize_t k = code.size();
             r.setItems(flat(code, k, "item codes"), flat(shape, k, "item shapes"),
                        flat(p, 3 * k, "item parameters"), flat(slot, k, "item slots"),
                        flat(rot, 9 * k, "item rotations"), flat(pos, 3 * k, "item positions"));
           })
      .def("set_planes",
           [](RayScene& r, const CArray<int64_t>& shape, const CArray<double>& normal,
              const CArray<int>& slot, const CArray<double>& rot, const CArray<double>& pos) {
             const py::ssize_t k = shape.size();
             r.setPlanes(flat(shape, k, "plane shapes"), flat(normal, 3 * k, "plane normals"),
                         flat(slot, k, "plane slots"), flat(rot, 9 * k, "plane rotations"),
                         flat(pos, 3 * k, "plane positions"));
           })
      .def("set_forest",
           [](RayScene& r, const CArray<double>& lo, const CArray<double>& hi,
              const CArray<int64_t>& first, const CArray<int64_t>& count,
              const CArray<uint8_t>& leaf, const CArray<double>& v0, const CArray<double>& e1,
              const CArray<double>& e2, const CArray<int64_t>& owner) {
             const py::ssize_t m = first.size(), t = owner.size();
             r.setForest(flat(lo, 3 * m, "node lo"), flat(hi, 3 * m, "node hi"),
                         flat(first, m, "node first"), flat(count, m, "node count"),
                         flat(leaf, m, "node leaf"), flat(v0, 3 * t, "triangle v0"),
                         flat(e1, 3 * t, "triangle e1"), flat(e2, 3 * t, "triangle e2"),
                         flat(owner, t, "triangle owner"));
           })
      .def("set_meshes",
           [](RayScene& r, int64_t static_root, const CArray<int64_t>& shape,
              const CArray<int64_t>& root, const CArray<int>& slot) {
             const py::ssize_t k = shape.size();
             r.setMeshes(static_root, flat(shape, k, "mesh shapes"), flat(root, k, "mesh roots"),
                         flat(slot, k, "mesh slots"));
           })
      .def_property_readonly("shapes", &RayScene::shapes)
      .def("set_slots",
           [](RayScene& r, const CArray<int64_t>& row, const CArray<double>& local_rot,
              const CArray<double>& local_pos, int64_t links) {
             const py::ssize_t k = row.size();
             r.setSlots(flat(row, k, "slot rows"), flat(local_rot, 9 * k, "slot rotations"),
                        flat(local_pos, 3 * k, "slot positions"), links);
           })
      .def_property_readonly("dynamic_slots", &RayScene::dynamicSlots)
      .def_property_readonly("link_rows", &RayScene::linkRows)
      .def(
          "cast",
          [](const RayScene& r, const CArray<double>& o, const CArray<double>& d, bool common,
             double tmin, double max_range, const CArray<double>& link_q,
             const CArray<double>& link_p, std::optional<CArray<uint8_t>> excluded) {
            if (d.ndim() != 2 || d.shape(1) != 3)
              throw std::invalid_argument("RayScene.cast: directions must be (N, 3)");
            const py::ssize_t n = d.shape(0);
            if (common ? o.size() < 3 : o.size() != 3 * n)
              throw std::invalid_argument("RayScene.cast: origins must be (3,) or (N, 3)");
            if (!r.ready())
              throw std::invalid_argument(
                  "RayScene.cast: the dynamic slots have no link rows "
                  "(set_slots)");
            const py::ssize_t links = r.linkRows();
            if (link_q.size() != 4 * links || link_p.size() != 3 * links)
              throw std::invalid_argument("RayScene.cast: expected the poses of " +
                                          std::to_string(links) + " link rows");
            if (excluded && excluded->size() != r.shapes())
              throw std::invalid_argument("RayScene.cast: excluded needs one flag per shape");
            py::array_t<double> t(n);
            py::array_t<int64_t> who(n);
            double* tp = t.mutable_data();
            int64_t* wp = who.mutable_data();
            const uint8_t* ex = excluded ? excluded->data() : nullptr;
            {
              py::gil_scoped_release release;
              r.cast(o.data(), d.data(), n, common, tmin, max_range, link_q.data(), link_p.data(),
                     ex, tp, wp);
            }
            return py::make_tuple(t, who);
          },
          py::arg("origins"), py::arg("directions"), py::arg("common"), py::arg("tmin"),
          py::arg("max_range"), py::arg("link_q"), py::arg("link_p"),
          py::arg("excluded") = py::none());
}

void bind_fanout(py::module& m) {
  py::class_<Fanout>(m, "Fanout",
                     "The newest of a stream of small frames, sent to stream sockets by a "
                     "thread of its own (engine/core/fanout.h).")
      .def(py::init<>())
      .def(
          "add",
          [](Fanout& f, int fd) {
            const int handle = f.Add(fd);
            if (handle < 0) throw std::system_error(errno, std::generic_category(), "dup");
            return handle;
          },
          py::arg("fd"), "Send later frames to (a duplicate of) the socket fd; a handle.")
      .def("remove", &Fanout::Remove, py::arg("handle"))
      .def(
          "publish", [](Fanout& f, py::bytes frame) { f.Publish(std::string(frame)); },
          py::arg("frame"))
      .def("take_dead", &Fanout::TakeDead,
           "Handles whose socket failed since the last call (removed).")
      .def("flush", &Fanout::Flush, py::call_guard<py::gil_scoped_release>())
      .def("close", &Fanout::Close, py::call_guard<py::gil_scoped_release>())
      .def_property_readonly("sent", &Fanout::sent)
      .def_property_readonly("dropped", &Fanout::dropped)
      .def("__len__", &Fanout::size);
}

}  // namespace

PYBIND11_MODULE(_core, m) {
  m.doc() = "ode_sim's compiled step loop on libode (see engine/core/stepper.h)";
  bind_mesh_import(m);
  bind_geoms(m);
  py::class_<Stepper> stepper = bind_stepper(m);
  bind_stepper_state(stepper);
  bind_ray_scene(m);
  bind_fanout(m);
}
