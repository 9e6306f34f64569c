"""SDF (1.4, 1.5, 1.6) worlds and models -> the description data model (model.py).

`load_world(path)`, `parse_world(text, source)`, `parse_sdf_model(text, source, name=None)`.
Errors are one line `FILE:LINE: what` (ModelError). Frames as in model.py: link poses are in
the model frame, joint anchors/axes in the model frame.
"""
import math
import os
import xml.parsers.expat
import xml.etree.ElementTree as ET

import numpy as np

from . import materials
from .mesh import load_stl
from .model import (Collision, Geometry, Inertial, Joint, Light, Link, Model, ModelError,
                    Plugin, Scene, Sensor, Surface, Visual, World)
from .resolve import ModelPaths
from .transforms import Pose

SUPPORTED_JOINTS = ('revolute', 'continuous', 'prismatic', 'fixed', 'ball')
UNSUPPORTED_JOINTS = ('revolute2', 'universal', 'screw', 'gearbox')


# ------------------------------------------------------------------------------------------
# XML with line numbers

class XmlDoc:
    """An ElementTree root plus the source line of every element."""

    def __init__(self, root, lines, source):
        self.root = root
        self.lines = lines
        self.source = source

    def line(self, elem):
        return self.lines.get(id(elem), 0)

    def where(self, elem):
        n = self.line(elem)
        return '%s:%d' % (self.source, n) if n else self.source

    def error(self, elem, msg):
        return ModelError('%s: %s' % (self.where(elem), msg))


def parse_xml(text, source):
    """Parse XML text; malformed -> ModelError 'SOURCE:LINE: malformed XML: ...'."""
    if isinstance(text, bytes):
        data = text
    else:
        data = (text or '').encode('utf-8')
        # the text is already decoded: drop a declared encoding other than UTF-8
        if data.lstrip().startswith(b'<?xml'):
            end = data.find(b'?>')
            if end > 0:
                decl = data[:end]
                if b'encoding' in decl and b'utf-8' not in decl.lower():
                    data = b'<?xml version="1.0"?>' + data[end + 2:]
    lines = {}
    stack = []
    result = []
    text_parts = {}
    parser = xml.parsers.expat.ParserCreate()

    def start(tag, attrs):
        elem = ET.Element(tag, attrs)
        lines[id(elem)] = parser.CurrentLineNumber
        if stack:
            stack[-1].append(elem)
        else:
            result.append(elem)
        stack.append(elem)

    def end(tag):
        elem = stack.pop()
        parts = text_parts.pop(id(elem), None)
        if parts:
            elem.text = ''.join(parts)

    def chars(data_):
        if stack:
            elem = stack[-1]
            if len(elem):       # text after a child: its tail
                child = elem[-1]
                child.tail = (child.tail or '') + data_
            else:
                text_parts.setdefault(id(elem), []).append(data_)

    parser.StartElementHandler = start
    parser.EndElementHandler = end
    parser.CharacterDataHandler = chars
    parser.buffer_text = True
    try:
        parser.Parse(data, True)
    except xml.parsers.expat.ExpatError as e:
        raise ModelError('%s:%d: malformed XML: %s (column %d)'
                         % (source, e.lineno, xml.parsers.expat.ErrorString(e.code),
                            e.offset + 1))
    if not result:
        raise ModelError('%s: malformed XML: no root element' % source)
    # keep the elements alive as long as the doc (ids stay unique)
    doc = XmlDoc(result[0], lines, source)
    doc._keep = list(result[0].iter())
    return doc


# ------------------------------------------------------------------------------------------
# small value parsers

def _text(elem, tag, default=None):
    child = elem.find(tag) if elem is not None else None
    if child is None or child.text is None or not child.text.strip():
        return default
    return child.text.strip()


