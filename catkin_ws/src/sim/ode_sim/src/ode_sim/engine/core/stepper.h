// The compiled step loop of ode_sim's PhysicsWorld (engine/physics.py): collision with the
// near callback and Gazebo's surface parameters, contact joints, (quick)step, auto-disable of
// resting models, the per-step work of commanded joints, and batched read-back. It works on
// the ODE objects PhysicsWorld built (raw ids of the same libode), and reproduces the Python
// step loop operation for operation so the two give the same trajectories.
#pragma once

#include <ode/ode.h>

#include <cstdint>
#include <deque>
#include <unordered_map>
#include <unordered_set>
#include <vector>

namespace ode_sim {

struct Surface {
  double mu1, mu2, kp, kd;
  bool has_fdir;
  double fdir[3];
  double bounce, bounce_vel;
  dBodyID body;  // the geom's body, nullptr for static or welded geoms
};

struct ActiveJoint {
  dJointID id;
  bool hinge;  // else slider
  bool has_pos_cmd;
  double pos_cmd;
  double effort_cmd;
  double damping;
  double vmax;     // <= 0: no velocity limit
  double fmax;     // servo force limit
  double applied;  // effort added this step (out)
};

// One contact point of a watched geom (a contact sensor's collision) in one step: `mine` is the
// watched geom, the normal points so that moving `mine` along it by `depth` separates the two
// (ODE's convention with `mine` as the first geom), force and torque act on mine's body (torque
// about its centre of mass; for a static watched geom, minus the force on the other body).
struct ContactRecord {
  int64_t step;  // the step count after the step that made the contact
  dGeomID mine, other;
  double pos[3], normal[3], depth, force[3], torque[3];
};

class Stepper {
 public:
  Stepper(dWorldID world, dSpaceID static_space);
  ~Stepper();
  Stepper(const Stepper&) = delete;
  Stepper& operator=(const Stepper&) = delete;

  void setStep(double dt, bool use_step, int max_contacts);
  void addGeom(dGeomID g, const Surface& s) { surf_[g] = s; }
  void removeGeom(dGeomID g) { surf_.erase(g); }
  void addSpace(dSpaceID sp, const std::vector<dBodyID>& bodies, bool self_collide);
  void removeSpace(dSpaceID sp);
  void rouse(dSpaceID sp);
  bool awake(dSpaceID sp) const;
  void setJoints(const std::vector<ActiveJoint>& joints) { active_ = joints; }
  const std::vector<ActiveJoint>& joints() const { return active_; }
  void setTracked(const std::vector<dBodyID>& bodies);
  const std::vector<double>& accels() const { return accel_; }  // 3 per tracked body
  /// n steps; `steps` is the step count before them (sleepers are sorted every 100 steps)
  void step(int n, int64_t steps);
  int64_t contacts() const { return contacts_; }
  /// geoms whose contacts are recorded (contact sensors); an empty set records nothing
  void setWatched(const std::vector<dGeomID>& geoms);
  /// the records of the steps since the last call (at most kMaxContactSteps steps with
  /// contacts, the oldest dropped first, as Gazebo's contact sensor keeps 100 messages)
  std::vector<ContactRecord> takeContacts();
  static constexpr size_t kMaxContactSteps = 100;

  static void nearCallback(void* data, dGeomID g1, dGeomID g2);

 private:
  void near(dGeomID g1, dGeomID g2);
  // dSpaceCollide2(a, b) with the same pairs in the same order, skipped when the two spaces'
  // bounding boxes are disjoint: then no pair of their geoms can pass ODE's AABB test
  void collideSpaces(dSpaceID a, dSpaceID b);
  // dSpaceCollide2(sp, static_) with the same pairs in the same order, but only against the
  // static geoms whose bounding box meets sp's (ODE's collide2 tests every static geom
  // against every geom of sp); the static boxes are read once per step (readStatic)
  void collideStatic(dSpaceID sp);
  void readStatic();
  void preStep(ActiveJoint& j);
  void sortSleepers();
  bool anyEnabled(dSpaceID sp) const;
  void moveTo(std::vector<dSpaceID>& from, std::vector<dSpaceID>& to, dSpaceID sp);
  void watch(dGeomID mine, dGeomID other, const dContactGeom& g, bool mine_first, dJointID j);
  void finishStepContacts(int64_t step);

  dWorldID world_;
  dSpaceID static_;
  dJointGroupID group_;
  double dt_ = 0.001;
  bool use_step_ = false;
  int max_contacts_ = 20;
  int64_t contacts_ = 0;
  std::unordered_map<dGeomID, Surface> surf_;
  std::unordered_map<dSpaceID, std::vector<dBodyID>> space_bodies_;
  std::vector<dSpaceID> awake_, dormant_, self_collide_, wake_;
  std::vector<ActiveJoint> active_;
  std::vector<dBodyID> tracked_;
  std::vector<double> prev_vel_, accel_;
  std::vector<dContactGeom> buf_;
  struct StaticGeom {
    dGeomID id;
    bool enabled;
    dReal box[6];
  };
  std::vector<StaticGeom> static_geoms_;  // this step's static geoms (readStatic)
  std::vector<const StaticGeom*> near_static_;
  bool static_nested_ = false;  // a space inside static_: plain dSpaceCollide2
  // contact sensors: the watched geoms, this step's points (their joints' feedback lives in
  // feedback_, whose elements keep their addresses), and the finished steps' records
  struct Pending {
    ContactRecord rec;
    dBodyID body;  // mine's body (nullptr: static)
    dJointID joint;
    size_t fb;  // index into feedback_
  };
  std::unordered_set<dGeomID> watched_;
  std::vector<Pending> pending_;
  std::deque<dJointFeedback> feedback_;  // one per watched contact joint of this step
  std::deque<std::vector<ContactRecord>> steps_with_contacts_;
};

}  // namespace ode_sim
