// The compiled step loop of ode_sim's PhysicsWorld (engine/physics.py): collision with the
// near callback and Gazebo's surface parameters, contact joints, (quick)step, auto-disable of
// resting models, the per-step work of commanded joints, and batched read-back. It works on
// the ODE objects PhysicsWorld built (raw ids of the same libode), and reproduces the Python
// step loop operation for operation so the two give the same trajectories.
#pragma once

#include <ode/ode.h>

#include <cstdint>
#include <unordered_map>
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
  bool hinge;          // else slider
  bool has_pos_cmd;
  double pos_cmd;
  double effort_cmd;
  double damping;
  double vmax;         // <= 0: no velocity limit
  double fmax;         // servo force limit
  double applied;      // effort added this step (out)
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

  static void nearCallback(void* data, dGeomID g1, dGeomID g2);

 private:
  void near(dGeomID g1, dGeomID g2);
  void preStep(ActiveJoint& j);
  void sortSleepers();
  bool anyEnabled(dSpaceID sp) const;
  void moveTo(std::vector<dSpaceID>& from, std::vector<dSpaceID>& to, dSpaceID sp);

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
};

}  // namespace ode_sim
