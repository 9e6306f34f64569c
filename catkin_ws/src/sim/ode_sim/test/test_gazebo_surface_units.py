"""Unit tests (no roscore) of the logic behind the rest of gazebo_ros' surface: the wrench /
effort time window, the physics reconfigure callback, light attenuations from a world file,
the range and block laser maths, hector's GPS radii and error model, the lazy /tf publisher."""
import math
import types

import numpy as np
import pytest

from ode_sim.description.model import Physics
from ode_sim.ros.gazebo_forces import Job
from ode_sim.ros.gazebo_lights import light_attenuations
from ode_sim.ros.physics_reconfigure import (PARAMETERS, PhysicsReconfigure, config_from_state,
                                             physics_config_type, request_from_config)


def test_job_window_is_gazebos():
    j = Job(None, 1.0, start=2.0, duration=0.5)
    assert not j.active(1.999) and j.active(2.0) and j.active(2.5) and not j.active(2.5001)
    assert not j.expired(2.5) and j.expired(2.5001)
    forever = Job(None, 1.0, start=0.0, duration=-1)
    assert forever.active(1e6) and not forever.expired(1e6)


class FakeApi:
    """physics_state() / set_physics() of GazeboApi on a plain Physics."""

    def __init__(self):
        self.p = Physics()
        self.g = (0.0, 0.0, -9.8)
        self.calls = []

    def physics_state(self):
        from gazebo_msgs.msg import ODEPhysics
        p = self.p
        o = ODEPhysics(auto_disable_bodies=False, sor_pgs_precon_iters=0,
                       sor_pgs_iters=p.iters, sor_pgs_w=p.sor, sor_pgs_rms_error_tol=0.0,
                       contact_surface_layer=p.contact_surface_layer,
                       contact_max_correcting_vel=p.contact_max_correcting_vel, cfm=p.cfm,
                       erp=p.erp, max_contacts=p.max_contacts)
        return p.max_step_size, p.real_time_update_rate, self.g, False, o

    def set_physics(self, req):
        self.calls.append(req)
        ok = req.time_step > 0
        if ok:
            self.p.max_step_size = req.time_step
            self.g = (req.gravity.x, req.gravity.y, req.gravity.z)
        return types.SimpleNamespace(success=ok, status_message='' if ok else 'refused')


def test_reconfigure_description_is_physics_cfg():
    t = physics_config_type()
    names = [p[0] for p in PARAMETERS]
    assert names == ['time_step', 'max_update_rate', 'gravity_x', 'gravity_y', 'gravity_z',
                     'auto_disable_bodies', 'sor_pgs_precon_iters', 'sor_pgs_iters',
                     'sor_pgs_w', 'sor_pgs_rms_error_tol', 'cfm', 'erp',
                     'contact_surface_layer', 'contact_max_correcting_vel', 'max_contacts']
    assert t.defaults['time_step'] == 0.001 and t.defaults['max_update_rate'] == 60.0
    assert t.max['max_update_rate'] == 1000.0 and t.min['sor_pgs_rms_error_tol'] == -1.0
    assert t.type['max_contacts'] == 'int' and t.all_level == 1


def test_reconfigure_callback_reads_then_applies_changes_only():
    api = FakeApi()
    rc = PhysicsReconfigure(api)
    cfg = dict(physics_config_type().defaults)
    first = rc.callback(cfg, -1)
    assert first['time_step'] == 0.001 and first['max_update_rate'] == 1000.0
    assert first['sor_pgs_iters'] == 50 and api.calls == []     # the first call only reads
    same = rc.callback(dict(first), 1)
    assert api.calls == [] and same == first                      # nothing changed: no set
    changed = dict(first, time_step=0.004, gravity_z=-1.62)
    out = rc.callback(changed, 1)
    assert len(api.calls) == 1 and api.calls[0].time_step == 0.004
    assert out['time_step'] == 0.004 and out['gravity_z'] == -1.62
    refused = rc.callback(dict(out, time_step=0.0), 1)
    assert refused['time_step'] == 0.004                          # the step in use


def test_request_round_trips_the_configuration():
    api = FakeApi()
    cfg = config_from_state(api.physics_state())
    req = request_from_config(cfg)
    assert (req.time_step, req.max_update_rate, req.gravity.z) == (0.001, 1000.0, -9.8)
    assert req.ode_config.max_contacts == 20 and req.ode_config.sor_pgs_w == 1.3


def test_light_attenuations_follow_includes(tmp_path):
    w = tmp_path / 'w.world'
    w.write_text("""<sdf version="1.6"><world name="default">
      <include><uri>model://sun</uri><name>sun2</name></include>
      <light type="point" name="lamp"><attenuation><range>5</range><linear>0.5</linear>
        </attenuation></light>
    </world></sdf>""")
    assert light_attenuations(str(w)) == {'sun2': (0.9, 0.01, 0.001), 'lamp': (1.0, 0.5, 0.0)}
    assert light_attenuations(str(tmp_path / 'missing.world')) == {}


def test_block_points_match_the_originals_formula():
    from ode_sim.ros.plugins.block_laser import block_points
    laser = types.SimpleNamespace(samples=3, v_samples=1, range_count=3, v_range_count=1,
                                  min_angle=-0.2, max_angle=0.2, v_min_angle=0.0,
                                  v_max_angle=0.0, range_min=0.1, range_max=5.0)
    pts = block_points(laser, [1.0, 2.0, 9.0], [0.0, 4.0, 0.0])
    # point 0: range of ray 0, direction halfway to ray 1; the last: capped at max - min
    assert pts[0][:2] == pytest.approx([math.cos(-0.1), math.sin(-0.1)])
    assert pts[2][:2] == pytest.approx([4.9 * math.cos(0.2), 4.9 * math.sin(0.2)])
    # intensity: the mean retro of the 4 corner rays (here rows a and b are the one row)
    assert [p[3] for p in pts] == pytest.approx([2.0, 2.0, 0.0])


def test_gps_radii_and_error_model():
    from ode_sim.ros.plugins.gps import ErrorModel, earth_radii
    rn, re = earth_radii(0.0)
    assert re == pytest.approx(6378137.0) and rn == pytest.approx(6335439.327, abs=1e-3)
    rn45, re45 = earth_radii(45.0)
    assert rn45 > rn and re45 == pytest.approx(6388838.29 * math.cos(math.radians(45)), rel=1e-6)
    plugin = types.SimpleNamespace(params={'offset': '1 2 3', 'gaussianNoise': '0'},
                                   has=lambda t: t in ('offset', 'gaussianNoise'))
    plugin.has = lambda t: t in plugin.params
    m = ErrorModel(plugin, '', np.random)
    assert m(np.zeros(3), 0.1) == pytest.approx([1, 2, 3])


def test_tf_is_advertised_only_when_a_plugin_broadcasts():
    from ode_sim.ros.plugins.rosio import MemoryIO, TfBatch
    batch = TfBatch(MemoryIO())
    assert not batch.advertised()
    batch.flush()
    assert not batch.advertised()
    batch.sendTransform([])
    assert batch.advertised()