class _Ctx:
    def __init__(self, doc, paths, base_dir, warnings, version):
        self.doc = doc
        self.paths = paths
        self.base_dir = base_dir
        self.warnings = warnings
        self.version = version

    @property
    def v14(self):
        return self.version < (1, 5)

    def err(self, elem, msg):
        return self.doc.error(elem, msg)

    def warn(self, elem, msg):
        self.warnings.append('%s: %s' % (self.doc.where(elem), msg))

    def floats(self, elem, tag, n, default=None):
        child = elem.find(tag)
        if child is None or child.text is None or not child.text.strip():
            if default is None:
                raise self.err(elem, '<%s> needs <%s> (%d number%s)'
                               % (elem.tag, tag, n, 's' if n > 1 else ''))
            return tuple(default) if n > 1 else default
        try:
            vals = [float(v) for v in child.text.split()]
        except ValueError:
            raise self.err(child, '<%s> must be %d number%s, got %r'
                           % (tag, n, 's' if n > 1 else '', child.text.strip()))
        if len(vals) != n or not all(math.isfinite(v) for v in vals):
            raise self.err(child, '<%s> must be %d finite number%s, got %r'
                           % (tag, n, 's' if n > 1 else '', child.text.strip()))
        return tuple(vals) if n > 1 else vals[0]

    def num(self, elem, tag, default):
        return self.floats(elem, tag, 1, default)

    def integer(self, elem, tag, default):
        v = self.floats(elem, tag, 1, float(default))
        if v != int(v):
            raise self.err(elem.find(tag), '<%s> must be an integer, got %r'
                           % (tag, elem.find(tag).text.strip()))
        return int(v)

    def boolean(self, elem, tag, default):
        child = elem.find(tag)
        if child is None or child.text is None or not child.text.strip():
            return default
        t = child.text.strip().lower()
        if t in ('1', 'true', 'yes'):
            return True
        if t in ('0', 'false', 'no'):
            return False
        raise self.err(child, '<%s> must be true/false/1/0, got %r' % (tag, child.text.strip()))

    def color(self, elem, tag, default):
        child = elem.find(tag)
        if child is None or child.text is None or not child.text.strip():
            return default
        try:
            vals = [float(v) for v in child.text.split()]
        except ValueError:
            vals = []
        if len(vals) == 3:
            vals.append(1.0)
        if len(vals) != 4:
            raise self.err(child, '<%s> must be "r g b a", got %r' % (tag, child.text.strip()))
        return tuple(vals)

    def pose(self, elem, parent_frame=None):
        """The <pose> child of `elem` (identity when missing)."""
        child = elem.find('pose')
        if child is None:
            return Pose()
        rel = (child.get('relative_to') or child.get('frame') or '').strip()
        if rel and rel != parent_frame and rel != '__model__':
            raise self.err(child, '<pose relative_to/frame=%r> in <%s name=%r>: only poses '
                                  'relative to the parent frame%s are supported'
                           % (rel, elem.tag, elem.get('name', ''),
                              ' (%r)' % parent_frame if parent_frame else ''))
        try:
            return Pose.parse(child.text)
        except ValueError:
            raise self.err(child, '<pose> must be 6 numbers "x y z roll pitch yaw", got %r'
                           % (child.text or '').strip())

    def name(self, elem, what=None):
        n = (elem.get('name') or '').strip()
        if not n:
            raise self.err(elem, '<%s> needs a name attribute' % (what or elem.tag))
        return n


def _version(doc):
    root = doc.root
    v = root.get('version', '1.6') if root.tag == 'sdf' else '1.6'
    try:
        parts = tuple(int(x) for x in v.strip().split('.')[:2])
    except ValueError:
        raise doc.error(root, '<sdf version=%r>: not a version number' % v)
    return parts


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
        uri = _text(shape, 'uri')
        if not uri:
            raise ctx.err(shape, '<mesh> needs <uri>')
        scale = ctx.floats(shape, 'scale', 3, (1.0, 1.0, 1.0))
        if shape.find('submesh') is not None:
            ctx.warn(shape, '<submesh> is ignored: the whole mesh is used')
        return load_mesh_geometry(ctx, shape, uri, scale, optional_mesh)
    if kind == 'empty':
        return None
    raise ctx.err(shape, '<%s> geometry is not supported (box, cylinder, sphere, plane, mesh)'
                  % kind)


