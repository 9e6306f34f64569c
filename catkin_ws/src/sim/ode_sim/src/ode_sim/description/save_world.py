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


def _fill(el, **children):
    """EL with a child a keyword, in order, its text the value (a None value: no child)."""
    for tag, text in children.items():
        if text is not None:
            _sub(el, tag, text)
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
    p = _fill(_sub(parent, 'physics', name='default_physics', default='0', type='ode'),
              max_step_size=num(physics.max_step_size),
              real_time_factor=num(physics.real_time_factor),
              real_time_update_rate=num(physics.real_time_update_rate),
              max_contacts=str(int(physics.max_contacts)))
    ode = _sub(p, 'ode')
    _fill(_sub(ode, 'solver'), type=physics.solver_type, iters=str(int(physics.iters)),
          sor=num(physics.sor))
    _fill(_sub(ode, 'constraints'), cfm=num(physics.cfm), erp=num(physics.erp),
          contact_max_correcting_vel=num(physics.contact_max_correcting_vel),
          contact_surface_layer=num(physics.contact_surface_layer))
    return p


def scene_element(parent, scene):
    return _fill(_sub(parent, 'scene'), ambient=nums(scene.ambient),
                 background=nums(scene.background), shadows=_flag(scene.shadows))


def light_element(parent, light, attenuation=None):
    el = _fill(_sub(parent, 'light', name=light.name, type=light.type),
               cast_shadows=_flag(light.cast_shadows), pose=pose_text(light.pose),
               diffuse=nums(light.diffuse), specular=nums(light.specular))
    att = _fill(_sub(el, 'attenuation'), range=num(light.attenuation_range))
    if attenuation is not None:
        _fill(att, **{tag: num(v) for tag, v in zip(('constant', 'linear', 'quadratic'), attenuation)})
    _sub(el, 'direction', nums(light.direction))
    return el


# ------------------------------------------------------------------------------------------
# a model from its description (robots spawned from URDF)

def geometry_element(parent, g):
    el = _sub(parent, 'geometry')
    if g.kind == 'box':
        _fill(_sub(el, 'box'), size=nums(g.size))
    elif g.kind == 'cylinder':
        _fill(_sub(el, 'cylinder'), radius=num(g.radius), length=num(g.length))
    elif g.kind == 'sphere':
        _fill(_sub(el, 'sphere'), radius=num(g.radius))
    elif g.kind == 'plane':
        _fill(_sub(el, 'plane'), normal=nums(g.normal), size=nums(g.plane_size))
    elif g.kind == 'mesh':
        uri = g.uri
        if not uri.startswith(('model://', 'package://', 'file://')) and g.filename:
            uri = 'file://' + g.filename     # a relative path would not survive a move
        m = _fill(_sub(el, 'mesh'), uri=uri)
        if g.submesh:
            _fill(_sub(m, 'submesh'), name=g.submesh, center=_flag(g.center))
        _sub(m, 'scale', nums(g.scale))
    else:
        raise ValueError('geometry kind %r cannot be saved' % g.kind)
    return el


