"""The ros_control bridge as a user meets it: `roslaunch gazebo_ros empty_world.launch
lockstep:=true`, `rosrun gazebo_ros spawn_model -urdf -file arm.urdf -model arm`, a URDF with
libgazebo_ros_control.so and two transmissions, and a controller-side client that speaks only
the documented topics (control_client.py, in place of gazebo_ros_control_node:
<controllerNode>false</controllerNode>): the arm holds its position, the wheel tracks its
velocity, and with lockstep every control period of sim time is answered."""
import json
import os
import subprocess

import numpy as np
import pytest

from course_testing import Proc, wait_for

HERE = os.path.dirname(os.path.abspath(__file__))

URDF = """<?xml version="1.0"?>
<robot name="arm">
  <link name="world"/>
  <joint name="fix" type="fixed"><parent link="world"/><child link="base"/></joint>
  <link name="base"><inertial><mass value="5"/>
      <inertia ixx="0.1" ixy="0" ixz="0" iyy="0.1" iyz="0" izz="0.1"/></inertial>
    <collision><geometry><box size="0.2 0.2 0.2"/></geometry></collision></link>
  <link name="arm"><inertial><origin xyz="0.25 0 0"/><mass value="0.5"/>
      <inertia ixx="0.001" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial>
    <collision><origin xyz="0.25 0 0"/><geometry><box size="0.5 0.04 0.04"/></geometry></collision></link>
  <joint name="arm_joint" type="revolute"><parent link="base"/><child link="arm"/>
    <origin xyz="0 0.2 1.0"/><axis xyz="0 1 0"/><limit lower="-2" upper="2" effort="20" velocity="3"/></joint>
  <link name="wheel"><inertial><mass value="0.3"/>
      <inertia ixx="0.001" ixy="0" ixz="0" iyy="0.001" iyz="0" izz="0.001"/></inertial>
    <collision><geometry><cylinder radius="0.05" length="0.02"/></geometry></collision></link>
  <joint name="wheel_joint" type="continuous"><parent link="base"/><child link="wheel"/>
    <origin xyz="0 -0.2 1.0" rpy="1.5708 0 0"/><axis xyz="0 0 1"/><limit effort="5" velocity="10"/></joint>
  <transmission name="arm_tr"><type>transmission_interface/SimpleTransmission</type>
    <joint name="arm_joint"><hardwareInterface>hardware_interface/PositionJointInterface</hardwareInterface></joint>
    <actuator name="arm_motor"><mechanicalReduction>1</mechanicalReduction></actuator></transmission>
  <transmission name="wheel_tr"><type>transmission_interface/SimpleTransmission</type>
    <joint name="wheel_joint"><hardwareInterface>hardware_interface/VelocityJointInterface</hardwareInterface></joint>
    <actuator name="wheel_motor"><mechanicalReduction>1</mechanicalReduction></actuator></transmission>
  <gazebo><plugin name="gazebo_ros_control" filename="libgazebo_ros_control.so">
    <controlPeriod>0.01</controlPeriod><controllerNode>false</controllerNode></plugin></gazebo>
</robot>
"""


def test_position_hold_and_wheel_velocity_in_lockstep(roscore, tmp_path):
    env = dict(roscore.env)
    env.pop('DISPLAY', None)
    urdf = tmp_path / 'arm.urdf'
    urdf.write_text(URDF)
    sim = Proc(['roslaunch', 'gazebo_ros', 'empty_world.launch', 'lockstep:=true', 'gui:=false',
                'paused:=true'], env=env, log=str(tmp_path / 'sim.log'))
    try:
        # the lockstep wait is wall time: give a loaded machine's client far more than 1 s, so
        # that the assertion below proves lockstep rather than the machine's speed
        subprocess.run(['rosparam', 'set', '/ode_sim/lockstep_timeout', '60.0'], env=env,
                       check=True, timeout=60, capture_output=True)
        spawn = subprocess.run(['rosrun', 'gazebo_ros', 'spawn_model', '-urdf', '-file', str(urdf),
                                '-model', 'arm'], env=env, capture_output=True, text=True,
                               timeout=120)
        assert spawn.returncode == 0, spawn.stdout + spawn.stderr + sim.output()
        client = Proc(['python3', os.path.join(HERE, 'control_client.py'), '3.0'], env=env,
                      log=str(tmp_path / 'client.log'))
        wait_for(lambda: '/control_client' in subprocess.run(
            ['rostopic', 'info', '/ode_sim/joint_commands'], env=env, capture_output=True,
            text=True, timeout=30).stdout, 60, 0.5, 'the client publishing joint_commands')
        subprocess.run(['rosservice', 'call', '/gazebo/unpause_physics'], env=env, check=True,
                       timeout=30, capture_output=True)
        line = wait_for(lambda: next((l for l in client.output().splitlines()
                                      if l.startswith('{')), None), 120, 0.5, 'the client report')
    finally:
        sim.stop()
    out = json.loads(line)
    assert [j['name'] for j in out['joints']] == ['arm_joint', 'wheel_joint']
    assert [j['interface'] for j in out['joints']] == ['PositionJointInterface',
                                                       'VelocityJointInterface']
    assert out['period'] == pytest.approx(0.01)
    stamps = np.array(out['stamps'])
    steps = np.diff(stamps[stamps > 0.05])
    # lockstep: one state per control period, none skipped however slow the client answers
    assert steps == pytest.approx([0.01] * len(steps), abs=1e-6)
    late = np.array(out['arm'])[stamps > 2.0]
    assert late == pytest.approx([0.5] * len(late), abs=0.01)       # held against gravity
    wv = np.array(out['wheel_vel'])[stamps > 1.0]
    assert wv == pytest.approx([2.0] * len(wv), rel=0.02)
    log = sim.output()
    # every period answered, and none waited out at the end: the client unregisters before it
    # exits and the simulator stops waiting for a controller that is gone
    assert 'lockstep: no joint command' not in log, log[-3000:]