def load_mesh_geometry(ctx, elem, uri, scale, optional):
    try:
        filename = ctx.paths.resolve_uri(uri, ctx.base_dir)
        verts, faces = load_stl(filename, scale)
    except ModelError as e:
        if optional:
            ctx.warn(elem, '%s; the visual is not drawn' % e)
            return None
        raise ctx.err(elem, str(e))
    return Geometry('mesh', uri=uri, filename=filename, scale=tuple(scale),
                    vertices=verts, faces=faces)


def parse_surface(ctx, surf_el, surface=None):
    s = surface or Surface()
    if surf_el is None:
        return s
    fr = surf_el.find('friction')
    if fr is not None:
        ode = fr.find('ode')
        if ode is not None:
            s.mu1 = ctx.num(ode, 'mu', s.mu1)
            s.mu2 = ctx.num(ode, 'mu2', s.mu2)
            if ode.find('fdir1') is not None:
                f = ctx.floats(ode, 'fdir1', 3, (0.0, 0.0, 0.0))
                s.fdir1 = None if not any(f) else f
            s.slip1 = ctx.num(ode, 'slip1', s.slip1)
            s.slip2 = ctx.num(ode, 'slip2', s.slip2)
    ct = surf_el.find('contact')
    if ct is not None:
        ode = ct.find('ode')
        if ode is not None:
            s.kp = ctx.num(ode, 'kp', s.kp)
            s.kd = ctx.num(ode, 'kd', s.kd)
            s.max_vel = ctx.num(ode, 'max_vel', s.max_vel)
            s.min_depth = ctx.num(ode, 'min_depth', s.min_depth)
    b = surf_el.find('bounce')
    if b is not None:
        s.bounce = ctx.num(b, 'restitution_coefficient', s.bounce)
        s.bounce_threshold = ctx.num(b, 'threshold', s.bounce_threshold)
    return s


def parse_material(ctx, mat_el, visual):
    """Set visual.color / material_name from an SDF <material>."""
    if mat_el is None:
        return
    script = mat_el.find('script')
    name = _text(script, 'name') if script is not None else None
    diffuse = ctx.color(mat_el, 'diffuse', None)
    ambient = ctx.color(mat_el, 'ambient', None)
    if diffuse is not None:
        visual.color = diffuse
    elif ambient is not None:
        visual.color = ambient
    elif name:
        visual.color = materials.material_color(name, ctx.warnings, ctx.doc.where(script))
    if name:
        visual.material_name = name


# ------------------------------------------------------------------------------------------
# sensors and plugins

def parse_plugin(ctx, el, source=None):
    name = (el.get('name') or '').strip()
    filename = (el.get('filename') or '').strip()
    if not filename:
        raise ctx.err(el, '<plugin name=%r> needs a filename attribute' % name)
    params = {}
    for child in el:
        if isinstance(child.tag, str):
            params[child.tag] = (child.text or '').strip()
    return Plugin(name=name, filename=filename, params=params, element=el,
                  source=source or ctx.doc.where(el))


def _noise(ctx, parent):
    """(mean, stddev) of a <noise> child of `parent` (0, 0 when missing)."""
    if parent is None:
        return 0.0, 0.0
    n = parent.find('noise')
    if n is None:
        return 0.0, 0.0
    return ctx.num(n, 'mean', 0.0), ctx.num(n, 'stddev', 0.0)


