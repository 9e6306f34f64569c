"""SDF elements below a model: geometry, surface, material, inertial, links and joints (the
description data model, model.py); sensors and plugins in sdf_sensors.py. Errors: ModelError
`FILE:LINE: what`."""
import os

import numpy as np

from ode_sim.description import materials, ogre
from ode_sim.description.mesh import load_mesh
from ode_sim.description.model import (Collision, Geometry, Inertial, Joint, Link, Material,
                                       ModelError, Surface, Visual)
from ode_sim.description.sdf_sensors import parse_sensor
from ode_sim.description.transforms import Pose
from ode_sim.description.xmldoc import text_of

SUPPORTED_JOINTS = ('revolute', 'continuous', 'prismatic', 'fixed', 'ball')
UNSUPPORTED_JOINTS = ('revolute2', 'universal', 'screw', 'gearbox')


# ------------------------------------------------------------------------------------------
# geometry, surface, material

def parse_geometry(ctx, geom_el, owner, optional_mesh=False):
    """Geometry of a <geometry> element; None for <empty/> (or an unreadable mesh of a visual
    when optional_mesh: a warning then)."""
    if geom_el is None:
        raise ctx.err(owner, '<%s name=%r> needs <geometry>' % (owner.tag, owner.get('name', '')))
    shapes = [c for c in geom_el if isinstance(c.tag, str)]
    if not shapes:
        raise ctx.err(geom_el, '<geometry> of <%s name=%r> is empty'
                      % (owner.tag, owner.get('name', '')))
    shape = shapes[0]
    kind = shape.tag
    if kind == 'box':
        size = ctx.floats(shape, 'size', 3, (1.0, 1.0, 1.0))
        if min(size) <= 0:
            raise ctx.err(shape, '<box><size> must be positive, got %s' % (size,))
        return Geometry('box', size=size)
    if kind == 'cylinder':
        r = ctx.num(shape, 'radius', 1.0)
        length = ctx.num(shape, 'length', 1.0)
        if r <= 0 or length <= 0:
            raise ctx.err(shape, '<cylinder> radius and length must be positive')
        return Geometry('cylinder', radius=r, length=length)
    if kind == 'sphere':
        r = ctx.num(shape, 'radius', 1.0)
        if r <= 0:
            raise ctx.err(shape, '<sphere><radius> must be positive')
        return Geometry('sphere', radius=r)
    if kind == 'plane':
        normal = np.array(ctx.floats(shape, 'normal', 3, (0.0, 0.0, 1.0)))
        n = np.linalg.norm(normal)
        if n == 0:
            raise ctx.err(shape, '<plane><normal> must not be zero')
        size = ctx.floats(shape, 'size', 2, (1.0, 1.0))
        return Geometry('plane', normal=tuple(normal / n), plane_size=size)
    if kind == 'mesh':
        uri = text_of(shape, 'uri')
        if not uri:
            raise ctx.err(shape, '<mesh> needs <uri>')
        scale = ctx.floats(shape, 'scale', 3, (1.0, 1.0, 1.0))
        sub = shape.find('submesh')
        name, center = '', False
        if sub is not None:
            name = text_of(sub, 'name') or ''
            if not name:
                raise ctx.err(sub, '<submesh> needs <name>')
            center = (text_of(sub, 'center') or 'false').strip().lower() in ('true', '1')
        return load_mesh_geometry(ctx, shape, uri, scale, optional_mesh, name, center)
    if kind == 'empty':
        return None
    raise ctx.err(shape, '<%s> geometry is not supported (box, cylinder, sphere, plane, mesh)'
                  % kind)


def load_mesh_geometry(ctx, elem, uri, scale, optional, submesh='', center=False):
    """Geometry of a mesh file (description/mesh.py load_mesh); its warnings (a missing
    texture, ...) go to the context's warnings, once per file and element."""
    try:
        filename = ctx.paths.resolve_uri(uri, ctx.base_dir)
        mesh = load_mesh(filename, scale, submesh, center)
    except ModelError as e:
        if optional:
            ctx.warn(elem, '%s; the visual is not drawn' % e)
            return None
        raise ctx.err(elem, str(e))
    if optional:                          # visuals: what the camera will not show as written
        for w in mesh.warnings:
            if w not in ctx.warnings:
                ctx.warnings.append(w)
    return Geometry('mesh', uri=uri, filename=filename, scale=tuple(scale),
                    vertices=mesh.vertices, faces=mesh.faces, submesh=submesh or '',
                    center=bool(center), parts=mesh.parts)


