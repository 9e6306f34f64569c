/* The least C that simulates the bench's scene: every dynamic model space collided with the
 * static space, contact joints with one fixed set of Gazebo-like surface parameters (soft
 * ERP/CFM from kp 1e12 / kd 1 at the step, mu 1, friction pyramid), quickStep, empty the group.
 * bench/sim_rtf compiles it (cc -O2 -shared ... -lode) and calls run() through ctypes on the
 * world and spaces ode_sim built, so both step the very same bodies. */
#include <ode/ode.h>

#define MAX_CONTACTS 20

static dWorldID world;
static dJointGroupID group;
static double step_dt;

static void near(void *data, dGeomID g1, dGeomID g2) {
  (void)data;
  if (dGeomIsSpace(g1) || dGeomIsSpace(g2)) {
    dSpaceCollide2(g1, g2, 0, &near);
    return;
  }
  dBodyID b1 = dGeomGetBody(g1), b2 = dGeomGetBody(g2);
  if (b1 == b2) return;
  if (b1 && b2 && dAreConnected(b1, b2)) return;
  dContactGeom cg[MAX_CONTACTS];
  int n = dCollide(g1, g2, MAX_CONTACTS, cg, sizeof(dContactGeom));
  const double kp = 1e12 / 2, kd = 2.0;
  const double erp = step_dt * kp / (step_dt * kp + kd), cfm = 1.0 / (step_dt * kp + kd);
  for (int i = 0; i < n; ++i) {
    dContact c = {0};
    c.geom = cg[i];
    c.surface.mode = dContactSoftERP | dContactSoftCFM | dContactApprox1_1 | dContactApprox1_2 |
                     dContactMu2;
    c.surface.mu = 1.0;
    c.surface.mu2 = 1.0;
    c.surface.soft_erp = erp;
    c.surface.soft_cfm = cfm;
    dJointAttach(dJointCreateContact(world, group, &c), b1, b2);
  }
}

/* steps of dt on `w`: each of the n_spaces model spaces against static_space */
void run(void *w, void *static_space, void **spaces, int n_spaces, double dt, int steps) {
  world = (dWorldID)w;
  step_dt = dt;
  if (!group) group = dJointGroupCreate(0);
  for (int s = 0; s < steps; ++s) {
    for (int i = 0; i < n_spaces; ++i)
      dSpaceCollide2((dGeomID)spaces[i], (dGeomID)static_space, 0, &near);
    dWorldQuickStep(world, dt);
    dJointGroupEmpty(group);
  }
}
