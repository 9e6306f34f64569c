"""Gazebo's physics dynamic_reconfigure on ode_sim: /gazebo/set_parameters,
/gazebo/parameter_descriptions and /gazebo/parameter_updates with the parameters of gazebo_ros'
cfg/Physics.cfg (names, types, defaults, limits and level 1), so `rqt_reconfigure` shows the
simulator and changes its step size, update rate, gravity and ODE solver settings live.

As gazebo_ros_api_plugin's physicsReconfigureCallback: the first call fills the configuration
from get_physics_properties; later calls compare the request with get_physics_properties and,
when something differs, apply the whole configuration as set_physics_properties would. The
configuration returned (and published on parameter_updates) is what the simulator then runs
with, so a rejected value (a zero step) shows the value kept.

The description is built here in the form dynamic_reconfigure's generator writes it
(PhysicsConfig.py), so no generated module is needed.
"""
import types

from dynamic_reconfigure.encoding import extract_params

# name, type, default, min, max, description (limits and defaults: gazebo_ros cfg/Physics.cfg)
PARAMETERS = [
    ('time_step', 'double', 0.001, 0.0, 10.0,
     'Length of one physics step in seconds (sim time advances by this per step).'),
    ('max_update_rate', 'double', 60.0, 0.0, 1000.0,
     'Physics steps per wall second at most; 0 steps as fast as possible.'),
    ('gravity_x', 'double', 0.0, -100.0, 100.0, 'Gravity along the world x axis (m/s^2).'),
    ('gravity_y', 'double', 0.0, -100.0, 100.0, 'Gravity along the world y axis (m/s^2).'),
    ('gravity_z', 'double', -9.8, -100.0, 100.0, 'Gravity along the world z axis (m/s^2).'),
    ('auto_disable_bodies', 'bool', False, False, True,
     'Let bodies at rest fall asleep until something touches them.'),
    ('sor_pgs_precon_iters', 'int', 0, 0, 10000,
     'Preconditioning iterations of the quickstep solver.'),
    ('sor_pgs_iters', 'int', 20, 0, 10000, 'Iterations of the quickstep (SOR PGS) solver.'),
    ('sor_pgs_w', 'double', 1.3, 0.0, 5.0, 'Over-relaxation factor of the quickstep solver.'),
    ('sor_pgs_rms_error_tol', 'double', -1.0, -1.0, 10000.0,
     'RMS error tolerance of the quickstep solver.'),
    ('cfm', 'double', 0.0, 0.0, 10.0, 'Global constraint force mixing (ODE).'),
    ('erp', 'double', 0.2, 0.0, 10.0, 'Global error reduction parameter (ODE).'),
    ('contact_surface_layer', 'double', 0.001, 0.0, 10.0,
     'Penetration depth allowed before contacts push back (m).'),
    ('contact_max_correcting_vel', 'double', 100.0, 0.0, 10000000.0,
     'Largest velocity contacts may use to correct penetration (m/s).'),
    ('max_contacts', 'int', 100, 0, 10000000, 'Contacts between two bodies at most.'),
]
_CTYPE = {'double': 'double', 'int': 'int', 'bool': 'bool'}


def physics_config_type():
    """A module-like object with what dynamic_reconfigure.server.Server reads of a generated
    <Name>Config module: config_description, defaults, min, max, level, type, all_level."""
    params = []
    for name, typ, default, lo, hi, descr in PARAMETERS:
        params.append({'name': name, 'type': typ, 'default': default, 'level': 1,
                       'description': descr, 'min': lo, 'max': hi, 'srcline': 0,
                       'srcfile': 'ode_sim/ros/physics_reconfigure.py', 'edit_method': '',
                       'ctype': _CTYPE[typ], 'cconsttype': 'const ' + _CTYPE[typ]})
    descr = {'name': 'Default', 'type': '', 'state': True, 'cstate': 'true', 'id': 0,
             'parent': 0, 'parameters': params, 'groups': [], 'srcline': 0,
             'srcfile': 'ode_sim/ros/physics_reconfigure.py', 'class': 'DEFAULT',
             'parentclass': '', 'parentname': 'Default', 'field': 'default',
             'upper': 'DEFAULT', 'lower': 'groups'}
    t = types.SimpleNamespace(config_description=descr, min={}, max={}, defaults={}, level={},
                              type={}, all_level=0)
    for p in extract_params(descr):
        t.min[p['name']] = p['min']
        t.max[p['name']] = p['max']
        t.defaults[p['name']] = p['default']
        t.level[p['name']] = p['level']
        t.type[p['name']] = p['type']
        t.all_level |= p['level']
    return t


def config_from_state(state):
    """{parameter: value} from GazeboApi.physics_state()."""
    time_step, rate, g, _paused, o = state
    return {'time_step': time_step, 'max_update_rate': rate,
            'gravity_x': g[0], 'gravity_y': g[1], 'gravity_z': g[2],
            'auto_disable_bodies': bool(o.auto_disable_bodies),
            'sor_pgs_precon_iters': int(o.sor_pgs_precon_iters),
            'sor_pgs_iters': int(o.sor_pgs_iters), 'sor_pgs_w': o.sor_pgs_w,
            'sor_pgs_rms_error_tol': o.sor_pgs_rms_error_tol, 'cfm': o.cfm, 'erp': o.erp,
            'contact_surface_layer': o.contact_surface_layer,
            'contact_max_correcting_vel': o.contact_max_correcting_vel,
            'max_contacts': int(o.max_contacts)}


def request_from_config(config):
    """The gazebo_msgs/SetPhysicsProperties request for a configuration."""
    from gazebo_msgs.srv import SetPhysicsPropertiesRequest
    req = SetPhysicsPropertiesRequest()
    req.time_step = float(config['time_step'])
    req.max_update_rate = float(config['max_update_rate'])
    req.gravity.x = float(config['gravity_x'])
    req.gravity.y = float(config['gravity_y'])
    req.gravity.z = float(config['gravity_z'])
    o = req.ode_config
    o.auto_disable_bodies = bool(config['auto_disable_bodies'])
    o.sor_pgs_precon_iters = int(config['sor_pgs_precon_iters'])
    o.sor_pgs_iters = int(config['sor_pgs_iters'])
    o.sor_pgs_w = float(config['sor_pgs_w'])
    o.sor_pgs_rms_error_tol = float(config['sor_pgs_rms_error_tol'])
    o.contact_surface_layer = float(config['contact_surface_layer'])
    o.contact_max_correcting_vel = float(config['contact_max_correcting_vel'])
    o.cfm = float(config['cfm'])
    o.erp = float(config['erp'])
    o.max_contacts = int(config['max_contacts'])
    return req


class PhysicsReconfigure:
    """The callback logic, on a GazeboApi (physics_state(), set_physics(req)); no ROS needed.
    `server(namespace)` starts dynamic_reconfigure's Server on it."""

    def __init__(self, api, log=None):
        self.api = api
        self.initialized = False
        self.log = log or (lambda text: None)

    def callback(self, config, level):
        current = config_from_state(self.api.physics_state())
        if not self.initialized:
            config.update(current)
            self.initialized = True
            return config
        if any(config[k] != v for k, v in current.items()):
            res = self.api.set_physics(request_from_config(config))
            if not res.success:
                self.log('physics dynamic reconfigure: %s' % res.status_message)
            self.log('physics dynamics reconfigure update complete')
            config.update(config_from_state(self.api.physics_state()))
        self.log('physics dynamics reconfigure complete')
        return config

    def server(self, namespace=''):
        from dynamic_reconfigure.server import Server
        return Server(physics_config_type(), self.callback, namespace=namespace)