def parse_sensor(ctx, el, link_name):
    """A Sensor from an SDF <sensor> (link_name: the link it is attached to)."""
    name = ctx.name(el, 'sensor')
    stype = (el.get('type') or '').strip()
    if not stype:
        raise ctx.err(el, '<sensor name=%r> needs a type attribute' % name)
    sensor = Sensor(name=name, type=stype, link=link_name)
    sensor.pose = ctx.pose(el, link_name)
    sensor.update_rate = ctx.num(el, 'update_rate', 0.0)
    sensor.always_on = ctx.boolean(el, 'always_on', True)
    sensor.visualize = ctx.boolean(el, 'visualize', False)
    sensor.topic = _text(el, 'topic', '') or ''
    p = sensor.params
    if stype in ('ray', 'gpu_ray'):
        ray = el.find('ray')
        if ray is None:
            ray = el.find('lidar')
        if ray is None:
            ray = ET.Element('ray')
        scan = ray.find('scan')
        hor = scan.find('horizontal') if scan is not None else None
        ver = scan.find('vertical') if scan is not None else None
        hor = hor if hor is not None else ET.Element('horizontal')
        p['samples'] = ctx.integer(hor, 'samples', 640)
        p['resolution'] = ctx.num(hor, 'resolution', 1.0)
        p['min_angle'] = ctx.num(hor, 'min_angle', 0.0)
        p['max_angle'] = ctx.num(hor, 'max_angle', 0.0)
        if ver is not None:
            p['v_samples'] = ctx.integer(ver, 'samples', 1)
            p['v_resolution'] = ctx.num(ver, 'resolution', 1.0)
            p['v_min_angle'] = ctx.num(ver, 'min_angle', 0.0)
            p['v_max_angle'] = ctx.num(ver, 'max_angle', 0.0)
        else:
            p['v_samples'], p['v_resolution'] = 1, 1.0
            p['v_min_angle'], p['v_max_angle'] = 0.0, 0.0
        rng = ray.find('range')
        rng = rng if rng is not None else ET.Element('range')
        p['range_min'] = ctx.num(rng, 'min', 0.0)
        p['range_max'] = ctx.num(rng, 'max', 0.0)
        p['range_resolution'] = ctx.num(rng, 'resolution', 0.0)
        p['noise_mean'], p['noise_stddev'] = _noise(ctx, ray)
        if p['samples'] < 1:
            raise ctx.err(hor, '<sensor name=%r>: <samples> must be >= 1' % name)
        if p['max_angle'] < p['min_angle']:
            raise ctx.err(hor, '<sensor name=%r>: <max_angle> is less than <min_angle>' % name)
    elif stype in ('camera', 'depth', 'multicamera', 'wideanglecamera'):
        cam = el.find('camera')
        cam = cam if cam is not None else ET.Element('camera')
        p['horizontal_fov'] = ctx.num(cam, 'horizontal_fov', 1.047)
        img = cam.find('image')
        img = img if img is not None else ET.Element('image')
        p['width'] = ctx.integer(img, 'width', 320)
        p['height'] = ctx.integer(img, 'height', 240)
        p['format'] = _text(img, 'format', 'R8G8B8')
        clip = cam.find('clip')
        clip = clip if clip is not None else ET.Element('clip')
        p['near'] = ctx.num(clip, 'near', 0.1)
        p['far'] = ctx.num(clip, 'far', 100.0)
        p['noise_mean'], p['noise_stddev'] = _noise(ctx, cam)
        if p['width'] < 1 or p['height'] < 1:
            raise ctx.err(img, '<sensor name=%r>: image width/height must be >= 1' % name)
        if not 0 < p['horizontal_fov'] < 2 * math.pi + 1e-9:
            raise ctx.err(cam, '<sensor name=%r>: <horizontal_fov> must be in (0, 2 pi)' % name)
    elif stype == 'imu':
        imu = el.find('imu')
        imu = imu if imu is not None else ET.Element('imu')
        av_mean = av_std = la_mean = la_std = 0.0
        av = imu.find('angular_velocity')
        if av is not None:
            for axis in ('x', 'y', 'z'):
                m, s = _noise(ctx, av.find(axis))
                av_mean, av_std = max(av_mean, m), max(av_std, s)
        la = imu.find('linear_acceleration')
        if la is not None:
            for axis in ('x', 'y', 'z'):
                m, s = _noise(ctx, la.find(axis))
                la_mean, la_std = max(la_mean, m), max(la_std, s)
        old = imu.find('noise')                    # SDF 1.4 <imu><noise><rate>/<accel>
        if old is not None:
            m, s = _noise(ctx, ET.Element('x', {}) if old.find('rate') is None else
                          _wrap_noise(old.find('rate')))
            av_mean, av_std = max(av_mean, m), max(av_std, s)
            m, s = _noise(ctx, ET.Element('x', {}) if old.find('accel') is None else
                          _wrap_noise(old.find('accel')))
            la_mean, la_std = max(la_mean, m), max(la_std, s)
        p['angular_velocity_noise_mean'] = av_mean
        p['angular_velocity_noise_stddev'] = av_std
        p['linear_acceleration_noise_mean'] = la_mean
        p['linear_acceleration_noise_stddev'] = la_std
        p['noise_mean'] = av_mean
        p['noise_stddev'] = av_std
        if not sensor.topic:
            sensor.topic = _text(imu, 'topic', '') or ''
    else:
        ctx.warn(el, '<sensor name=%r type=%r>: sensor type not simulated, kept without data'
                 % (name, stype))
    for pl in el.findall('plugin'):
        sensor.plugins.append(parse_plugin(ctx, pl))
    return sensor


