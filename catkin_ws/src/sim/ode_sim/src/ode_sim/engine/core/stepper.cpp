#include "stepper.h"

#include "trimesh.h"

#include <algorithm>
#include <cmath>

namespace ode_sim {

namespace {
// As many contact points as PyODE's ode.collide() asks for: the first max_contacts of them are
// kept, so box-box culling is the same as on the Python path.
constexpr int kCollideMax = 150;
// PyODE 1.2's ContactApprox1 (0x3000): the friction pyramid on both directions.
constexpr int kApprox1 = dContactApprox1_1 | dContactApprox1_2;

// ODE's own AABB overlap test (collideAABBs): boxes are (minx, maxx, miny, maxy, minz, maxz)
bool disjoint(const dReal* a, const dReal* b) {
  return a[0] > b[1] || a[1] < b[0] || a[2] > b[3] || a[3] < b[2] || a[4] > b[5] || a[5] < b[4];
}

dGeomID asGeom(dSpaceID sp) { return reinterpret_cast<dGeomID>(sp); }
}  // namespace

Stepper::Stepper(dWorldID world, dSpaceID static_space)
    : world_(world), static_(static_space), group_(dJointGroupCreate(0)), buf_(kCollideMax) {}

Stepper::~Stepper() {
  dJointGroupEmpty(group_);
  dJointGroupDestroy(group_);
}

void Stepper::setStep(double dt, bool use_step, int max_contacts) {
  dt_ = dt;
  use_step_ = use_step;
  max_contacts_ = std::max(1, max_contacts);
}

void Stepper::addSpace(dSpaceID sp, const std::vector<dBodyID>& bodies, bool self_collide) {
  space_bodies_[sp] = bodies;
  awake_.push_back(sp);
  if (self_collide) self_collide_.push_back(sp);
}

void Stepper::removeSpace(dSpaceID sp) {
  space_bodies_.erase(sp);
  for (auto* v : {&awake_, &dormant_, &self_collide_, &wake_})
    v->erase(std::remove(v->begin(), v->end(), sp), v->end());
}

void Stepper::moveTo(std::vector<dSpaceID>& from, std::vector<dSpaceID>& to, dSpaceID sp) {
  from.erase(std::remove(from.begin(), from.end(), sp), from.end());
  to.push_back(sp);
}

void Stepper::rouse(dSpaceID sp) {
  if (std::find(dormant_.begin(), dormant_.end(), sp) == dormant_.end()) return;
  moveTo(dormant_, awake_, sp);
  for (dBodyID b : space_bodies_[sp]) dBodyEnable(b);
}

bool Stepper::awake(dSpaceID sp) const {
  return std::find(awake_.begin(), awake_.end(), sp) != awake_.end();
}

void Stepper::setTracked(const std::vector<dBodyID>& bodies) {
  tracked_ = bodies;
  prev_vel_.assign(3 * bodies.size(), 0.0);
  accel_.assign(3 * bodies.size(), 0.0);
  for (size_t i = 0; i < bodies.size(); ++i) {
    const dReal* v = dBodyGetLinearVel(bodies[i]);
    for (int k = 0; k < 3; ++k) prev_vel_[3 * i + k] = v[k];
  }
}

void Stepper::nearCallback(void* data, dGeomID g1, dGeomID g2) {
  static_cast<Stepper*>(data)->near(g1, g2);
}

void Stepper::near(dGeomID g1, dGeomID g2) {
  if (dGeomIsSpace(g1) || dGeomIsSpace(g2)) {
    dSpaceCollide2(g1, g2, this, &Stepper::nearCallback);
    return;
  }
  auto i1 = surf_.find(g1);
  auto i2 = surf_.find(g2);
  if (i1 == surf_.end() || i2 == surf_.end()) return;
  const Surface& s1 = i1->second;
  const Surface& s2 = i2->second;
  dBodyID b1 = s1.body, b2 = s2.body;
  if (b1 == b2) return;  // one body, or two bodiless (static, welded) geoms
  if (b1 && b2 && dAreConnected(b1, b2)) return;
  int n = dCollide(g1, g2, kCollideMax, buf_.data(), sizeof(dContactGeom));
  if (n <= 0) return;
  const double kp = 1.0 / (1.0 / s1.kp + 1.0 / s2.kp);
  const double kd = s1.kd + s2.kd;
  const double denom = dt_ * kp + kd;
  const double erp = dt_ * kp / denom;
  const double cfm = 1.0 / denom;
  const double mu1 = std::min(s1.mu1, s2.mu1);
  const double mu2 = std::min(s1.mu2, s2.mu2);
  const bool fdir = s1.has_fdir || s2.has_fdir;
  const double bounce = std::max(s1.bounce, s2.bounce);
  int mode = dContactSoftERP | dContactSoftCFM | kApprox1 | dContactMu2;
  if (fdir) mode |= dContactFDir1;
  if (bounce > 0) mode |= dContactBounce;
  dVector3 dir = {0, 0, 0, 0};
  if (fdir) {
    const Surface& s = s1.has_fdir ? s1 : s2;
    dBodyID body = s1.has_fdir ? b1 : b2;
    if (body) {
      dBodyVectorToWorld(body, s.fdir[0], s.fdir[1], s.fdir[2], dir);
    } else {
      dir[0] = s.fdir[0];
      dir[1] = s.fdir[1];
      dir[2] = s.fdir[2];
    }
  }
  n = std::min(n, max_contacts_);
  for (int i = 0; i < n; ++i) {
    dContact c{};
    c.geom = buf_[i];
    c.surface.mode = mode;
    c.surface.mu = mu1 < 1e30 ? mu1 : dInfinity;
    c.surface.mu2 = mu2 < 1e30 ? mu2 : dInfinity;
    c.surface.soft_erp = erp;
    c.surface.soft_cfm = cfm;
    if (fdir) {
      c.fdir1[0] = dir[0];
      c.fdir1[1] = dir[1];
      c.fdir1[2] = dir[2];
    }
    if (bounce > 0) {
      c.surface.bounce = bounce;
      c.surface.bounce_vel = std::min(s1.bounce_vel, s2.bounce_vel);
    } else {
      c.surface.bounce = 0.1;  // PyODE's Contact default (unused without dContactBounce)
    }
    dJointID j = dJointCreateContact(world_, group_, &c);
    dJointAttach(j, b1, b2);
    if (!watched_.empty()) {
      const bool w1 = watched_.count(g1) > 0, w2 = watched_.count(g2) > 0;
      if (w1 || w2) {
        feedback_.emplace_back();
        dJointSetFeedback(j, &feedback_.back());
        if (w1) watch(g1, g2, buf_[i], true, j);
        if (w2) watch(g2, g1, buf_[i], false, j);
      }
    }
  }
  ++contacts_;
}

void Stepper::setWatched(const std::vector<dGeomID>& geoms) {
  watched_ = std::unordered_set<dGeomID>(geoms.begin(), geoms.end());
  if (watched_.empty()) steps_with_contacts_.clear();
}

void Stepper::watch(dGeomID mine, dGeomID other, const dContactGeom& g, bool mine_first,
                    dJointID j) {
  Pending p{};
  p.rec.mine = mine;
  p.rec.other = other;
  const double sign = mine_first ? 1.0 : -1.0;  // ODE's normal is for (g1, g2)
  for (int k = 0; k < 3; ++k) {
    p.rec.pos[k] = g.pos[k];
    p.rec.normal[k] = sign * g.normal[k];
  }
  p.rec.depth = g.depth;
  p.body = dGeomGetBody(mine);
  p.joint = j;
  p.fb = feedback_.size() - 1;  // the joint's feedback, allocated by near()
  pending_.push_back(p);
}

void Stepper::finishStepContacts(int64_t step) {
  std::vector<ContactRecord> recs;
  recs.reserve(pending_.size());
  for (Pending& p : pending_) {
    const dJointFeedback& f = feedback_[p.fb];
    ContactRecord r = p.rec;
    r.step = step;
    // ODE fills f1/t1 for the joint's first body: after dJointAttach(j, 0, b) that is b
    const dReal *force = nullptr, *torque = nullptr;
    double sign = 1.0;
    if (p.body && dJointGetBody(p.joint, 0) == p.body) {
      force = f.f1;
      torque = f.t1;
    } else if (p.body) {
      force = f.f2;
      torque = f.t2;
    } else {  // static: the reaction to the force on the other body, no torque of its own
      force = f.f1;
      sign = -1.0;
    }
    for (int k = 0; k < 3; ++k) {
      r.force[k] = sign * force[k];
      r.torque[k] = torque ? torque[k] : 0.0;
    }
    recs.push_back(r);
  }
  pending_.clear();
  feedback_.clear();
  if (recs.empty()) return;
  steps_with_contacts_.push_back(std::move(recs));
  while (steps_with_contacts_.size() > kMaxContactSteps) steps_with_contacts_.pop_front();
}

std::vector<ContactRecord> Stepper::takeContacts() {
  std::vector<ContactRecord> out;
  for (auto& s : steps_with_contacts_) out.insert(out.end(), s.begin(), s.end());
  steps_with_contacts_.clear();
  return out;
}

void Stepper::preStep(ActiveJoint& j) {
  if (j.has_pos_cmd) {
    double pos = j.hinge ? dJointGetHingeAngle(j.id) : dJointGetSliderPosition(j.id);
    double vel = (j.pos_cmd - pos) / dt_;
    if (j.vmax > 0) vel = std::max(-j.vmax, std::min(j.vmax, vel));
    if (j.hinge) {
      dJointSetHingeParam(j.id, dParamVel, vel);
      dJointSetHingeParam(j.id, dParamFMax, j.fmax);
    } else {
      dJointSetSliderParam(j.id, dParamVel, vel);
      dJointSetSliderParam(j.id, dParamFMax, j.fmax);
    }
  }
  double effort = j.effort_cmd;
  if (j.damping != 0.0) {
    double rate = j.hinge ? dJointGetHingeAngleRate(j.id) : dJointGetSliderPositionRate(j.id);
    effort -= j.damping * rate;
  }
  j.applied = effort;
  if (effort != 0.0) {
    if (j.hinge)
      dJointAddHingeTorque(j.id, effort);
    else
      dJointAddSliderForce(j.id, effort);
  }
}

bool Stepper::anyEnabled(dSpaceID sp) const {
  auto it = space_bodies_.find(sp);
  if (it == space_bodies_.end()) return false;
  for (dBodyID b : it->second)
    if (dBodyIsEnabled(b)) return true;
  return false;
}

void Stepper::sortSleepers() {
  for (dSpaceID sp : std::vector<dSpaceID>(awake_))
    if (!anyEnabled(sp)) moveTo(awake_, dormant_, sp);
  for (dSpaceID sp : std::vector<dSpaceID>(dormant_))
    if (anyEnabled(sp)) rouse(sp);
}

void Stepper::collideSpaces(dSpaceID a, dSpaceID b) {
  dReal ba[6], bb[6];
  dGeomGetAABB(asGeom(a), ba);
  dGeomGetAABB(asGeom(b), bb);
  if (dSpaceGetNumGeoms(a) == 0 || dSpaceGetNumGeoms(b) == 0 || disjoint(ba, bb)) return;
  dSpaceCollide2(asGeom(a), asGeom(b), this, &Stepper::nearCallback);
}

void Stepper::readStatic() {
  const int ns = dSpaceGetNumGeoms(static_);
  static_geoms_.resize(ns);
  static_nested_ = false;
  for (int i = 0; i < ns; ++i) {
    StaticGeom& s = static_geoms_[i];
    s.id = dSpaceGetGeom(static_, i);  // the space's list order, as ODE's collide2 walks it
    if (dGeomIsSpace(s.id)) static_nested_ = true;
    s.enabled = dGeomIsEnabled(s.id) != 0;
    dGeomGetAABB(s.id, s.box);
  }
}

void Stepper::collideStatic(dSpaceID sp) {
  const int nr = dSpaceGetNumGeoms(sp);
  const int ns = static_cast<int>(static_geoms_.size());
  if (static_nested_) {
    dSpaceCollide2(asGeom(sp), asGeom(static_), this, &Stepper::nearCallback);
    return;
  }
  if (nr == 0 || ns == 0) return;
  dReal box[6];
  dGeomGetAABB(asGeom(sp), box);
  near_static_.clear();
  for (const StaticGeom& s : static_geoms_)
    if (!disjoint(box, s.box)) near_static_.push_back(&s);
  if (near_static_.empty()) return;
  // dSpaceCollide2 of two spaces walks the one with fewer geoms and collide2's each of them
  // into the other, which skips its own disabled geoms; every pair reaches near() as (sp's
  // geom, static geom). dSpaceCollide2 on two geoms is ODE's collideAABBs on them.
  if (nr < ns) {
    for (int i = 0; i < nr; ++i) {
      dGeomID g = dSpaceGetGeom(sp, i);
      for (const StaticGeom* s : near_static_)
        if (s->enabled) dSpaceCollide2(g, s->id, this, &Stepper::nearCallback);
    }
  } else {
    for (const StaticGeom* s : near_static_)
      for (int i = 0; i < nr; ++i) {
        dGeomID g = dSpaceGetGeom(sp, i);
        if (dGeomIsEnabled(g)) dSpaceCollide2(g, s->id, this, &Stepper::nearCallback);
      }
  }
}

void Stepper::step(int n, int64_t steps) {
  ensureThreadData();  // the trimesh collider's caches on the thread that steps
  for (int s = 0; s < n; ++s) {
    for (auto& j : active_) preStep(j);
    if (!awake_.empty()) readStatic();
    for (size_t i = 0; i < awake_.size(); ++i) {
      dSpaceID sp = awake_[i];
      collideStatic(sp);
      for (size_t k = i + 1; k < awake_.size(); ++k) collideSpaces(sp, awake_[k]);
      for (dSpaceID other : dormant_) {
        int64_t before = contacts_;
        collideSpaces(sp, other);
        if (contacts_ != before) wake_.push_back(other);
      }
    }
    if (!wake_.empty()) {
      std::vector<dSpaceID> wake;
      wake.swap(wake_);
      for (dSpaceID sp : wake) {
        if (std::find(dormant_.begin(), dormant_.end(), sp) != dormant_.end()) {
          rouse(sp);
          collideStatic(sp);
        }
      }
    }
    for (dSpaceID sp : self_collide_) dSpaceCollide(sp, this, &Stepper::nearCallback);
    if (use_step_)
      dWorldStep(world_, dt_);
    else
      dWorldQuickStep(world_, dt_);
    if (!pending_.empty()) finishStepContacts(steps + 1);
    dJointGroupEmpty(group_);
    for (size_t i = 0; i < tracked_.size(); ++i) {
      const dReal* v = dBodyGetLinearVel(tracked_[i]);
      for (int k = 0; k < 3; ++k) {
        accel_[3 * i + k] = (v[k] - prev_vel_[3 * i + k]) / dt_;
        prev_vel_[3 * i + k] = v[k];
      }
    }
    ++steps;
    if (steps % 100 == 0) sortSleepers();
  }
}

}  // namespace ode_sim
