"""The step loop on PyODE: collision with a Python near callback, contact joints, (quick)step,
sleeping models. The reference the compiled core (compiled.py, core/) reproduces operation for
operation; PhysicsWorld(core='python') uses it."""
from collections import deque

import numpy as np
import ode

from ode_sim.engine.contacts import MAX_STEPS


def disjoint(a, b):
    """ODE's AABB overlap test on (minx, maxx, miny, maxy, minz, maxz) boxes."""
    return (a[0] > b[1] or a[1] < b[0] or a[2] > b[3] or a[3] < b[2] or a[4] > b[5]
            or a[5] < b[4])


class PythonLoop:
    """PhysicsWorld's step loop in Python; keeps its state in the PhysicsWorld `pw`."""

    joints_dirty = False
    tracked_dirty = False

    def __init__(self, pw):
        self.pw = pw
        self._watched = set()       # contact sensors' geoms
        self._pending = []          # this step's watched contacts:
        # (geom, other, contact, joint, normal sign, force slot)
        # finished steps' records, one list per step with contacts (the core's bound)
        self._steps = deque(maxlen=MAX_STEPS)

    # the compiled loop mirrors these changes; here the lists of pw are the state
    def sync_step(self):
        pass

    def add_geom(self, geom, surf):
        pass

    def remove_geom(self, geom):
        pass

    def add_space(self, space, bodies, self_collide):
        pass

    def remove_space(self, space):
        pass

    def set_watched(self, geoms):
        self._watched = set(geoms)
        if not self._watched:
            self._steps.clear()

    def take_contacts(self):
        out = [r for recs in self._steps for r in recs]
        self._steps.clear()
        return out

    def _watch(self, g1, g2, b1, b2, contact, joint):
        """Record a watched geom's contact joint. ODE puts a lone body first (attach(None, b)
        makes b body 0), so the watched geom's force is feedback slot 0 when its body is the
        joint's first body, slot 1 when it is the other one, and for a static watched geom the
        reaction to slot 0 (None)."""
        first = b1 if b1 is not None else b2
        for mine, other, body, sign in ((g1, g2, b1, 1.0), (g2, g1, b2, -1.0)):
            if mine in self._watched:
                joint.setFeedback(True)
                slot = None if body is None else 0 if body is first else 1
                self._pending.append((mine, other, contact, joint, sign, slot))

    def _finish_step_contacts(self, step):
        feedback = {}
        zero = ((0.0, 0.0, 0.0),) * 4
        for *_, joint, _s, _slot in self._pending:
            if id(joint) not in feedback:
                # ODE leaves the feedback of a joint between sleeping bodies unwritten (and
                # PyODE's buffer uninitialised): no force, as the compiled core reports
                awake = any(b is not None and b.isEnabled()
                            for b in (joint.getBody(0), joint.getBody(1)))
                feedback[id(joint)] = joint.getFeedback() if awake else zero
                joint.setFeedback(False)    # PyODE would touch it after the group frees it
        recs = []
        for mine, other, contact, joint, sign, slot in self._pending:
            pos, normal, depth, _g1, _g2 = contact.getContactGeomParams()
            f1, t1, f2, t2 = feedback[id(joint)]
            if slot is None:            # static: the reaction, no torque of its own
                force, torque = tuple(-v for v in f1), (0.0, 0.0, 0.0)
            else:
                force, torque = (f1, t1) if slot == 0 else (f2, t2)
            recs.append((step, mine, other, tuple(pos) + tuple(sign * v for v in normal)
                         + (depth,) + tuple(force) + tuple(torque)))
        self._pending = []
        if recs:
            self._steps.append(recs)

    def near(self, _arg, g1, g2):
        pw = self.pw
        if g1.isSpace() or g2.isSpace():
            ode.collide2(g1, g2, None, self.near)
            return
        s1 = pw._surf.get(g1)
        s2 = pw._surf.get(g2)
        if s1 is None or s2 is None:
            return
        b1, b2 = s1[7], s2[7]
        if b1 is b2:
            return                      # one body, or two bodiless (static, welded) geoms
        if b1 is not None and b2 is not None and ode.areConnected(b1, b2):
            return
        contacts = ode.collide(g1, g2)
        if not contacts:
            return
        dt = pw.dt
        kp = 1.0 / (1.0 / s1[2] + 1.0 / s2[2])
        kd = s1[3] + s2[3]
        denom = dt * kp + kd
        erp = dt * kp / denom
        cfm = 1.0 / denom
        mu1 = min(s1[0], s2[0])
        mu2 = min(s1[1], s2[1])
        fdir = s1[4] or s2[4]
        bounce = max(s1[5], s2[5])
        mode = ode.ContactSoftERP | ode.ContactSoftCFM | ode.ContactApprox1 | ode.ContactMu2
        if fdir is not None:
            mode |= ode.ContactFDir1
        if bounce > 0:
            mode |= ode.ContactBounce
        world = pw.world
        group = pw.contact_group
        for c in contacts[:pw.max_contacts]:
            c.setMode(mode)
            c.setMu(mu1 if mu1 < 1e30 else ode.Infinity)
            c.setMu2(mu2 if mu2 < 1e30 else ode.Infinity)
            c.setSoftERP(erp)
            c.setSoftCFM(cfm)
            if fdir is not None:
                body = b1 if s1[4] else b2
                d = body.vectorToWorld(fdir) if body is not None else fdir
                c.setFDir1(d)
            if bounce > 0:
                c.setBounce(bounce)
                c.setBounceVel(min(s1[6], s2[6]))
            joint = ode.ContactJoint(world, group, c)
            joint.attach(b1, b2)
            if self._watched and (g1 in self._watched or g2 in self._watched):
                self._watch(g1, g2, b1, b2, c, joint)
        pw._contacts += 1

    def sort_sleepers(self):
        """Models whose bodies all sleep stop colliding with the static world (and back)."""
        pw = self.pw
        for sp in list(pw._awake):
            if not any(b.isEnabled() for b in pw._space_bodies[sp]):
                pw._awake.remove(sp)
                pw._dormant.append(sp)
        for sp in list(pw._dormant):
            if any(b.isEnabled() for b in pw._space_bodies[sp]):
                self.rouse(sp)

    def rouse(self, sp):
        pw = self.pw
        if sp in pw._dormant:
            pw._dormant.remove(sp)
            pw._awake.append(sp)
            for b in pw._space_bodies[sp]:
                b.enable()

    # Broad phase (the core's collideSpaces / readStatic / collideStatic, call for call, so the
    # pairs reach near() in the same order and ODE's space lists change the same way): ODE's
    # collide2 of two spaces tests every geom of one against every geom of the other.
    def _collide_spaces(self, a, b):
        """ode.collide2(a, b), skipped when the spaces' boxes are disjoint."""
        box_a, box_b = a.getAABB(), b.getAABB()
        if a.getNumGeoms() == 0 or b.getNumGeoms() == 0 or disjoint(box_a, box_b):
            return
        ode.collide2(a, b, None, self.near)

    @staticmethod
    def _read_static(static):
        """[(geom, enabled, box)] of the static space in its list order; None when it holds a
        space (then _collide_static collides the whole static space)."""
        out = []
        for i in range(static.getNumGeoms()):
            g = static.getGeom(i)
            if g.isSpace():
                return None
            out.append((g, bool(g.isEnabled()), g.getAABB()))
        return out

    def _collide_static(self, sp, statics):
        """ode.collide2(sp, static_space) against the static geoms whose box meets sp's only,
        with ODE's pair order: it walks the space with fewer geoms."""
        if statics is None:
            ode.collide2(sp, self.pw.static_space, None, self.near)
            return
        nr = sp.getNumGeoms()
        if nr == 0 or not statics:
            return
        box = sp.getAABB()
        near_static = [s for s in statics if not disjoint(box, s[2])]
        if not near_static:
            return
        near = self.near
        if nr < len(statics):
            for i in range(nr):
                g = sp.getGeom(i)
                for s, enabled, _ in near_static:
                    if enabled:
                        ode.collide2(g, s, None, near)
        else:
            for s, _, _ in near_static:
                for i in range(nr):
                    g = sp.getGeom(i)
                    if g.isEnabled():
                        ode.collide2(g, s, None, near)

    def step(self, n):
        pw = self.pw
        dt = pw.dt
        static = pw.static_space
        near = self.near
        for k in range(n):
            for sj in pw._active:
                sj.pre_step(dt)
            awake = pw._awake
            statics = self._read_static(static) if awake else []
            for i, sp in enumerate(awake):
                self._collide_static(sp, statics)           # model vs the static world
                for other in awake[i + 1:]:
                    self._collide_spaces(sp, other)         # models vs each other
                for other in pw._dormant:
                    before = pw._contacts
                    self._collide_spaces(sp, other)         # a touch wakes the sleeper
                    if pw._contacts != before:
                        pw._wake.append(other)
            if pw._wake:
                for sp in pw._wake:
                    if sp in pw._dormant:
                        self.rouse(sp)
                        self._collide_static(sp, statics)
                pw._wake = []
            for sp in pw._self_collide:
                sp.collide(None, near)
            if pw.use_step:
                pw.world.step(dt)
            else:
                pw.world.quickStep(dt)
            if self._pending:
                self._finish_step_contacts(pw.steps + k + 1)
            pw.contact_group.empty()
            for link in pw._tracked:
                v = np.array(link.body.getLinearVel())
                link.accel = (v - link.prev_vel) / dt
                link.prev_vel = v
            if (pw.steps + k + 1) % 100 == 0:
                self.sort_sleepers()
