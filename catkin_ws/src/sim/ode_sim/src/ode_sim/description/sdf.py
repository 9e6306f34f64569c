"""SDF (1.4, 1.5, 1.6) worlds and models -> the description data model (model.py).

`load_world(path)`, `parse_world(text, source)`, `parse_sdf_model(text, source, name=None)`.
Errors are one line `FILE:LINE: what` (ModelError). Frames as in model.py: link poses are in
the model frame, joint anchors/axes in the model frame.
"""
import copy
import os
import xml.etree.ElementTree as ET

from ode_sim.description.model import Light, Model, ModelError, Scene, World
from ode_sim.description.resolve import ModelPaths
from ode_sim.description.sdf_elements import parse_joint, parse_link, read_nums
from ode_sim.description.sdf_sensors import parse_plugin
from ode_sim.description.transforms import Pose
from ode_sim.description.xmldoc import ParseContext, parse_xml, sdf_version, text_of


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
        sub_name = text_of(inc, 'name') or sub_el.get('name')
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
        model.sdf_element = _saved_form(ctx, el)
    return model


def _saved_form(ctx, el):
    """The <model> as Save World writes it into an SDF 1.6 file anywhere: a copy where joint
    axes of SDF 1.4 without <use_parent_model_frame> say they were in the model frame, and URIs
    that are paths relative to this file become absolute file:// URIs."""
    el = copy.deepcopy(el)
    if ctx.v14:
        for joint in el.iter('joint'):
            for tag in ('axis', 'axis2'):
                ax = joint.find(tag)
                if ax is not None and ax.find('use_parent_model_frame') is None:
                    ET.SubElement(ax, 'use_parent_model_frame').text = 'true'
    for u in el.iter('uri'):
        uri = (u.text or '').strip()
        if not uri or '://' in uri or os.path.isabs(uri) or uri.startswith('__'):
            continue
        try:
            u.text = 'file://' + ctx.paths.resolve_uri(uri, ctx.base_dir)
        except ModelError:
            pass                        # the loader has said what is wrong with it
    return el


def _include_element(ctx, inc):
    """(root element of the included file: <model> or <light>, its context)."""
    uri = text_of(inc, 'uri')
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
    sub_ctx = ParseContext(doc, ctx.paths, os.path.dirname(path), ctx.warnings, sdf_version(doc))
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
    new_name = text_of(inc, 'name')
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
    read_nums(ctx, el, physics, [(n, n) for n in (
        'max_step_size', 'real_time_update_rate', 'real_time_factor')])
    physics.max_contacts = ctx.integer(el, 'max_contacts', physics.max_contacts)
    if physics.max_step_size <= 0:
        raise ctx.err(el.find('max_step_size'), '<max_step_size> must be positive')
    if physics.real_time_update_rate < 0:
        raise ctx.err(el.find('real_time_update_rate'), '<real_time_update_rate> must be >= 0')
    ode = el.find('ode')
    if ode is not None:
        solver = ode.find('solver')
        if solver is not None:
            physics.solver_type = text_of(solver, 'type', physics.solver_type)
            if physics.solver_type not in ('quick', 'world'):
                raise ctx.err(solver, '<solver><type> must be quick or world, got %r'
                              % physics.solver_type)
            physics.iters = ctx.integer(solver, 'iters', physics.iters)
            physics.sor = ctx.num(solver, 'sor', physics.sor)
        read_nums(ctx, ode.find('constraints'), physics, [(n, n) for n in (
            'cfm', 'erp', 'contact_max_correcting_vel', 'contact_surface_layer')])
    return physics


def _world_from_doc(doc, paths, base_dir):
    warnings = []
    if doc.root.tag != 'sdf':
        raise doc.error(doc.root, 'expected <sdf> as the root element, got <%s>' % doc.root.tag)
    version = sdf_version(doc)
    ctx = ParseContext(doc, paths, base_dir, warnings, version)
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
            m = parse_model(ParseContext(doc, paths, base_dir, [], version), child)
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
                m.include_uri = text_of(child, 'uri')
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


SPAWNABLE = ('model', 'light', 'include')


def _spawn_element(text, source, paths):
    """(context, element) of a spawn request's SDF: the <model>, <light> or <include> that is
    the root or the first of those children of <sdf>, else the first of those in <sdf><world>
    (gazebo_ros' spawn_model -database sends <sdf><world><include>, which gazebo_ros'
    updateSDFAttributes looks for after <sdf><model>)."""
    doc = parse_xml(text, source)
    root = doc.root
    el = root if root.tag in SPAWNABLE else None
    if el is None and root.tag == 'sdf':
        el = next((c for c in root if c.tag in SPAWNABLE), None)
        world = root.find('world')
        if el is None and world is not None:
            el = next((c for c in world if c.tag in SPAWNABLE), None)
    if el is None:
        if root.tag == 'robot':
            raise doc.error(root, 'this is URDF (<robot>), not SDF: spawn it with -urdf')
        raise doc.error(root, 'no <model>, <include> or <light> in the SDF')
    base_dir = os.path.dirname(os.path.abspath(source)) if os.path.exists(source) \
        else os.getcwd()
    ctx = ParseContext(doc, paths or ModelPaths(), base_dir, [], sdf_version(doc))
    return ctx, el


def parse_sdf_light(text, source, paths=None, name=None):
    """The Light a spawn request's SDF describes (<light>, or an <include> of a file whose
    element is a light, e.g. model://sun), `name` replacing its name; None when the SDF
    describes a model."""
    ctx, el = _spawn_element(text, source, paths)
    if el.tag == 'include':
        sub_el, sub_ctx = _include_element(ctx, el)
        if sub_el.tag != 'light':
            return None
        _apply_include_overrides(ctx, el, sub_el)
        ctx, el = sub_ctx, sub_el
    if el.tag != 'light':
        return None
    if name:
        el.set('name', name)
    light = parse_light(ctx, el)
    light.element = el
    return light


def parse_sdf_model(text, source, paths=None, name=None):
    """Model from SDF text whose root is <sdf><model> (or <model>), e.g. the model_xml of
    /gazebo/spawn_sdf_model, or an include of a model://: <sdf><include>, <sdf><world><include>
    (gazebo_ros' spawn_model -database) or <include> (the model remembers its URI, include_uri,
    for Save World); `name` replaces the model's name.

    Model.pose is the model's own pose that a spawn composes with its initial pose
    (spawning.spawn_pose): the <model>'s <pose>; for an include the <include>'s <pose>, the
    identity without one (gazebo_ros always writes a <pose> into the include, which replaces
    the included file's own <pose>)."""
    ctx, mel = _spawn_element(text, source, paths)
    if mel.tag == 'light':
        raise ctx.doc.error(mel, 'this SDF describes a light, not a model')
    uri = ''
    own = None
    if mel.tag == 'include':
        inc = mel
        mel, sub_ctx = _include_element(ctx, inc)
        if mel.tag != 'model':
            raise ctx.err(inc, '<include> of a light: spawn it as a light')
        _apply_include_overrides(ctx, inc, mel)
        uri = text_of(inc, 'uri')
        own = ctx.pose(inc)
        ctx = sub_ctx
    if name:
        mel.set('name', name)
    model = parse_model(ctx, mel)
    model.include_uri = uri
    if own is not None:
        model.pose = own
    return model