def _wrap_noise(el):
    w = ET.Element('w')
    n = ET.SubElement(w, 'noise')
    for c in el:
        n.append(c)
    return w


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
    parent = _text(el, 'parent')
    child = _text(el, 'child')
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
    xyz = (0.0, 0.0, 1.0)
    if ax is not None:
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
    else:
        in_model = ctx.v14
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


def parse_model(ctx, el, prefix='', parent_pose=None, nested_in=None):
    """A Model from a <model> element. Nested models are flattened into `nested_in` with
    'outer::inner::' prefixed names."""
    name = ctx.name(el, 'model')
    top = nested_in is None
    model = Model(name=name) if top else nested_in
    pose = ctx.pose(el)
    if top:
        model.pose = pose
        model.static = ctx.boolean(el, 'static', False)
        model.allow_auto_disable = ctx.boolean(el, 'allow_auto_disable', True)
        model.source = ctx.doc.source
        base = Pose()
    else:
        base = parent_pose * pose
        if ctx.boolean(el, 'static', False) and not model.static:
            ctx.warn(el, 'nested static model %r in a non-static model: simulated as dynamic'
                     % name)
    default_self_collide = ctx.boolean(el, 'self_collide', False)
    for lel in el.findall('link'):
        link = parse_link(ctx, lel, name, prefix, model.static)
        if lel.find('self_collide') is None:
            link.self_collide = default_self_collide
        link.pose = base * link.pose
        if model.link(link.name) is not None:
            raise ctx.err(lel, 'model %r has two links named %r' % (name, link.name))
        model.links.append(link)
    for inc in el.findall('include'):
        sub_el, sub_ctx = _include_element(ctx, inc)
        if sub_el.tag != 'model':
            raise ctx.err(inc, '<include> inside a model must name a model, got <%s>'
                          % sub_el.tag)
        _apply_include_overrides(ctx, inc, sub_el)
        sub_name = _text(inc, 'name') or sub_el.get('name')
        sub_ctx.warnings = ctx.warnings
        parse_model(sub_ctx, sub_el, prefix + sub_name + '::', base, model)
    for mel in el.findall('model'):
        parse_model(ctx, mel, prefix + ctx.name(mel, 'model') + '::', base, model)
    for jel in el.findall('joint'):
        joint = parse_joint(ctx, jel, model, prefix)
        if model.joint(joint.name) is not None:
            raise ctx.err(jel, 'model %r has two joints named %r' % (name, joint.name))
        model.joints.append(joint)
    for pel in el.findall('plugin'):
        model.plugins.append(parse_plugin(ctx, pel))
    if top:
        if not model.links:
            raise ctx.err(el, 'model %r has no links' % name)
        model.canonical_link = model.links[0].name
        model.warnings = ctx.warnings
    return model


def _include_element(ctx, inc):
    """(root element of the included file: <model> or <light>, its context)."""
    uri = _text(inc, 'uri')
    if not uri:
        raise ctx.err(inc, '<include> needs <uri>')
    try:
        if uri.startswith('model://'):
            path = ctx.paths.model_sdf(uri[len('model://'):].strip('/'))
        else:
            path = ctx.paths.resolve_uri(uri, ctx.base_dir)
            if os.path.isdir(path):
                cfg = ModelPaths([os.path.dirname(path)])
                path = cfg.model_sdf(os.path.basename(path))
    except ModelError as e:
        raise ctx.err(inc, '<include>: %s' % e)
    with open(path, 'rb') as f:
        doc = parse_xml(f.read(), path)
    sub_ctx = _Ctx(doc, ctx.paths, os.path.dirname(path), ctx.warnings, _version(doc))
    root = doc.root
    if root.tag == 'sdf':
        for child in root:
            if child.tag in ('model', 'light'):
                return child, sub_ctx
        raise doc.error(root, 'no <model> or <light> in the included file')
    if root.tag in ('model', 'light'):
        return root, sub_ctx
    raise doc.error(root, 'expected <sdf>, got <%s>' % root.tag)


