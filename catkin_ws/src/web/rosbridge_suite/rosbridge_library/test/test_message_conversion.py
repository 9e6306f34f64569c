"""message_conversion without a master: JSON <-> genpy messages as rosbridge_library."""
import base64
import json
import math

import genpy
import pytest
from geometry_msgs.msg import PoseWithCovariance, Twist
from sensor_msgs.msg import Image, LaserScan
from std_msgs.msg import Header, String, UInt8MultiArray

from rosbridge_library.internal import message_conversion as mc
from rosbridge_library.internal import ros_loader, wire


def test_twist_round_trip():
    t = mc.populate_instance({'linear': {'x': 1.5}, 'angular': {'z': -2}}, Twist())
    assert (t.linear.x, t.linear.y, t.angular.z) == (1.5, 0.0, -2.0)
    assert mc.extract_values(t) == {'linear': {'x': 1.5, 'y': 0.0, 'z': 0.0},
                                    'angular': {'x': 0.0, 'y': 0.0, 'z': -2.0}}


def test_time_is_secs_nsecs():
    h = Header(seq=3, stamp=genpy.Time(12, 345), frame_id='map')
    assert mc.extract_values(h) == {'seq': 3, 'stamp': {'secs': 12, 'nsecs': 345},
                                    'frame_id': 'map'}
    back = mc.populate_instance({'stamp': {'secs': 7, 'nsecs': 8}}, Header())
    assert back.stamp == genpy.Time(7, 8)


def test_uint8_array_is_base64_both_ways():
    img = Image(height=1, width=3, encoding='rgb8', step=9, data=bytes(range(9)))
    v = mc.extract_values(img)
    assert v['data'] == base64.b64encode(bytes(range(9))).decode()
    back = mc.populate_instance(json.loads(json.dumps(v)), Image())
    assert back.data == bytes(range(9))
    # a list of ints is accepted too
    assert mc.populate_instance({'data': [1, 2, 255]}, UInt8MultiArray()).data == b'\x01\x02\xff'


def test_nan_and_inf_become_null_and_json_stays_valid():
    scan = LaserScan(ranges=[1.0, float('inf'), float('nan')], range_max=float('inf'))
    v = mc.extract_values(scan)
    assert v['ranges'] == [1.0, None, None] and v['range_max'] is None
    text = wire.to_json({'op': 'publish', 'msg': v})
    assert 'NaN' not in text and 'Infinity' not in text
    back = mc.populate_instance({'range_max': None}, LaserScan())
    assert math.isnan(back.range_max)


def test_unknown_field_is_an_error_naming_it():
    with pytest.raises(mc.NonexistentFieldException) as e:
        mc.populate_instance({'linear': {'x': 1, 'w': 2}}, Twist())
    assert str(e.value) == 'Message type geometry_msgs/Vector3 does not have a field linear.w'


def test_wrong_types_are_errors():
    with pytest.raises(mc.FieldTypeMismatchException) as e:
        mc.populate_instance({'data': 5}, String())
    assert 'std_msgs/String message requires a string for field data, but got a int' == \
        str(e.value)
    with pytest.raises(mc.FieldTypeMismatchException):
        mc.populate_instance({'linear': {'x': 'fast'}}, Twist())
    with pytest.raises(mc.FieldTypeMismatchException) as e:
        mc.populate_instance('hello', String())
    assert 'Expected a JSON object for type std_msgs/String' in str(e.value)
    with pytest.raises(mc.FieldTypeMismatchException):   # fixed-size array of wrong length
        mc.populate_instance({'covariance': [0.0] * 5}, PoseWithCovariance())
    with pytest.raises(mc.FieldTypeMismatchException):   # out of range
        mc.populate_instance({'height': -1}, Image())


def test_missing_fields_keep_defaults_and_header_gets_now():
    now = lambda: (100, 5)   # noqa: E731
    img = mc.populate_instance({'width': 4}, Image(), now=now)
    assert img.width == 4 and img.encoding == '' and img.header.stamp == genpy.Time(100, 5)
    img = mc.populate_instance({'header': {'frame_id': 'cam'}}, Image(), now=now)
    assert img.header.frame_id == 'cam' and img.header.stamp == genpy.Time(100, 5)
    img = mc.populate_instance({'header': {'stamp': {'secs': 1, 'nsecs': 2}}}, Image(), now=now)
    assert img.header.stamp == genpy.Time(1, 2)


def test_cbor_values_keep_bytes_and_typed_arrays():
    import cbor2
    scan = LaserScan(ranges=[1.0, 2.0])
    v = mc.extract_values(scan, binary=True)
    assert isinstance(v['ranges'], cbor2.CBORTag) and v['ranges'].tag == 85
    assert mc.extract_values(Image(data=b'\x00\x01'), binary=True)['data'] == b'\x00\x01'


def test_loader_errors():
    assert ros_loader.get_message_class('std_msgs/msg/String') is String
    with pytest.raises(ros_loader.InvalidTypeStringException):
        ros_loader.get_message_class('String')
    with pytest.raises(ros_loader.InvalidModuleException):
        ros_loader.get_message_class('no_such_pkg/Foo')
    with pytest.raises(ros_loader.InvalidClassException):
        ros_loader.get_message_class('std_msgs/NoSuch')


def test_wire_png_and_fragments():
    text = json.dumps({'op': 'publish', 'topic': '/x', 'msg': {'data': 'a' * 1000}})
    assert wire.png_decode(wire.png_encode(text)) == text
    frames = wire.frames(json.loads(text), fragment_size=100, mid='m')
    parts = [json.loads(f) for f, _ in frames]
    assert all(p['op'] == 'fragment' and p['id'] == 'm' for p in parts)
    assert [p['num'] for p in parts] == list(range(len(parts))) and parts[0]['total'] == len(parts)
    assert json.loads(''.join(p['data'] for p in parts)) == json.loads(text)
    (png, binary), = wire.frames(json.loads(text), compression='png')
    assert not binary and json.loads(wire.png_decode(json.loads(png)['data'])) == \
        json.loads(text)
