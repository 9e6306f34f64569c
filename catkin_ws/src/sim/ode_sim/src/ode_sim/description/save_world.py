"""Save World: the current world as SDF 1.6, as Gazebo's File -> Save World As writes it, and the
<state> of a saved world read back. No ROS, no ODE: the models are read through the engine's
SimModel/SimLink interface (pose(), velocity(), desc), so this module only formats.

What is written (world_sdf):
- <physics type="ode"> (step, update rate, real-time factor, max contacts, solver, constraints),
  <gravity>, <scene>, every <light> with its current pose, the world's <plugin>s;
- every model at its CURRENT pose:
  - a model that came from `model://` (a world <include>, or spawned as
    <sdf><include><uri>model://NAME</uri></include>) stays an <include> with <uri>, <name>,
    <pose> (and <static> when static);
  - a model given as an SDF <model> (inline in the world, inserted shapes, walls) is that
    element again, with its name and current pose;
  - a robot spawned from URDF becomes a full <model>, as Gazebo's URDF conversion: links (fixed
    joints lumped) with their pose in the model frame, <inertial>, <collision>s with
    <surface> friction and contact parameters, <visual>s with <material>, <sensor>s, <gravity>,
    <self_collide>, <joint>s (pose in the child frame, axis in the model frame with
    <use_parent_model_frame>, limits, dynamics; continuous joints as revolute with +-1e16
    limits, as sdformat writes them), the <plugin>s (robotNamespace filled in) and <static>;
- a <state world_name=...> as Gazebo's: sim_time, real_time, wall_time, iterations, and per model
  its pose and each link's world pose, velocity, acceleration and wrench; per light its pose.

Loading it back: sdf.load_world reads the models' <state> poses; read_state() +
apply_link_states() put every link where the state says, which restores joint positions of
robots (what a <state> can hold: link poses; joint velocities, controller set points and the
plugins' own state, e.g. odometry, are not saved, as in Gazebo).
"""
import copy
import math
import os
import time
import xml.etree.ElementTree as ET

from ode_sim.description.transforms import Pose

GAZEBO_MATERIAL = 'file://media/materials/scripts/gazebo.material'
NO_LIMIT = 1e16         # sdformat's "no limit" for revolute joints


# ------------------------------------------------------------------------------------------
# formatting

def num(x):
    """Shortest text of the float to 1e-12 ('1' rather than '1.0' or '1.0000000000000009'):
    saved poses are exact to far below what the physics resolves."""
    x = round(float(x), 12)
    if x == 0.0 or x != x:
        return '0'
    r = repr(x)
    return r[:-2] if r.endswith('.0') else r


def nums(values):
    return ' '.join(num(v) for v in values)


def pose_text(pose):
    return nums(list(pose.p) + list(pose.rpy()))


def _sub(parent, tag, text=None, **attrib):
    el = ET.SubElement(parent, tag, {k: str(v) for k, v in attrib.items()})
    if text is not None:
        el.text = text
    return el


def _flag(b):
    return '1' if b else '0'


def _set_pose(el, pose):
    """Replace the element's own <pose> child with `pose` (first child position kept)."""
    old = el.find('pose')
    if old is not None:
        idx = list(el).index(old)
        el.remove(old)
    else:
        idx = 0
    new = ET.Element('pose')
    new.text = pose_text(pose)
    el.insert(idx, new)


# ------------------------------------------------------------------------------------------
# world parts

def physics_element(parent, physics):
    p = _sub(parent, 'physics', name='default_physics', default='0', type='ode')
    _sub(p, 'max_step_size', num(physics.max_step_size))
    _sub(p, 'real_time_factor', num(physics.real_time_factor))
    _sub(p, 'real_time_update_rate', num(physics.real_time_update_rate))
    _sub(p, 'max_contacts', str(int(physics.max_contacts)))
    ode = _sub(p, 'ode')
    solver = _sub(ode, 'solver')
    _sub(solver, 'type', physics.solver_type)
    _sub(solver, 'iters', str(int(physics.iters)))
    _sub(solver, 'sor', num(physics.sor))
    c = _sub(ode, 'constraints')
    _sub(c, 'cfm', num(physics.cfm))
    _sub(c, 'erp', num(physics.erp))
    _sub(c, 'contact_max_correcting_vel', num(physics.contact_max_correcting_vel))
    _sub(c, 'contact_surface_layer', num(physics.contact_surface_layer))
    return p


def scene_element(parent, scene):
    s = _sub(parent, 'scene')
    _sub(s, 'ambient', nums(scene.ambient))
    _sub(s, 'background', nums(scene.background))
    _sub(s, 'shadows', _flag(scene.shadows))
    return s


