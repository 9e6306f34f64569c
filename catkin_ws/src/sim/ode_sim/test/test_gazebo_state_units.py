"""Unit tests (no roscore) of the /gazebo/* services' lookups (StateServices._model, _link,
_reference, _seen_from) on a real PhysicsWorld: every "not found" answer and error line is
gazebo_ros_api_plugin's text, and states are read relative to the reference entity."""
import io
import math
import threading
import types

import numpy as np
import pytest
from gazebo_msgs import msg as gm
from gazebo_msgs import srv as gs

from ode_sim.description import sdf
from ode_sim.description.model import World
from ode_sim.description.transforms import Pose
from ode_sim.engine.physics import PhysicsWorld
from ode_sim.ros import convert, world_control
from ode_sim.ros.gazebo_api import GazeboApi

BOX = """<sdf version="1.6"><model name="box">
  <link name="link"><collision name="c"><geometry><box><size>1 1 1</size></box></geometry></collision>
  </link></model></sdf>"""
LAMP = ('<sdf version="1.6"><light name="lamp" type="point"><pose>0 0 1 0 0 0</pose>'
        '<diffuse>1 1 1 1</diffuse></light></sdf>')


@pytest.fixture
def api(monkeypatch):
    """GazeboApi's services over a world with a box at (1, 2, 0.5) turned 90 degrees; .log
    holds what rospy.logerr was given."""
    import rospy
    log = []
    monkeypatch.setattr(rospy, 'logerr', lambda m, *a: log.append(m % a if a else m))
    world = World()
    pw = PhysicsWorld(world.physics, (0.0, 0.0, 0.0))
    desc = sdf.parse_sdf_model(BOX, 'box.sdf', name='box')
    desc.pose = Pose.from_xyz_rpy((1, 2, 0.5), (0, 0, math.pi / 2))
    pw.add_model(desc)
    a = GazeboApi.__new__(GazeboApi)        # the services without their ROS publishers
    a.node = types.SimpleNamespace(physics=pw, lock=threading.RLock(), world=world)
    a._get_model_state_count, a._wrenches, a._efforts, a._attenuation = {}, [], [], {}
    a.log = log
    return a


def answer(api, res):
    """(success, status_message, the error lines logged) of one call."""
    ok, text = res if isinstance(res, tuple) else (res.success, res.status_message)
    logged = list(api.log)
    api.log.clear()
    return ok, text, logged


def test_missing_model_answers_and_log_lines(api):
    assert answer(api, api.get_model_state(gs.GetModelStateRequest(model_name='ghost'))) == (
        False, 'GetModelState: model does not exist', ['GetModelState: model [ghost] does not exist'])
    assert answer(api, api.set_model_state(gs.SetModelStateRequest(gm.ModelState(model_name='ghost')))) == (
        False, 'SetModelState: model does not exist', ['Updating ModelState: model [ghost] does not exist'])
    assert answer(api, api.set_model_configuration(gs.SetModelConfigurationRequest(model_name='ghost'))) == (
        False, 'SetModelConfiguration: model does not exist',
        ['SetModelConfiguration: model [ghost] does not exist'])
    assert answer(api, api.get_model_properties(gs.GetModelPropertiesRequest(model_name='ghost'))) == (
        False, 'GetModelProperties: model does not exist', ['GetModelProperties: model [ghost] does not exist'])
    assert answer(api, api.delete_model(gs.DeleteModelRequest(model_name='ghost'))) == (
        False, 'DeleteModel: model does not exist', ['DeleteModel: model [ghost] does not exist'])


def test_missing_link_answers(api):
    scope = 'link not found, did you forget to scope the link by model name?'
    assert answer(api, api.get_link_state(gs.GetLinkStateRequest(link_name='nolink'))) == (
        False, 'GetLinkState: ' + scope, [])
    assert answer(api, api.get_link_properties(gs.GetLinkPropertiesRequest(link_name='box::nolink'))) == (
        False, 'GetLinkProperties: ' + scope, [])
    assert answer(api, api.set_link_properties(gs.SetLinkPropertiesRequest(link_name='nolink'))) == (
        False, 'SetLinkProperties: ' + scope, [])
    assert answer(api, api.set_link_state(gs.SetLinkStateRequest(gm.LinkState(link_name='nolink')))) == (
        False, 'SetLinkState: link does not exist', ['Updating LinkState: link [nolink] does not exist'])
    assert answer(api, api.apply_body_wrench(gs.ApplyBodyWrenchRequest(body_name='nolink'))) == (
        False, 'ApplyBodyWrench: body does not exist', ['ApplyBodyWrench: body [nolink] does not exist'])