def read_nums(ctx, el, obj, names):
    """obj.ATTR = the number in <el><TAG> for each (TAG, ATTR) of `names` (a tag that is absent
    keeps the value); nothing when `el` is None."""
    if el is None:
        return
    for tag, attr in names:
        setattr(obj, attr, ctx.num(el, tag, getattr(obj, attr)))


def parse_surface(ctx, surf_el, surface=None):
    s = surface or Surface()
    if surf_el is None:
        return s
    fr = surf_el.find('friction')
    if fr is not None:
        ode = fr.find('ode')
        if ode is not None:
            read_nums(ctx, ode, s, (('mu', 'mu1'), ('mu2', 'mu2')))
            if ode.find('fdir1') is not None:
                f = ctx.floats(ode, 'fdir1', 3, (0.0, 0.0, 0.0))
                s.fdir1 = None if not any(f) else f
            read_nums(ctx, ode, s, (('slip1', 'slip1'), ('slip2', 'slip2')))
    ct = surf_el.find('contact')
    if ct is not None:
        read_nums(ctx, ct.find('ode'), s, (('kp', 'kp'), ('kd', 'kd'), ('max_vel', 'max_vel'),
                                           ('min_depth', 'min_depth')))
    read_nums(ctx, surf_el.find('bounce'), s, (('restitution_coefficient', 'bounce'),
                                               ('threshold', 'bounce_threshold')))
    return s


_SCRIPTS = {}      # tuple of (script file, mtime) -> ogre.parse_scripts result


def _scripts(files):
    key = tuple((f, os.path.getmtime(f)) for f in files)
    hit = _SCRIPTS.get(key)
    if hit is None:
        hit = _SCRIPTS[key] = ogre.parse_scripts(files)
    return hit


def parse_material(ctx, mat_el, visual):
    """visual.color / material_name / material from an SDF <material>: an OGRE script named by
    <script><uri>s and <name> (the .material files of the URIs' folders, then Gazebo's own
    Gazebo/... names), then <ambient> <diffuse> <specular> <emissive> over it, as Gazebo
    applies them. An unknown material or a missing texture: a warning, a plain colour."""
    if mat_el is None:
        return
    script = mat_el.find('script')
    name = text_of(script, 'name') if script is not None else None
    diffuse = ctx.color(mat_el, 'diffuse', None)
    ambient = ctx.color(mat_el, 'ambient', None)
    specular = ctx.color(mat_el, 'specular', None)
    emissive = ctx.color(mat_el, 'emissive', None)
    mat = None
    if name:
        dirs = []
        for u in script.findall('uri'):
            uri = (u.text or '').strip()
            if not uri or uri.startswith('file://media/') or uri.startswith('__default__'):
                continue                       # Gazebo's own media: the built-in table below
            try:
                dirs.append(ctx.paths.resolve_uri(uri, ctx.base_dir))
            except ModelError as e:
                ctx.warn(u, '%s; material %r drawn in a plain colour' % (e, name))
        broken = False
        try:
            found = _scripts(ogre.script_files(dirs)).get(name) if dirs else None
        except ModelError as e:
            ctx.warn(script, '%s; material %r drawn in a plain colour' % (e, name))
            found, broken = None, True
        if found is not None:
            mat, warning = ogre.to_material(name, found[0], found[1], dirs)
            if warning:
                ctx.warn(script, warning)
        else:
            known = materials.is_known(name)
            rgba = materials.material_color(
                name, ctx.warnings if not (dirs or broken) else None, ctx.doc.where(script))
            if not known and dirs and not broken:
                ctx.warn(script, 'unknown material %r: not in %s nor one of Gazebo\'s '
                         'Gazebo/... names; drawn grey' % (name, ', '.join(dirs)))
            mat = Material(name=name, diffuse=rgba, source='gazebo.material')
    if diffuse is not None or ambient is not None or specular is not None or \
            emissive is not None:
        mat = mat or Material(name='', diffuse=diffuse or ambient)
        if diffuse is not None:
            mat.diffuse = diffuse
            mat.opacity = diffuse[3] if len(diffuse) > 3 else 1.0
        if ambient is not None:
            mat.ambient = ambient
        if specular is not None:
            mat.specular = tuple(specular[:3])
        if emissive is not None:
            mat.emissive = tuple(emissive[:3])
    if diffuse is not None:
        visual.color = diffuse
    elif ambient is not None:
        visual.color = ambient
    elif mat is not None:
        visual.color = tuple(mat.diffuse)
    if name:
        visual.material_name = name
    visual.material = mat