def surface_element(parent, s):
    el = _sub(parent, 'surface')
    _fill(_sub(_sub(el, 'friction'), 'ode'), mu=num(s.mu1), mu2=num(s.mu2),
          fdir1=None if s.fdir1 is None else nums(s.fdir1), slip1=num(s.slip1), slip2=num(s.slip2))
    _fill(_sub(_sub(el, 'contact'), 'ode'), kp=num(s.kp), kd=num(s.kd), max_vel=num(s.max_vel),
          min_depth=num(s.min_depth))
    _fill(_sub(el, 'bounce'), restitution_coefficient=num(s.bounce),
          threshold=num(s.bounce_threshold))
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
        _fill(_sub(el, 'script'), uri=GAZEBO_MATERIAL, name=v.material_name)
    color = tuple(v.color)
    ambient = mat.ambient if mat is not None and mat.ambient is not None else color
    spec = tuple(mat.specular) if mat is not None else (0.1, 0.1, 0.1)
    emis = tuple(mat.emissive) if mat is not None else (0.0, 0.0, 0.0)
    return _fill(el, ambient=nums(ambient), diffuse=nums(color),
                 specular=nums(tuple(spec[:3]) + (1.0,)), emissive=nums(tuple(emis[:3]) + (1.0,)))


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
    el = _fill(_sub(parent, 'link', name=link.name), pose=pose_text(link.pose))
    ine = link.inertial
    if ine is not None and not static:
        i = _fill(_sub(el, 'inertial'), pose=pose_text(ine.pose), mass=num(ine.mass))
        _fill(_sub(i, 'inertia'), **{tag: num(getattr(ine, tag))
                                     for tag in ('ixx', 'ixy', 'ixz', 'iyy', 'iyz', 'izz')})
    for c in link.collisions:
        ce = _fill(_sub(el, 'collision', name=c.name), pose=pose_text(c.pose),
                   laser_retro=num(c.laser_retro) if c.laser_retro else None)
        geometry_element(ce, c.geometry)
        surface_element(ce, c.surface)
    for v in link.visuals:
        ve = _fill(_sub(el, 'visual', name=v.name), pose=pose_text(v.pose))
        geometry_element(ve, v.geometry)
        material_element(ve, v)
    for s in link.sensors:
        if s.element is None:
            continue
        se = _with_namespace(s.element, namespace)
        se.set('name', s.name)
        _set_pose(se, s.pose)
        el.append(se)
    return _fill(el, gravity=_flag(link.gravity), self_collide=_flag(link.self_collide),
                 kinematic=_flag(link.kinematic))


def joint_element(parent, joint, model):
    el = _sub(parent, 'joint', name=joint.name,
              type='revolute' if joint.type == 'continuous' else joint.type)
    parent_pose = Pose() if joint.parent == 'world' else model.link(joint.parent).pose
    frame = parent_pose * joint.origin          # joint frame in the model frame
    _fill(el, parent=joint.parent, child=joint.child,
          pose=pose_text(model.link(joint.child).pose.inverse() * frame))
    if joint.type in ('fixed', 'ball'):
        return el
    ax = _fill(_sub(el, 'axis'), xyz=nums(joint.axis), use_parent_model_frame='1')
    _fill(_sub(ax, 'limit'), lower=num(-NO_LIMIT if joint.lower is None else joint.lower),
          upper=num(NO_LIMIT if joint.upper is None else joint.upper),
          effort=num(-1 if joint.effort is None else joint.effort),
          velocity=num(-1 if joint.velocity is None else joint.velocity))
    _fill(_sub(ax, 'dynamics'), damping=num(joint.damping), friction=num(joint.friction))
    return el


def model_element(desc, pose, name=None):
    """A full SDF <model> of a description at `pose` (what Gazebo writes for a robot spawned
    from URDF)."""
    el = _fill(ET.Element('model', name=name or desc.name), pose=pose_text(pose))
    for link in desc.links:
        link_element(el, link, desc.static, desc.robot_namespace)
    for joint in desc.joints:
        joint_element(el, joint, desc)
    for p in desc.plugins:
        if p.element is not None:
            el.append(_with_namespace(p.element, desc.robot_namespace))
    return _fill(el, static=_flag(desc.static), allow_auto_disable=_flag(desc.allow_auto_disable))


def saved_model(desc, pose):
    """The element Save World writes for one model at `pose`: <include> for model://, the
    SDF <model> it was given as, or a full <model> built from the description (URDF)."""
    if desc.include_uri:
        return _fill(ET.Element('include'), uri=desc.include_uri, name=desc.name,
                     pose=pose_text(pose), static='1' if desc.static else None)
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
    st = _fill(_sub(w, 'state', world_name=world.name), sim_time=_time_text(sim_time),
               real_time=_time_text(real_time),
               wall_time=_time_text(time.time() if wall_time is None else wall_time),
               iterations=str(int(iterations)))
    for m in models:
        me = _fill(_sub(st, 'model', name=m.name), pose=pose_text(poses[m.name]), scale='1 1 1')
        for lname, link in m.links.items():
            lin, ang = link.velocity() if link.body is not None else ((0, 0, 0), (0, 0, 0))
            _fill(_sub(me, 'link', name=lname), pose=pose_text(link.pose()),
                  velocity=nums(list(lin) + list(ang)), acceleration='0 0 0 0 0 0',
                  wrench='0 0 0 0 0 0')
    for light in world.lights:
        _fill(_sub(st, 'light', name=light.name), pose=pose_text(light.pose))
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
