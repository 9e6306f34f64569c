"""SDF <sensor> and <plugin> elements (the description data model, model.py): a sensor's type
specific parameters (ray, camera, imu, contact) in Sensor.params under the names the engine's
sensor models read. Errors: ModelError `FILE:LINE: what`."""
import math
import xml.etree.ElementTree as ET

from ode_sim.description.model import Plugin, Sensor
from ode_sim.description.xmldoc import text_of


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


def _camera_entry(ctx, cam, sensor_name):
    img = cam.find('image')
    img = img if img is not None else ET.Element('image')
    clip = cam.find('clip')
    clip = clip if clip is not None else ET.Element('clip')
    mean, std = _noise(ctx, cam)
    return {'name': (cam.get('name') or '').strip(), 'pose': ctx.pose(cam),
            'horizontal_fov': ctx.num(cam, 'horizontal_fov', 1.047),
            'width': ctx.integer(img, 'width', 320), 'height': ctx.integer(img, 'height', 240),
            'format': text_of(img, 'format', 'R8G8B8'), 'near': ctx.num(clip, 'near', 0.1),
            'far': ctx.num(clip, 'far', 100.0), 'noise_mean': mean, 'noise_stddev': std}


def parse_sensor(ctx, el, link_name):
    """A Sensor from an SDF <sensor> (link_name: the link it is attached to)."""
    name = ctx.name(el, 'sensor')
    stype = (el.get('type') or '').strip()
    if not stype:
        raise ctx.err(el, '<sensor name=%r> needs a type attribute' % name)
    sensor = Sensor(name=name, type=stype, link=link_name, element=el)
    sensor.pose = ctx.pose(el, link_name)
    sensor.update_rate = ctx.num(el, 'update_rate', 0.0)
    sensor.always_on = ctx.boolean(el, 'always_on', True)
    sensor.visualize = ctx.boolean(el, 'visualize', False)
    sensor.topic = text_of(el, 'topic', '') or ''
    if stype in ('ray', 'gpu_ray'):
        _ray_params(ctx, el, sensor)
    elif stype in ('camera', 'depth', 'multicamera', 'wideanglecamera'):
        _camera_params(ctx, el, sensor)
    elif stype == 'imu':
        _imu_params(ctx, el, sensor)
    elif stype == 'contact':
        _contact_params(ctx, el, sensor)
    else:
        ctx.warn(el, '<sensor name=%r type=%r>: sensor type not simulated, kept without data'
                 % (name, stype))
    for pl in el.findall('plugin'):
        sensor.plugins.append(parse_plugin(ctx, pl))
    return sensor


def _ray_params(ctx, el, sensor):
    """<ray> (or <lidar>) of a ray / gpu_ray sensor into its params."""
    name, p = sensor.name, sensor.params
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


def _camera_params(ctx, el, sensor):
    """<camera> of a camera / depth / multicamera / wideanglecamera sensor into its params."""
    name, p = sensor.name, sensor.params
    cam = el.find('camera')
    cam = cam if cam is not None else ET.Element('camera')
    p['horizontal_fov'] = ctx.num(cam, 'horizontal_fov', 1.047)
    img = cam.find('image')
    img = img if img is not None else ET.Element('image')
    p['width'] = ctx.integer(img, 'width', 320)
    p['height'] = ctx.integer(img, 'height', 240)
    p['format'] = text_of(img, 'format', 'R8G8B8')
    clip = cam.find('clip')
    clip = clip if clip is not None else ET.Element('clip')
    p['near'] = ctx.num(clip, 'near', 0.1)
    p['far'] = ctx.num(clip, 'far', 100.0)
    p['noise_mean'], p['noise_stddev'] = _noise(ctx, cam)
    if p['width'] < 1 or p['height'] < 1:
        raise ctx.err(img, '<sensor name=%r>: image width/height must be >= 1' % name)
    if not 0 < p['horizontal_fov'] < 2 * math.pi + 1e-9:
        raise ctx.err(cam, '<sensor name=%r>: <horizontal_fov> must be in (0, 2 pi)' % name)
    if sensor.type == 'multicamera':
        # every <camera> of the sensor (name, pose in the sensor frame, its own image),
        # for libgazebo_ros_multicamera.so
        p['cameras'] = [_camera_entry(ctx, c, name) for c in el.findall('camera')]


def _imu_params(ctx, el, sensor):
    """<imu> noise (SDF 1.5+ per axis, SDF 1.4 <noise><rate>/<accel>) into its params."""
    p = sensor.params
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
        sensor.topic = text_of(imu, 'topic', '') or ''


def _contact_params(ctx, el, sensor):
    """<contact><collision> names (and <topic>) of a contact sensor."""
    name, p = sensor.name, sensor.params
    contact = el.find('contact')
    names = [(c.text or '').strip() for c in (contact.findall('collision')
                                              if contact is not None else [])]
    if not names or not all(names):
        raise ctx.err(el, '<sensor name=%r type="contact"> needs <contact><collision>NAME'
                          '</collision></contact> naming collisions of its link' % name)
    p['collisions'] = names
    if not sensor.topic:
        sensor.topic = text_of(contact, 'topic', '') or ''


def _wrap_noise(el):
    w = ET.Element('w')
    n = ET.SubElement(w, 'noise')
    for c in el:
        n.append(c)
    return w
