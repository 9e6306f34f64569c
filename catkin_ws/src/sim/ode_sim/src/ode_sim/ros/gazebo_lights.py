"""The light services of gazebo_ros_api_plugin served by ode_sim (GazeboApi's LightServices):
/gazebo/get_light_properties, set_light_properties and delete_light. The world description
keeps a light's range only; the attenuations come from the world file (`light_attenuations`)
and what set_light_properties sets. Cameras re-read the lights at their next frame.
"""
import xml.etree.ElementTree as ET

from gazebo_msgs import srv as gs

from ode_sim.ros.convert import color_msg, pose_from_msg, rgba, xyz
from ode_sim.ros.gazebo_state import failure

# SDF 1.6 <light><attenuation> defaults
ATTENUATION_DEFAULT = (1.0, 1.0, 0.0)


def attenuation_of(light):
    vals = list(ATTENUATION_DEFAULT)
    att = light.find('attenuation')
    if att is not None:
        for i, tag in enumerate(('constant', 'linear', 'quadratic')):
            e = att.find(tag)
            if e is not None and e.text:
                try:
                    vals[i] = float(e.text)
                except ValueError:
                    pass
    return tuple(vals)


def light_attenuations(world_file):
    """{light name: (constant, linear, quadratic)} of the lights a world file declares or
    includes (model://sun); the description keeps only the range. {} when the file cannot be
    read."""
    import os
    from ode_sim.description.resolve import model_sdf_file, resolve_uri
    out = {}
    try:
        root = ET.parse(world_file).getroot()
    except (OSError, ET.ParseError, TypeError):
        return out
    world = root.find('world')
    if world is None:
        return out
    for light in world.findall('light'):
        if light.get('name'):
            out[light.get('name')] = attenuation_of(light)
    for inc in world.findall('include'):
        uri = (inc.findtext('uri') or '').strip()
        try:
            path = resolve_uri(uri, os.path.dirname(os.path.abspath(world_file)))
            if os.path.isdir(path):
                path = model_sdf_file(path)
            light = ET.parse(path).getroot().find('light')
        except Exception:               # a model, or unreadable: no light here
            continue
        if light is None:
            continue
        name = (inc.findtext('name') or '').strip() or light.get('name')
        if name:
            out[name] = attenuation_of(light)
    return out


class LightServices:
    """GazeboApi's light services (mixin: uses self.node and self._attenuation)."""

    def _light(self, name):
        for light in self.node.world.lights:
            if light.name == name:
                return light
        return None

    def _lights_changed(self):
        """Cameras re-read the world's lights at their next frame."""
        ctx = getattr(self.node, 'ctx', None)
        if ctx is not None:
            ctx._render_version = -1

    def get_light_properties(self, req):
        res = gs.GetLightPropertiesResponse()
        light = self._light(req.light_name)
        if light is None:
            return failure(res, 'getLightProperties: Requested light %s not found!' % req.light_name)
        res.diffuse = color_msg(light.diffuse)
        (res.attenuation_constant, res.attenuation_linear,
         res.attenuation_quadratic) = self._attenuation.get(light.name, ATTENUATION_DEFAULT)
        res.success = True
        return res

    def set_light_properties(self, req):
        light = self._light(req.light_name)
        if light is None:
            return gs.SetLightPropertiesResponse(
                False, 'setLightProperties: Requested light %s not found!' % req.light_name)
        with self.node.lock:
            light.cast_shadows = bool(req.cast_shadows)
            light.diffuse = rgba(req.diffuse)
            light.specular = rgba(req.specular)
            light.direction = xyz(req.direction)
            light.pose = pose_from_msg(req.pose)
            self._attenuation[light.name] = (req.attenuation_constant, req.attenuation_linear,
                                             req.attenuation_quadratic)
            self._lights_changed()
        return gs.SetLightPropertiesResponse(True, '')

    def delete_light(self, req):
        with self.node.lock:
            light = self._light(req.light_name)
            if light is None:
                return gs.DeleteLightResponse(
                    False, 'DeleteLight: Requested light %s not found!' % req.light_name)
            self.node.world.lights.remove(light)
            self._lights_changed()
        return gs.DeleteLightResponse(True, 'DeleteLight: %s successfully deleted'
                                      % req.light_name)