def light_element(parent, light, attenuation=None):
    el = _sub(parent, 'light', name=light.name, type=light.type)
    _sub(el, 'cast_shadows', _flag(light.cast_shadows))
    _sub(el, 'pose', pose_text(light.pose))
    _sub(el, 'diffuse', nums(light.diffuse))
    _sub(el, 'specular', nums(light.specular))
    att = _sub(el, 'attenuation')
    _sub(att, 'range', num(light.attenuation_range))
    if attenuation is not None:
        for tag, v in zip(('constant', 'linear', 'quadratic'), attenuation):
            _sub(att, tag, num(v))
    _sub(el, 'direction', nums(light.direction))
    return el


# ------------------------------------------------------------------------------------------
# a model from its description (robots spawned from URDF)

def geometry_element(parent, g):
    el = _sub(parent, 'geometry')
    if g.kind == 'box':
        _sub(_sub(el, 'box'), 'size', nums(g.size))
    elif g.kind == 'cylinder':
        c = _sub(el, 'cylinder')
        _sub(c, 'radius', num(g.radius))
        _sub(c, 'length', num(g.length))
    elif g.kind == 'sphere':
        _sub(_sub(el, 'sphere'), 'radius', num(g.radius))
    elif g.kind == 'plane':
        p = _sub(el, 'plane')
        _sub(p, 'normal', nums(g.normal))
        _sub(p, 'size', nums(g.plane_size))
    elif g.kind == 'mesh':
        m = _sub(el, 'mesh')
        uri = g.uri
        if not uri.startswith(('model://', 'package://', 'file://')) and g.filename:
            uri = 'file://' + g.filename     # a relative path would not survive a move
        _sub(m, 'uri', uri)
        if g.submesh:
            sm = _sub(m, 'submesh')
            _sub(sm, 'name', g.submesh)
            _sub(sm, 'center', _flag(g.center))
        _sub(m, 'scale', nums(g.scale))
    else:
        raise ValueError('geometry kind %r cannot be saved' % g.kind)
    return el


def surface_element(parent, s):
    el = _sub(parent, 'surface')
    fr = _sub(_sub(el, 'friction'), 'ode')
    _sub(fr, 'mu', num(s.mu1))
    _sub(fr, 'mu2', num(s.mu2))
    if s.fdir1 is not None:
        _sub(fr, 'fdir1', nums(s.fdir1))
    _sub(fr, 'slip1', num(s.slip1))
    _sub(fr, 'slip2', num(s.slip2))
    ct = _sub(_sub(el, 'contact'), 'ode')
    _sub(ct, 'kp', num(s.kp))
    _sub(ct, 'kd', num(s.kd))
    _sub(ct, 'max_vel', num(s.max_vel))
    _sub(ct, 'min_depth', num(s.min_depth))
    b = _sub(el, 'bounce')
    _sub(b, 'restitution_coefficient', num(s.bounce))
    _sub(b, 'threshold', num(s.bounce_threshold))
    return el


def material_element(parent, v):
    """<material> of a visual: a named (Gazebo/...) material as a script, the colour as
    ambient/diffuse; a mesh without a material of its own keeps its file's materials (when
    the file has none, its plain colour is what is drawn, and is written)."""
    mat = v.material
    g = v.geometry
    if g.kind == 'mesh' and not v.material_name and mat is None and \
            any(getattr(part, 'material', None) is not None for part in (g.parts or [])):
        return None
    el = _sub(parent, 'material')
    if v.material_name:
        sc = _sub(el, 'script')
        _sub(sc, 'uri', GAZEBO_MATERIAL)
        _sub(sc, 'name', v.material_name)
    color = tuple(v.color)
    ambient = mat.ambient if mat is not None and mat.ambient is not None else color
    _sub(el, 'ambient', nums(ambient))
    _sub(el, 'diffuse', nums(color))
    spec = tuple(mat.specular) if mat is not None else (0.1, 0.1, 0.1)
    _sub(el, 'specular', nums(tuple(spec[:3]) + (1.0,)))
    emis = tuple(mat.emissive) if mat is not None else (0.0, 0.0, 0.0)
    _sub(el, 'emissive', nums(tuple(emis[:3]) + (1.0,)))
    return el


