"""Unit tests of rqt_plot's ROS data module on message objects (no roscore)."""
import math

import pytest
import rospy
from geometry_msgs.msg import Point, Twist
from rosgraph_msgs.msg import Log
from sensor_msgs.msg import Imu, JointState
from std_msgs.msg import Float64, Header

from rqt_plot.rosplot import (PlotFieldError, ROSData, check_field, expand_specs, extract,
                              match_topic, parse_field_path, resolve_spec)


def test_expand_specs():
    assert expand_specs(['/turtle1/pose/x', '/turtle1/pose/y']) == ['/turtle1/pose/x', '/turtle1/pose/y']
    assert expand_specs(['/turtle1/pose/x:y:theta']) == \
        ['/turtle1/pose/x', '/turtle1/pose/y', '/turtle1/pose/theta']
    assert expand_specs(['/a/x,/b/y', '/c/d:e']) == ['/a/x', '/b/y', '/c/d', '/c/e']
    with pytest.raises(PlotFieldError, match='x:y'):
        expand_specs(['x:y'])


def test_parse_field_path():
    assert parse_field_path('') == []
    assert parse_field_path('linear_acceleration/x') == [('linear_acceleration', None), ('x', None)]
    assert parse_field_path('velocity[0]') == [('velocity', 0)]
    assert parse_field_path('/a[12]/b/') == [('a', 12), ('b', None)]
    for bad in ('a[', 'a[-1]', '1a', 'a b', 'a[x]'):
        with pytest.raises(PlotFieldError, match='bad field name'):
            parse_field_path(bad)


def test_match_topic_prefers_longest_topic_at_slash():
    topics = {'/pt': 'geometry_msgs/Point', '/pt/sub': 'std_msgs/Float64', '/ptx': 'x/Y'}
    assert match_topic('/pt/x', topics) == ('/pt', 'geometry_msgs/Point', 'x')
    assert match_topic('/pt/sub/data', topics) == ('/pt/sub', 'std_msgs/Float64', 'data')
    assert match_topic('/ptx/a', topics) == ('/ptx', 'x/Y', 'a')
    assert match_topic('/pt', topics) == ('/pt', 'geometry_msgs/Point', '')
    assert match_topic('/other/x', topics) is None
    assert match_topic('/p', topics) is None


def test_resolve_and_extract_nested_and_arrays():
    topics = {'/imu': 'sensor_msgs/Imu', '/joint_states': 'sensor_msgs/JointState',
              '/pt': 'geometry_msgs/Point', '/rosout': 'rosgraph_msgs/Log',
              '/f': 'std_msgs/Float64', '/twist': 'geometry_msgs/Twist'}
    imu = Imu()
    imu.linear_acceleration.x = 9.81
    imu.orientation_covariance[4] = 0.25
    imu.header.stamp = rospy.Time(12, 500000000)
    (spec, topic, cls, path), = resolve_spec('/imu/linear_acceleration/x', topics)
    assert (spec, topic, cls) == ('/imu/linear_acceleration/x', '/imu', Imu)
    assert extract(imu, path) == 9.81
    (_, _, _, path), = resolve_spec('/imu/orientation_covariance[4]', topics)
    assert extract(imu, path) == 0.25
    (_, _, _, path), = resolve_spec('/imu/header/stamp', topics)
    assert extract(imu, path) == 12.5

    js = JointState(name=['a', 'b'], velocity=[0.5, -1.5])
    (_, topic, cls, path), = resolve_spec('/joint_states/velocity[1]', topics)
    assert (topic, cls) == ('/joint_states', JointState)
    assert extract(js, path) == -1.5
    with pytest.raises(PlotFieldError, match='out of range'):
        extract(JointState(velocity=[0.5]), path)

    (_, _, _, path), = resolve_spec('/f/data', topics)
    assert extract(Float64(data=-2.0), path) == -2.0
    (_, _, _, path), = resolve_spec('/rosout/level', topics)      # byte
    assert extract(Log(level=4), path) == 4.0

    # a spec naming a message plots its scalar numeric fields
    assert [s for s, *_ in resolve_spec('/pt', topics)] == ['/pt/x', '/pt/y', '/pt/z']
    assert [s for s, *_ in resolve_spec('/f', topics)] == ['/f/data']
    assert resolve_spec('/not_yet/x', topics) is None