# ------------------------------------------------------------------------------------------
# links, joints, models

def parse_inertial(ctx, el):
    if el is None:
        # SDF default: 1 kg, unit inertia
        return Inertial(mass=1.0, ixx=1.0, iyy=1.0, izz=1.0)
    mass = ctx.num(el, 'mass', 1.0)
    inertial = Inertial(mass=mass, pose=ctx.pose(el))
    ia = el.find('inertia')
    if ia is not None:
        inertial.ixx = ctx.num(ia, 'ixx', 1.0)
        inertial.ixy = ctx.num(ia, 'ixy', 0.0)
        inertial.ixz = ctx.num(ia, 'ixz', 0.0)
        inertial.iyy = ctx.num(ia, 'iyy', 1.0)
        inertial.iyz = ctx.num(ia, 'iyz', 0.0)
        inertial.izz = ctx.num(ia, 'izz', 1.0)
    else:
        inertial.ixx = inertial.iyy = inertial.izz = 1.0
    return inertial


def parse_link(ctx, el, model_name, prefix, model_static):
    name = prefix + ctx.name(el, 'link')
    link = Link(name=name)
    link.pose = ctx.pose(el, model_name)
    link.inertial = parse_inertial(ctx, el.find('inertial'))
    if not model_static:
        check_inertial(link.inertial, '%s: <link name=%r>' % (ctx.doc.where(el), name))
    link.gravity = ctx.boolean(el, 'gravity', True)
    link.self_collide = ctx.boolean(el, 'self_collide', False)
    link.kinematic = ctx.boolean(el, 'kinematic', False)
    names = set()
    for c in el.findall('collision'):
        cname = ctx.name(c, 'collision')
        if cname in names:
            raise ctx.err(c, 'link %r has two collisions named %r' % (name, cname))
        names.add(cname)
        geom = parse_geometry(ctx, c.find('geometry'), c)
        if geom is None:
            continue
        col = Collision(name=cname, geometry=geom, pose=ctx.pose(c, name))
        col.surface = parse_surface(ctx, c.find('surface'))
        col.laser_retro = ctx.num(c, 'laser_retro', 0.0)
        link.collisions.append(col)
    for v in el.findall('visual'):
        vname = ctx.name(v, 'visual')
        geom = parse_geometry(ctx, v.find('geometry'), v, optional_mesh=True)
        if geom is None:
            continue
        vis = Visual(name=vname, geometry=geom, pose=ctx.pose(v, name))
        parse_material(ctx, v.find('material'), vis)
        tr = ctx.num(v, 'transparency', 0.0)
        if tr:
            vis.color = tuple(vis.color[:3]) + (vis.color[3] * (1.0 - tr),)
        link.visuals.append(vis)
    for s in el.findall('sensor'):
        link.sensors.append(parse_sensor(ctx, s, name))
    return link


def check_inertial(inertial, where):
    """ModelError unless mass > 0 and the inertia tensor is positive definite."""
    if inertial is None or not inertial.mass > 0:
        raise ModelError('%s has zero mass (mass %s): every simulated link needs '
                         '<inertial> with a positive <mass>'
                         % (where, None if inertial is None else inertial.mass))
    t = inertial.tensor()
    if not np.all(np.isfinite(t)):
        raise ModelError('%s: inertia is not finite' % where)
    eig = np.linalg.eigvalsh(t)
    if eig.min() <= 0:
        raise ModelError('%s: inertia tensor is not positive definite (eigenvalues %s): give '
                         'ixx, iyy, izz > 0' % (where, ', '.join('%.3g' % e for e in eig)))