def _apply_include_overrides(ctx, inc, sub_el):
    """<include> <name>, <pose>, <static> replace those of the included model/light."""
    ctx.pose(inc)                       # check it here, where errors name the right file
    ctx.boolean(inc, 'static', False)
    for tag in ('pose', 'static'):
        over = inc.find(tag)
        if over is not None:
            old = sub_el.find(tag)
            if old is not None:
                sub_el.remove(old)
            copy = ET.SubElement(sub_el, tag, dict(over.attrib))
            copy.text = over.text
    new_name = _text(inc, 'name')
    if new_name:
        sub_el.set('name', new_name)


# ------------------------------------------------------------------------------------------
# world

def parse_light(ctx, el):
    light = Light(name=ctx.name(el, 'light'))
    light.type = (el.get('type') or 'point').strip()
    if light.type not in ('directional', 'point', 'spot'):
        raise ctx.err(el, '<light name=%r>: unknown type %r' % (light.name, light.type))
    light.pose = ctx.pose(el)
    light.diffuse = ctx.color(el, 'diffuse', (1.0, 1.0, 1.0, 1.0))
    light.specular = ctx.color(el, 'specular', (0.1, 0.1, 0.1, 1.0))
    light.direction = ctx.floats(el, 'direction', 3, (0.0, 0.0, -1.0))
    light.cast_shadows = ctx.boolean(el, 'cast_shadows', False)
    att = el.find('attenuation')
    if att is not None:
        light.attenuation_range = ctx.num(att, 'range', 10.0)
    else:
        light.attenuation_range = 10.0
    return light


def parse_physics(ctx, el, physics):
    ptype = (el.get('type') or 'ode').strip()
    if ptype != 'ode':
        ctx.warn(el, '<physics type=%r>: ode_sim always simulates with ODE' % ptype)
    physics.max_step_size = ctx.num(el, 'max_step_size', physics.max_step_size)
    physics.real_time_update_rate = ctx.num(el, 'real_time_update_rate',
                                            physics.real_time_update_rate)
    physics.real_time_factor = ctx.num(el, 'real_time_factor', physics.real_time_factor)
    physics.max_contacts = ctx.integer(el, 'max_contacts', physics.max_contacts)
    if physics.max_step_size <= 0:
        raise ctx.err(el.find('max_step_size'), '<max_step_size> must be positive')
    if physics.real_time_update_rate < 0:
        raise ctx.err(el.find('real_time_update_rate'), '<real_time_update_rate> must be >= 0')
    ode = el.find('ode')
    if ode is not None:
        solver = ode.find('solver')
        if solver is not None:
            physics.solver_type = _text(solver, 'type', physics.solver_type)
            if physics.solver_type not in ('quick', 'world'):
                raise ctx.err(solver, '<solver><type> must be quick or world, got %r'
                              % physics.solver_type)
            physics.iters = ctx.integer(solver, 'iters', physics.iters)
            physics.sor = ctx.num(solver, 'sor', physics.sor)
        con = ode.find('constraints')
        if con is not None:
            physics.cfm = ctx.num(con, 'cfm', physics.cfm)
            physics.erp = ctx.num(con, 'erp', physics.erp)
            physics.contact_max_correcting_vel = ctx.num(con, 'contact_max_correcting_vel',
                                                         physics.contact_max_correcting_vel)
            physics.contact_surface_layer = ctx.num(con, 'contact_surface_layer',
                                                    physics.contact_surface_layer)
    return physics


