"""Gazebo's fixed-joint lumping of a URDF (sdformat's URDF->SDF converter), the part of the
URDF reader (urdf.py) that turns the parsed URDF links and joints into the model's links and
joints: a link joined by a fixed joint is lumped into its parent (mass, centre of mass and
inertia combined; collisions, visuals and sensors re-posed, named as Gazebo names them) unless
the joint's <gazebo reference="JOINT"> sets <disableFixedJointLumping> or <preserveFixedJoint>;
a link without <inertial> that is not lumped is left out with everything below it.
"""
import numpy as np

from ode_sim.description import materials
from ode_sim.description.model import (Collision, Inertial, Joint, Link, Material, ModelError,
                                       Visual)
from ode_sim.description.sdf_elements import check_inertial
from ode_sim.description.sdf_sensors import parse_sensor
from ode_sim.description.transforms import Pose

LUMP = '_fixed_joint_lump__'
IGNORED_JOINT_EXT = ('implicitSpringDamper', 'provideFeedback', 'stopCfm', 'stopErp',
                     'cfmDamping', 'springReference', 'springStiffness', 'fudgeFactor')


class FixedJointLumping:
    """build(): the model's links and joints from the URDF's (mixin of urdf._Parser: uses its
    warn, joint_flag, link_extension, surface_for, ctx, doc, source, warnings, doc_text)."""

    def build(self, model, links, joints, root_name, order, link_ext, joint_ext):
        self._warn_joint_ext(joint_ext)
        world_root = root_name == 'world'
        X, surv, rel, pre = self._kinematics(links, root_name, joint_ext)
        if world_root:
            if links['world'].collisions or links['world'].visuals or links['world'].inertial:
                self.warn(links['world'].el, "link 'world' is the world: its inertial, "
                                             "collisions and visuals are ignored")
        groups = {}
        for n in pre:
            if n == 'world' and world_root:
                continue
            groups.setdefault(surv[n], []).append(n)
        dropped = self._massless(links, pre, groups, surv)
        survivors = [n for n in pre if n in groups and n not in dropped]
        if not survivors:
            raise ModelError("%s: link '%s' has zero mass (no <inertial>): the robot has no "
                             "link to simulate; give it <inertial> with a positive <mass>"
                             % (self.doc.where(links[root_name].el), root_name))
        for s in survivors:
            model.links.append(self._survivor(s, X[s], groups[s], links, rel, link_ext))
        alive = set(survivors)
        for n in pre:
            j = links[n].parent_joint
            if j is None or n not in alive or surv[n] != n:
                continue
            parent = 'world' if (j.parent == 'world' and world_root) else surv[j.parent]
            joint = Joint(name=j.name, type=j.type, parent=parent, child=n)
            joint.anchor = X[n].p.copy()
            if j.type != 'fixed':
                joint.axis = X[n].rotate(j.axis)
            joint.lower, joint.upper = j.lower, j.upper
            joint.effort, joint.velocity = j.effort, j.velocity
            joint.damping, joint.friction = j.damping, j.friction
            joint.origin = (Pose() if parent == 'world' else rel[j.parent]) * j.origin
            model.joints.append(joint)
        model.canonical_link = survivors[0]
        model.urdf = self.doc_text

    def _warn_joint_ext(self, joint_ext):
        for name, gs in joint_ext.items():
            for g in gs:
                for c in g:
                    if isinstance(c.tag, str) and c.tag not in (
                            'disableFixedJointLumping', 'preserveFixedJoint') + IGNORED_JOINT_EXT:
                        self.warn(c, "<gazebo reference='%s'><%s> is ignored" % (name, c.tag))

    def _kinematics(self, links, root_name, joint_ext):
        """Forward kinematics of every URDF link: (X: its pose in the model frame, surv: the
        link it survives in, rel: its pose relative to that one, pre: DFS pre-order)."""
        def reducible(j):
            return (j.type == 'fixed' and j.parent != 'world'
                    and not self.joint_flag(joint_ext, j.name, 'disableFixedJointLumping')
                    and not self.joint_flag(joint_ext, j.name, 'preserveFixedJoint'))

        X, surv, rel = {}, {}, {}
        pre = []                    # DFS pre-order
        stack = [root_name]
        while stack:
            n = stack.pop()
            pre.append(n)
            ul = links[n]
            j = ul.parent_joint
            if j is None:
                X[n] = Pose()
                surv[n], rel[n] = n, Pose()
            else:
                X[n] = X[j.parent] * j.origin
                if reducible(j):
                    surv[n] = surv[j.parent]
                    rel[n] = rel[j.parent] * j.origin
                else:
                    surv[n], rel[n] = n, Pose()
            stack.extend(reversed([cj.child for cj in ul.child_joints]))
        return X, surv, rel, pre

    def _massless(self, links, pre, groups, surv):
        """Gazebo leaves out non-lumped links without inertia, and everything below them:
        the set of those links, with a warning each."""
        dropped = set()
        for s in [n for n in pre if n in groups]:
            if s in dropped:
                continue
            if all(links[m].inertial is None for m in groups[s]):
                below = []
                st = [s]
                while st:
                    x = st.pop()
                    for cj in links[x].child_joints:
                        below.append(cj.child)
                        st.append(cj.child)
                dropped.add(s)
                dropped.update(below)
                lost = sorted(set(surv[b] for b in below) - {s})
                self.warn(links[s].el,
                          "link '%s' has no <inertial>: like Gazebo (urdf2sdf: link[%s] has no "
                          "inertia, not modeled in sdf) it is left out of the simulation%s"
                          % (s, s, ', with the links below it: %s' % ', '.join(lost)
                             if lost else ''))
        return dropped

    def _survivor(self, s, pose, members, links, rel, link_ext):
        """The Link `s` at `pose` with its lumped `members` (s first)."""
        link = Link(name=s, pose=pose)
        link.inertial = self.lumped_inertial(links, members, rel)
        check_inertial(link.inertial, "%s: link '%s'" % (self.source, s)
                       + (' (with lumped %s)' % ', '.join(members[1:]) if members[1:] else ''))
        for m in members[1:]:
            link.lumped[m] = rel[m]
        ci = vi = 0
        used = set()
        for m in members:
            ext = self.link_extension(m, link_ext)
            for col, _ in links[m].collisions:
                c = Collision(name=self.shape_name(s, m, col.name, '_collision', ci, used),
                              geometry=col.geometry, pose=rel[m] * col.pose)
                c.surface = self.surface_for(ext, m)
                if 'laserRetro' in ext:
                    c.laser_retro = ext['laserRetro']
                link.collisions.append(c)
                ci += 1
            for vis, _ in links[m].visuals:
                link.visuals.append(self._visual(s, m, vis, vi, used, rel[m], ext))
                vi += 1
            if ext.get('selfCollide'):
                link.self_collide = True
            if ext.get('gravity') is False:
                link.gravity = False
            for sel in ext.get('sensors', []):
                sensor = parse_sensor(self.ctx, sel, s)
                sensor.pose = rel[m] * sensor.pose
                link.sensors.append(sensor)
        return link

    def _visual(self, s, m, vis, index, used, rel, ext):
        """A URDF visual of member link `m` as a Visual of the surviving link `s`."""
        v = Visual(name=self.shape_name(s, m, vis.name, '_visual', index, used),
                   geometry=vis.geometry, pose=rel * vis.pose, color=vis.color)
        if 'material' in ext:
            v.material_name = ext['material']
            v.color = materials.material_color(ext['material'], self.warnings,
                                               ext['material_where'])
        if 'visual_diffuse' in ext:
            v.color = ext['visual_diffuse']
        if ('material' in ext or 'visual_diffuse' in ext) and \
                v.geometry.kind == 'mesh' and v.geometry.parts:
            # Gazebo paints the whole mesh with the <gazebo> material, over the
            # file's own materials (a plain colour needs none: its look is v.color)
            v.material = Material(name=v.material_name, diffuse=tuple(v.color))
        return v

    def lumped_inertial(self, links, members, rel):
        parts = [(m, links[m].inertial) for m in members if links[m].inertial is not None]
        if len(parts) == 1 and parts[0][0] == members[0]:
            i = parts[0][1]
            return Inertial(mass=i.mass, pose=i.pose.copy(), ixx=i.ixx, ixy=i.ixy, ixz=i.ixz,
                            iyy=i.iyy, iyz=i.iyz, izz=i.izz)
        total = sum(i.mass for _, i in parts)
        if total <= 0:
            return Inertial(mass=total)
        coms, tensors = [], []
        for m, i in parts:
            f = rel[m] * i.pose                     # inertial frame in the surviving link
            R = f.rotation()
            coms.append(f.p)
            tensors.append(R @ i.tensor() @ R.T)
        com = sum(i.mass * c for (_, i), c in zip(parts, coms)) / total
        t = np.zeros((3, 3))
        for (_, i), c, ti in zip(parts, coms, tensors):
            d = c - com
            t += ti + i.mass * (np.dot(d, d) * np.eye(3) - np.outer(d, d))
        return Inertial(mass=total, pose=Pose(com), ixx=t[0, 0], ixy=t[0, 1], ixz=t[0, 2],
                        iyy=t[1, 1], iyz=t[1, 2], izz=t[2, 2])

    @staticmethod
    def shape_name(surv, member, urdf_name, suffix, index, used):
        """Gazebo's names: LINK_collision, LINK_collision_1, ...; shapes of lumped links
        SURV_fixed_joint_lump__LUMPED_collision."""
        name = (urdf_name or member) + suffix
        if index > 0:
            name += '_%d' % index
        if not name.startswith(surv):
            name = surv + LUMP + name
        base, k = name, 1
        while name in used:
            name = '%s_%d' % (base, k)
            k += 1
        used.add(name)
        return name