def _parse_axis(ctx, ax, joint, child):
    """<axis> of a joint: limits, effort/velocity limits and dynamics into `joint`; returns
    (xyz, in_model): the axis as written and whether it is in the model frame."""
    name, jtype = joint.name, joint.type
    xyz = ctx.floats(ax, 'xyz', 3, (0.0, 0.0, 1.0))
    in_model = ctx.boolean(ax, 'use_parent_model_frame', ctx.v14)
    xyz_el = ax.find('xyz')
    exp = xyz_el.get('expressed_in') if xyz_el is not None else None
    if exp:
        if exp == '__model__':
            in_model = True
        elif exp == child:
            in_model = False
        else:
            raise ctx.err(xyz_el, '<xyz expressed_in=%r>: only the joint frame or '
                                  '__model__ are supported' % exp)
    lim = ax.find('limit')
    if lim is not None and jtype in ('revolute', 'prismatic'):
        lo = ctx.num(lim, 'lower', -1e16)
        hi = ctx.num(lim, 'upper', 1e16)
        if lo > -1e15:
            joint.lower = lo
        if hi < 1e15:
            joint.upper = hi
        if joint.lower is not None and joint.upper is not None and joint.lower > joint.upper:
            raise ctx.err(lim, 'joint %r: <lower> %g is greater than <upper> %g'
                          % (name, joint.lower, joint.upper))
    if lim is not None:
        eff = ctx.num(lim, 'effort', -1.0)
        vel = ctx.num(lim, 'velocity', -1.0)
        joint.effort = eff if eff >= 0 else None
        joint.velocity = vel if vel >= 0 else None
    dyn = ax.find('dynamics')
    if dyn is not None:
        joint.damping = ctx.num(dyn, 'damping', 0.0)
        joint.friction = ctx.num(dyn, 'friction', 0.0)
    return xyz, in_model


def parse_joint(ctx, el, model, prefix):
    name = prefix + ctx.name(el, 'joint')
    jtype = (el.get('type') or '').strip()
    if not jtype:
        raise ctx.err(el, '<joint name=%r> needs a type attribute' % name)
    if jtype in UNSUPPORTED_JOINTS:
        raise ctx.err(el, '<joint name=%r type=%r>: joint type not supported (revolute, '
                          'continuous, prismatic, fixed, ball)' % (name, jtype))
    if jtype not in SUPPORTED_JOINTS:
        raise ctx.err(el, '<joint name=%r>: unknown joint type %r' % (name, jtype))
    parent = text_of(el, 'parent')
    child = text_of(el, 'child')
    if not parent or not child:
        raise ctx.err(el, '<joint name=%r> needs <parent> and <child>' % name)

    def link_name(n):
        if n == 'world':
            return n
        if model.link(prefix + n) is not None:
            return prefix + n
        if model.link(n) is not None:
            return n
        raise ctx.err(el, 'joint %r refers to unknown link %r' % (name, n))

    parent, child = link_name(parent), link_name(child)
    if child == 'world':
        raise ctx.err(el, 'joint %r: child cannot be the world' % name)
    if parent == child:
        raise ctx.err(el, 'joint %r: parent and child are the same link %r' % (name, child))
    child_link = model.link(child)
    jpose_child = ctx.pose(el, child)
    jframe = child_link.pose * jpose_child           # joint frame in the model frame
    joint = Joint(name=name, type=jtype, parent=parent, child=child)
    joint.anchor = jframe.p.copy()
    ax = el.find('axis')
    if ax is not None:
        xyz, in_model = _parse_axis(ctx, ax, joint, child)
    else:
        xyz, in_model = (0.0, 0.0, 1.0), ctx.v14
    if jtype not in ('fixed', 'ball'):
        v = np.array(xyz, dtype=float)
        n = np.linalg.norm(v)
        if n == 0:
            raise ctx.err(el, 'joint %r: <axis><xyz> must not be zero' % name)
        v = v / n
        joint.axis = v if in_model else jframe.rotate(v)
    if jtype == 'continuous':
        joint.lower = joint.upper = None
    parent_pose = Pose() if parent == 'world' else model.link(parent).pose
    joint.origin = parent_pose.inverse() * jframe
    return joint