def _with_namespace(el, namespace):
    """A copy of a <plugin> element with <robotNamespace> filled in (as spawn_model injected
    it into the plugin's parameters)."""
    el = copy.deepcopy(el)
    if namespace and el.tag == 'plugin' and el.find('robotNamespace') is None:
        _sub(el, 'robotNamespace', namespace)
    for sub in el.iter('plugin'):
        if sub is not el and namespace and sub.find('robotNamespace') is None:
            _sub(sub, 'robotNamespace', namespace)
    return el


def link_element(parent, link, static, namespace=''):
    el = _sub(parent, 'link', name=link.name)
    _sub(el, 'pose', pose_text(link.pose))
    ine = link.inertial
    if ine is not None and not static:
        i = _sub(el, 'inertial')
        _sub(i, 'pose', pose_text(ine.pose))
        _sub(i, 'mass', num(ine.mass))
        t = _sub(i, 'inertia')
        for tag in ('ixx', 'ixy', 'ixz', 'iyy', 'iyz', 'izz'):
            _sub(t, tag, num(getattr(ine, tag)))
    for c in link.collisions:
        ce = _sub(el, 'collision', name=c.name)
        _sub(ce, 'pose', pose_text(c.pose))
        if c.laser_retro:
            _sub(ce, 'laser_retro', num(c.laser_retro))
        geometry_element(ce, c.geometry)
        surface_element(ce, c.surface)
    for v in link.visuals:
        ve = _sub(el, 'visual', name=v.name)
        _sub(ve, 'pose', pose_text(v.pose))
        geometry_element(ve, v.geometry)
        material_element(ve, v)
    for s in link.sensors:
        if s.element is None:
            continue
        se = _with_namespace(s.element, namespace)
        se.set('name', s.name)
        _set_pose(se, s.pose)
        el.append(se)
    _sub(el, 'gravity', _flag(link.gravity))
    _sub(el, 'self_collide', _flag(link.self_collide))
    _sub(el, 'kinematic', _flag(link.kinematic))
    return el


def joint_element(parent, joint, model):
    el = _sub(parent, 'joint', name=joint.name,
              type='revolute' if joint.type == 'continuous' else joint.type)
    _sub(el, 'parent', joint.parent)
    _sub(el, 'child', joint.child)
    parent_pose = Pose() if joint.parent == 'world' else model.link(joint.parent).pose
    frame = parent_pose * joint.origin          # joint frame in the model frame
    _sub(el, 'pose', pose_text(model.link(joint.child).pose.inverse() * frame))
    if joint.type in ('fixed', 'ball'):
        return el
    ax = _sub(el, 'axis')
    _sub(ax, 'xyz', nums(joint.axis))
    _sub(ax, 'use_parent_model_frame', '1')
    lim = _sub(ax, 'limit')
    _sub(lim, 'lower', num(-NO_LIMIT if joint.lower is None else joint.lower))
    _sub(lim, 'upper', num(NO_LIMIT if joint.upper is None else joint.upper))
    _sub(lim, 'effort', num(-1 if joint.effort is None else joint.effort))
    _sub(lim, 'velocity', num(-1 if joint.velocity is None else joint.velocity))
    dyn = _sub(ax, 'dynamics')
    _sub(dyn, 'damping', num(joint.damping))
    _sub(dyn, 'friction', num(joint.friction))
    return el


def model_element(desc, pose, name=None):
    """A full SDF <model> of a description at `pose` (what Gazebo writes for a robot spawned
    from URDF)."""
    el = ET.Element('model', name=name or desc.name)
    _sub(el, 'pose', pose_text(pose))
    for link in desc.links:
        link_element(el, link, desc.static, desc.robot_namespace)
    for joint in desc.joints:
        joint_element(el, joint, desc)
    for p in desc.plugins:
        if p.element is not None:
            el.append(_with_namespace(p.element, desc.robot_namespace))
    _sub(el, 'static', _flag(desc.static))
    _sub(el, 'allow_auto_disable', _flag(desc.allow_auto_disable))
    return el


def saved_model(desc, pose):
    """The element Save World writes for one model at `pose`: <include> for model://, the
    SDF <model> it was given as, or a full <model> built from the description (URDF)."""
    if desc.include_uri:
        el = ET.Element('include')
        _sub(el, 'uri', desc.include_uri)
        _sub(el, 'name', desc.name)
        _sub(el, 'pose', pose_text(pose))
        if desc.static:
            _sub(el, 'static', '1')
        return el
    if desc.sdf_element is not None and not desc.urdf:
        el = copy.deepcopy(desc.sdf_element)
        el.set('name', desc.name)
        _set_pose(el, pose)
        if desc.robot_namespace:        # what spawn_sdf_model's robot_namespace injected
            for p in el.iter('plugin'):
                if p.find('robotNamespace') is None:
                    _sub(p, 'robotNamespace', desc.robot_namespace)
        return el
    return model_element(desc, pose)