def _world_from_doc(doc, paths, base_dir):
    warnings = []
    if doc.root.tag != 'sdf':
        raise doc.error(doc.root, 'expected <sdf> as the root element, got <%s>' % doc.root.tag)
    version = _version(doc)
    ctx = _Ctx(doc, paths, base_dir, warnings, version)
    if not (1, 4) <= version <= (1, 6):
        ctx.warn(doc.root, 'SDF version %d.%d: ode_sim reads 1.4-1.6, trying anyway' % version)
    wel = doc.root.find('world')
    if wel is None:
        raise doc.error(doc.root, 'no <world> in the file')
    world = World(name=wel.get('name') or 'default', source=doc.source, warnings=warnings)
    pel = wel.find('physics')
    if pel is not None:
        parse_physics(ctx, pel, world.physics)
        if pel.find('gravity') is not None:        # SDF 1.4
            world.gravity = ctx.floats(pel, 'gravity', 3)
    if wel.find('gravity') is not None:
        world.gravity = ctx.floats(wel, 'gravity', 3)
    sel = wel.find('scene')
    if sel is not None:
        world.scene = Scene(ambient=ctx.color(sel, 'ambient', (0.4, 0.4, 0.4, 1.0)),
                            background=ctx.color(sel, 'background', (0.7, 0.7, 0.7, 1.0)),
                            shadows=ctx.boolean(sel, 'shadows', True))
    names = set()

    def add_model(m, el):
        if m.name in names:
            ctx.warn(el, 'a model named %r already exists: this one is skipped' % m.name)
            return
        names.add(m.name)
        world.models.append(m)

    for child in wel:
        if child.tag == 'light':
            world.lights.append(parse_light(ctx, child))
        elif child.tag == 'model':
            m = parse_model(_Ctx(doc, paths, base_dir, [], version), child)
            warnings.extend(m.warnings)
            add_model(m, child)
        elif child.tag == 'include':
            sub_el, sub_ctx = _include_element(ctx, child)
            _apply_include_overrides(ctx, child, sub_el)
            if sub_el.tag == 'light':
                world.lights.append(parse_light(sub_ctx, sub_el))
            else:
                sub_ctx.warnings = []
                m = parse_model(sub_ctx, sub_el)
                warnings.extend(m.warnings)
                add_model(m, child)
        elif child.tag == 'plugin':
            world.plugins.append(parse_plugin(ctx, child))
    # saved worlds: <state> holds the models' and lights' poses at save time
    st = wel.find('state')
    if st is not None:
        for mst in st.findall('model'):
            m = next((m for m in world.models if m.name == mst.get('name')), None)
            if m is not None and mst.find('pose') is not None:
                m.pose = ctx.pose(mst)
        for lst in st.findall('light'):
            lt = next((x for x in world.lights if x.name == lst.get('name')), None)
            if lt is not None and lst.find('pose') is not None:
                lt.pose = ctx.pose(lst)
    return world


def parse_world(text, source, paths=None):
    """World from SDF text; `source` names the file in messages and is the base for relative
    URIs."""
    doc = parse_xml(text, source)
    base_dir = os.path.dirname(os.path.abspath(source)) if os.path.exists(source) \
        else os.getcwd()
    return _world_from_doc(doc, paths or ModelPaths(), base_dir)


def load_world(path, paths=None):
    try:
        with open(path, 'rb') as f:
            data = f.read()
    except OSError as e:
        raise ModelError('%s: cannot read world file: %s' % (path, e.strerror or e))
    return parse_world(data, path, paths)


def parse_sdf_model(text, source, paths=None, name=None):
    """Model from SDF text whose root is <sdf><model> (or <model>), e.g. the model_xml of
    /gazebo/spawn_sdf_model; `name` replaces the model's name."""
    doc = parse_xml(text, source)
    root = doc.root
    version = _version(doc)
    mel = root if root.tag == 'model' else (root.find('model') if root.tag == 'sdf' else None)
    if mel is None:
        if root.tag == 'robot':
            raise doc.error(root, 'this is URDF (<robot>), not SDF: spawn it with -urdf')
        raise doc.error(root, 'no <model> in the SDF')
    base_dir = os.path.dirname(os.path.abspath(source)) if os.path.exists(source) \
        else os.getcwd()
    ctx = _Ctx(doc, paths or ModelPaths(), base_dir, [], version)
    if name:
        mel.set('name', name)
    return parse_model(ctx, mel)