def test_missing_reference_frame_answers(api):
    assert answer(api, api.get_model_state(gs.GetModelStateRequest(model_name='box',
                                                                   relative_entity_name='nowhere'))) == (
        False, 'GetModelState: reference relative_entity_name not found, did you forget to scope the body '
               'by model name?', [])
    assert answer(api, api.get_link_state(gs.GetLinkStateRequest(link_name='box::link',
                                                                 reference_frame='nowhere'))) == (
        False, 'GetLinkState: reference reference_frame not found, did you forget to scope the link by '
               'model name?', [])
    assert answer(api, api.set_model_state(gs.SetModelStateRequest(gm.ModelState(
        model_name='box', reference_frame='nowhere')))) == (
        False, 'SetModelState: specified reference frame entity does not exist',
        ['Updating ModelState: for model[box], specified reference frame entity [nowhere] does not exist'])
    assert answer(api, api.set_link_state(gs.SetLinkStateRequest(gm.LinkState(
        link_name='box::link', reference_frame='nowhere')))) == (
        False, 'SetLinkState: failed', ['Updating LinkState: reference_frame is not a valid entity name'])
    assert answer(api, api.apply_body_wrench(gs.ApplyBodyWrenchRequest(body_name='box::link',
                                                                       reference_frame='nowhere'))) == (
        False, 'ApplyBodyWrench: reference_frame not found',
        ['ApplyBodyWrench: reference_frame is not a valid entity name'])
    assert answer(api, api.spawn_sdf(gs.SpawnModelRequest(model_name='cube', model_xml=BOX,
                                                          reference_frame='nowhere'))) == (
        False, 'SpawnModel: Failure - reference frame [nowhere] not found', [])
    assert answer(api, world_control.spawn_light(api, gs.SpawnModelRequest(
        model_name='lamp', model_xml=LAMP, reference_frame='nowhere'))) == (
        False, 'SpawnModel: Failure - reference frame [nowhere] not found', [])
    assert list(api.physics.models) == ['box'] and api.node.world.lights == []


def test_states_relative_to_the_reference_entity(api):
    r = api.get_model_state(gs.GetModelStateRequest(model_name='box', relative_entity_name='world'))
    assert r.success and r.status_message == 'GetModelState: got properties'
    assert (r.pose.position.x, r.pose.position.y, r.pose.position.z) == pytest.approx((1, 2, 0.5))
    assert r.header.seq == 1 and r.header.frame_id == 'world'
    r = api.get_model_state(gs.GetModelStateRequest(model_name='box', relative_entity_name='box'))
    assert (r.pose.position.x, r.pose.position.y, r.pose.position.z) == pytest.approx((0, 0, 0), abs=1e-12)
    assert r.header.seq == 2
    r = api.get_link_state(gs.GetLinkStateRequest(link_name='link', reference_frame=''))
    assert r.success and r.status_message == 'GetLinkState: got state'
    assert (r.link_state.pose.position.x, r.link_state.pose.position.y) == pytest.approx((1, 2))
    assert r.link_state.link_name == 'link' and r.link_state.reference_frame == ''
    # the world origin seen from the box (turned 90 degrees about z at (1, 2)): x = -2, y = 1
    seen, error = api._seen_from('box', lambda: (Pose(), (np.zeros(3), np.zeros(3))), 'unused')
    assert error is None
    assert (seen[0].position.x, seen[0].position.y) == pytest.approx((-2, 1))


ARM = """<sdf version="1.6"><model name="arm"><pose>0.5 -1 2 0 0 0.3</pose>
  <link name="base"><pose>0.2 0.1 0 0.1 0 0.4</pose><inertial><mass>2</mass></inertial>
    <collision name="c"><geometry><box><size>0.2 0.2 0.2</size></box></geometry></collision></link>
  <link name="tip"><pose>0.2 0.1 0.5 0 0 0</pose><inertial><mass>1</mass></inertial>
    <collision name="c"><geometry><sphere><radius>0.05</radius></sphere></geometry></collision></link>
  <joint name="j" type="revolute"><parent>base</parent><child>tip</child><axis><xyz>1 0 0</xyz></axis></joint>
  </model></sdf>"""


def test_model_and_link_states_on_the_wire(api):
    """/gazebo/model_states and link_states are written as bytes straight from the engine's
    tuples: what a subscriber deserializes is each entity's pose and twist as the Pose maths
    give them (the canonical link's frame times its pose in the model; velocities at the
    frame's origin), for a static model and a moving one whose canonical link is offset."""
    pw = api.node.physics
    pw.add_model(sdf.parse_sdf_model(ARM, 'arm.sdf', name='arm'))
    for link in pw.models['arm'].links.values():
        link.body.setLinearVel((0.3, -0.2, 0.1))
        link.body.setAngularVel((0.5, 0.2, -1.0))
    pw.step()
    api._model_frame = convert.EntityStatesFrame(gm.ModelStates)
    api._link_frame = convert.EntityStatesFrame(gm.LinkStates)
    for make, cls, entries in (
            (api._model_states, gm.ModelStates, [(n, m.canonical.pose() * m.canonical.desc.pose.inverse(), m)
                                                 for n, m in pw.models.items()]),
            (api._link_states, gm.LinkStates, [('%s::%s' % (n, ln), link.pose(), link)
                                               for n, m in pw.models.items() for ln, link in m.links.items()])):
        for _ in range(2):                  # the second time from the kept names
            buff = io.BytesIO()
            make().serialize(buff)
            msg = cls().deserialize(buff.getvalue())
            assert msg.name == [n for n, _p, _e in entries]
            for k, (_n, pose, entity) in enumerate(entries):
                got = msg.pose[k]
                assert (got.position.x, got.position.y, got.position.z) == pytest.approx(tuple(pose.p), abs=1e-12)
                q = (got.orientation.x, got.orientation.y, got.orientation.z, got.orientation.w)
                assert q == pytest.approx(tuple(pose.q), abs=1e-12)
                body = entity.canonical.body if hasattr(entity, 'canonical') else entity.body
                lin = body.getPointVel(tuple(pose.p)) if body else (0.0, 0.0, 0.0)
                ang = body.getAngularVel() if body else (0.0, 0.0, 0.0)
                t = msg.twist[k]
                assert (t.linear.x, t.linear.y, t.linear.z) == pytest.approx(lin, abs=1e-12)
                assert (t.angular.x, t.angular.y, t.angular.z) == pytest.approx(ang, abs=1e-12)
    moving = msg.twist[msg.name.index('arm::tip')]
    assert moving.angular.z == pytest.approx(-1.0, abs=0.05)