# ------------------------------------------------------------------------------------------
# the world

def _time_text(t):
    t = max(0.0, float(t))
    sec = int(math.floor(t))
    nsec = int(round((t - sec) * 1e9))
    if nsec >= 1000000000:
        sec, nsec = sec + 1, nsec - 1000000000
    return '%d %d' % (sec, nsec)


def world_element(world, models, gravity=None, sim_time=0.0, real_time=0.0, iterations=0,
                  attenuations=None, wall_time=None):
    """<sdf version="1.6"><world> of the current world.

    world: description World (name, physics, scene, lights, plugins; kept current by the
    simulator); models: the engine's SimModels in spawn order (pose(), links{name: SimLink
    with pose() and velocity()}, desc); gravity: the engine's current gravity (default
    world.gravity); attenuations: {light name: (constant, linear, quadratic)}."""
    attenuations = attenuations or {}
    sdf = ET.Element('sdf', version='1.6')
    w = _sub(sdf, 'world', name=world.name)
    for light in world.lights:
        light_element(w, light, attenuations.get(light.name))
    poses = {}
    for m in models:
        pose = m.pose()
        poses[m.name] = pose
        w.append(saved_model(m.desc, pose))
    _sub(w, 'gravity', nums(gravity if gravity is not None else world.gravity))
    physics_element(w, world.physics)
    scene_element(w, world.scene)
    for p in world.plugins:
        if p.element is not None:
            w.append(copy.deepcopy(p.element))
    st = _sub(w, 'state', world_name=world.name)
    _sub(st, 'sim_time', _time_text(sim_time))
    _sub(st, 'real_time', _time_text(real_time))
    _sub(st, 'wall_time', _time_text(time.time() if wall_time is None else wall_time))
    _sub(st, 'iterations', str(int(iterations)))
    for m in models:
        me = _sub(st, 'model', name=m.name)
        _sub(me, 'pose', pose_text(poses[m.name]))
        _sub(me, 'scale', '1 1 1')
        for lname, link in m.links.items():
            le = _sub(me, 'link', name=lname)
            _sub(le, 'pose', pose_text(link.pose()))
            lin, ang = link.velocity() if link.body is not None else ((0, 0, 0), (0, 0, 0))
            _sub(le, 'velocity', nums(list(lin) + list(ang)))
            _sub(le, 'acceleration', '0 0 0 0 0 0')
            _sub(le, 'wrench', '0 0 0 0 0 0')
    for light in world.lights:
        le = _sub(st, 'light', name=light.name)
        _sub(le, 'pose', pose_text(light.pose))
    return sdf


def world_sdf(world, models, **kw):
    """The saved world file's text (see world_element)."""
    root = world_element(world, models, **kw)
    ET.indent(root, '  ')
    return '<?xml version="1.0" ?>\n' + ET.tostring(root, encoding='unicode') + '\n'


# ------------------------------------------------------------------------------------------
# loading a saved world back

def read_state(path_or_text):
    """{model name: {link name: world Pose}} of a world file's <state> (a saved world); {}
    without one. Errors of the file itself are the loader's (sdf.load_world) to report."""
    try:
        if os.path.exists(path_or_text):
            root = ET.parse(path_or_text).getroot()
        else:
            root = ET.fromstring(path_or_text)
    except (ET.ParseError, OSError, TypeError, ValueError):
        return {}
    world = root.find('world') if root.tag == 'sdf' else None
    st = world.find('state') if world is not None else None
    out = {}
    if st is None:
        return out
    for mst in st.findall('model'):
        links = {}
        for lst in mst.findall('link'):
            pe = lst.find('pose')
            if pe is None or not lst.get('name'):
                continue
            try:
                links[lst.get('name')] = Pose.parse(pe.text)
            except ValueError:
                continue
        if links and mst.get('name'):
            out[mst.get('name')] = links
    return out


def apply_link_states(models, states):
    """Put the links of {name: SimModel} at the world poses of read_state() (at rest), which
    restores the joint positions a saved world had. Returns the number of links placed."""
    n = 0
    for mname, links in states.items():
        m = models.get(mname)
        if m is None or m.static:
            continue
        for lname, pose in links.items():
            link = m.links.get(lname)
            if link is None or link.body is None:
                continue
            link.set_state(pose, (0.0, 0.0, 0.0), (0.0, 0.0, 0.0))
            n += 1
    return n