@pytest.mark.parametrize('spec,message', [
    ('/pt/w', "/pt/w: geometry_msgs/Point has no field 'w'"),
    ('/imu/linear_acceleration/q', "geometry_msgs/Vector3 has no field 'q'"),
    ('/rosout/msg', '/rosout/msg: field is a string, not a number'),
    ('/joint_states/velocity', "field 'velocity' is an array (float64[]); plot one element, "
                               "e.g. /joint_states/velocity[0]"),
    ('/joint_states/name[0]', 'field is a string, not a number'),
    ('/pt/x[0]', "field 'x' is a float64, not an array"),
    ('/imu/orientation_covariance[9]', 'index 9 is out of range for float64[9]'),
    ('/pt/x/y', "'x' is a float64 and has no field 'y'"),
    ('/twist', 'geometry_msgs/Twist has no numeric fields of its own'),
    ('/twist/linear', None),
])
def test_unplottable_fields_are_named(spec, message):
    topics = {'/imu': 'sensor_msgs/Imu', '/joint_states': 'sensor_msgs/JointState',
              '/pt': 'geometry_msgs/Point', '/rosout': 'rosgraph_msgs/Log',
              '/twist': 'geometry_msgs/Twist'}
    if message is None:
        assert [s for s, *_ in resolve_spec(spec, topics)] == \
            ['/twist/linear/x', '/twist/linear/y', '/twist/linear/z']
        return
    with pytest.raises(PlotFieldError) as e:
        resolve_spec(spec, topics)
    assert message in str(e.value)
    assert '\n' not in str(e.value)


def test_unknown_type():
    with pytest.raises(PlotFieldError, match='nosuch_msgs/Thing is not known'):
        resolve_spec('/x/y', {'/x': 'nosuch_msgs/Thing'})


def test_check_field_types():
    assert check_field(Header, parse_field_path('seq')) == 'uint32'
    assert check_field(Header, parse_field_path('stamp')) == 'time'
    assert check_field(Twist, parse_field_path('angular')) is type(Twist().angular)  # noqa: E721


class FakeROSData(ROSData):
    def __init__(self, *a, now=100.0, **kw):
        super().__init__(*a, subscribe=False, **kw)
        self.fake_now = now

    def _now(self):
        return self.fake_now


def test_rosdata_buffers_and_hands_errors_to_consumer():
    d = FakeROSData('/pt/x', '/pt', Point, parse_field_path('x'), start_time=90.0)
    for i in range(5):
        d.fake_now = 100.0 + i * 0.1
        d._callback(Point(x=math.sin(i)))
    xs, ys = d.next()
    assert xs == pytest.approx([10.0, 10.1, 10.2, 10.3, 10.4])
    assert ys == [math.sin(i) for i in range(5)]
    assert d.next() == ([], [])                      # drained

    j = FakeROSData('/js/velocity[2]', '/js', JointState, parse_field_path('velocity[2]'), 0.0)
    j._callback(JointState(velocity=[1.0]))          # too short: error, kept for the GUI thread
    with pytest.raises(PlotFieldError, match=r'/js/velocity\[2\]: index 2 is out of range'):
        j.next()
    assert j.next() == ([], [])                      # reported once
    j._callback(JointState(velocity=[1.0, 2.0, 3.0]))
    assert j.next()[1] == [3.0]


def test_rosdata_uses_header_stamp():
    d = FakeROSData('/imu/linear_acceleration/z', '/imu', Imu,
                    parse_field_path('linear_acceleration/z'), start_time=1000.0)
    m = Imu()
    m.header.stamp = rospy.Time(1002, 250000000)
    m.linear_acceleration.z = 9.8
    d._callback(m)
    m2 = Imu()                                      # zero stamp: receipt time
    d._callback(m2)
    assert d.next() == ([2.25, -900.0], [9.8, 0.0])
