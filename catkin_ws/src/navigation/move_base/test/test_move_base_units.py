"""move_base pieces without a master: the planner registry, goal checks, the diploma's
planner YAML read the way TrajectoryPlannerROS reads it, the test map of the office."""
import math
import os
import subprocess

import pytest
import yaml
from geometry_msgs.msg import Quaternion

import nav_core
from base_local_planner.trajectory_planner_ros import TrajectoryPlannerROS
from dwa_local_planner.dwa_planner_ros import DWAPlannerROS
from move_base.conversions import quaternion_valid

HERE = os.path.dirname(os.path.abspath(__file__))
DIPLOMA = os.path.join(HERE, 'config/diploma')
from course_testing import world_map  # noqa: E402


def test_registry_knows_the_original_names():
    assert nav_core.load_class('global', 'navfn/NavfnROS').__name__ == 'NavfnROS'
    assert nav_core.load_class('local', 'base_local_planner/TrajectoryPlannerROS') is \
        TrajectoryPlannerROS
    assert nav_core.load_class('local', 'dwa_local_planner/DWAPlannerROS') is DWAPlannerROS
    assert nav_core.resolve_name('global', 'NavfnROS') == 'navfn/NavfnROS'   # old style
    for name in ('clear_costmap_recovery/ClearCostmapRecovery', 'rotate_recovery/RotateRecovery'):
        assert nav_core.load_class('recovery', name)


def test_unknown_planner_message():
    with pytest.raises(nav_core.PluginError) as e:
        nav_core.load_class('global', 'global_planner/GlobalPlannr')
    msg = str(e.value)
    assert 'class global_planner/GlobalPlannr with base class type ' \
           'nav_core::BaseGlobalPlanner does not exist' in msg
    assert 'navfn/NavfnROS' in msg


def test_quaternion_validity():
    assert quaternion_valid(Quaternion(0, 0, 0, 1))
    assert quaternion_valid(Quaternion(0, 0, math.sin(0.5), math.cos(0.5)))
    assert not quaternion_valid(Quaternion(0, 0, 0, 0))
    assert not quaternion_valid(Quaternion(float('nan'), 0, 0, 1))
    assert not quaternion_valid(Quaternion(1, 0, 0, 0))       # upside down


class DictParams:
    def __init__(self, d):
        self.d = d

    def has(self, name):
        return name in self.d

    def get(self, name, default, *legacy):
        for n in (name,) + legacy:
            if n in self.d:
                return self.d[n]
        return default


def test_diploma_planner_yaml(monkeypatch):
    import rospy
    monkeypatch.setattr(rospy, 'search_param', lambda name: None)
    monkeypatch.setattr(rospy, 'logwarn', lambda *a: None)
    with open(os.path.join(DIPLOMA, 'base_local_planner_params.yaml')) as f:
        params = yaml.safe_load(f)['TrajectoryPlannerROS']
    tp = TrajectoryPlannerROS()
    tp.read_params(DictParams(params))
    p = tp.p
    assert (p.max_vel_x, p.min_vel_x, p.max_vel_theta, p.min_vel_theta) == (0.6, 0.35, 0.85, -0.85)
    assert (p.min_in_place_vel_theta, p.acc_lim_theta, p.acc_lim_x, p.acc_lim_y) == (0.9, 5, 1, 1)
    assert p.holonomic_robot is False
    assert (tp.yaw_goal_tolerance, tp.xy_goal_tolerance) == (0.15, 0.2)
    # unset: the values the original ends up with (its dynamic reconfigure defaults)
    assert (p.sim_time, p.vx_samples, p.vtheta_samples) == (1.7, 20, 20)
    assert (p.pdist_scale, p.gdist_scale, p.occdist_scale) == (0.6, 0.8, 0.01)
    assert p.dwa is False and p.sim_period == pytest.approx(0.05)
    tp2 = TrajectoryPlannerROS()
    tp2.read_params(DictParams({}))
    assert (tp2.p.max_vel_x, tp2.p.min_vel_x, tp2.xy_goal_tolerance,
            tp2.yaw_goal_tolerance) == (0.55, 0.0, 0.10, 0.05)
    d = DWAPlannerROS()
    d.read_params(DictParams({}))
    assert (d.p.vx_samples, d.p.vtheta_samples, d.p.dwa) == (3, 20, True)
    assert (d.xy_goal_tolerance, d.yaw_goal_tolerance) == (0.1, 0.1)


def test_office_map_has_the_walls_and_the_door():
    world = os.path.join(HERE, '../../../space_scanner/space_scanner_simulation/worlds/'
                               'office.world')
    v, ox, oy = world_map.world_map(world)

    def at(x, y):
        return v[int((y - oy) / 0.05), int((x - ox) / 0.05)]
    assert at(0.0, -4.0) == 100 and at(6.0, 0.0) == 100       # outer walls
    assert at(0.0, 0.0) == 0 and at(0.0, 2.0) == 0             # start, the door to the corridor
    assert at(1.0, 2.0) == 100                                 # the wall beside the door
    assert at(-1.6, -1.0) == 100                               # the trash bin


def test_unknown_planner_is_fatal_with_the_original_message(roscore):
    r = subprocess.run(['rosrun', 'move_base', 'move_base',
                        '_base_global_planner:=global_planner/GlobalPlannr'],
                       env=roscore.env, capture_output=True, text=True, timeout=120)
    out = r.stdout + r.stderr
    assert r.returncode != 0
    assert 'Failed to create the global_planner/GlobalPlannr planner, are you sure it is ' \
           'properly registered and that the containing library is built?' in out
