"""Message Publisher expressions and message filling, without a roscore."""
import pytest

from rqt_publisher.expression import (ExpressionError, evaluate, field_paths, fill_message,
                                      format_rate, slot_type_of)


def get_class(name):
    import roslib.message
    if name in ('float64', 'int32', 'string', 'bool', 'uint8', 'time', 'duration'):
        return None
    return roslib.message.get_message_class(name)


def test_counter_and_math_names():
    assert evaluate('sin(i/10)', 'float64', 5) == pytest.approx(0.479425538604203)
    assert evaluate('i', 'int32', 3) == 3
    assert evaluate('pi', 'float64', 1) == pytest.approx(3.14159265)
    assert 0 <= evaluate('randint(0, 3)', 'int32', 1) <= 3


def test_conversions():
    assert evaluate('2', 'float64', 1) == 2.0 and isinstance(evaluate('2', 'float64', 1), float)
    assert evaluate('2.0', 'int32', 1) == 2
    assert evaluate('[1, 2]', 'float64[]', 1) == [1, 2]
    assert evaluate('(1.0, 2.0)', 'float64[]', 1) == (1.0, 2.0)
    assert evaluate('True', 'bool', 1) is True


def test_string_falls_back_to_raw_text():
    assert evaluate('hello world', 'string', 1) == 'hello world'
    assert evaluate("'a' * 3", 'string', 1) == 'aaa'


def test_bad_value_gives_the_originals_cell_text():
    with pytest.raises(ExpressionError) as e:
        evaluate('abc', 'float64', 1)
    assert str(e.value) == 'abc # error evaluating as "float64"'
    with pytest.raises(ExpressionError) as e:
        evaluate('2.5', 'int32', 1)
    assert str(e.value) == '2.5 # error evaluating as "int32"'
    with pytest.raises(ExpressionError):
        evaluate('"x"', 'float64', 1)


def test_fill_twist_and_errors():
    from geometry_msgs.msg import Twist
    msg, errors = fill_message(Twist, {'/linear/x': '0.5 * i', '/angular/z': 'cos(0)',
                                       '/linear/y': 'oops'}, 2, get_class)
    assert msg.linear.x == 1.0 and msg.angular.z == 1.0 and msg.linear.y == 0.0
    assert errors == {'/linear/y': 'oops # error evaluating as "float64"'}


def test_whole_submessage_expression_and_arrays():
    from geometry_msgs.msg import Twist, Vector3
    from std_msgs.msg import Float64MultiArray
    msg, errors = fill_message(Twist, {'/linear': 'genpy.Message.__new__(__import__("geometry_msgs.msg").msg.Vector3)'},
                               1, get_class)
    assert isinstance(msg.linear, Vector3)
    msg, errors = fill_message(Float64MultiArray, {'/data': '[i, 2*i]'}, 3, get_class)
    assert not errors and list(msg.data) == [3, 6]


def test_field_paths_and_types():
    from geometry_msgs.msg import Twist
    paths = field_paths(Twist, '', get_class)
    assert ('/linear', 'geometry_msgs/Vector3') in paths and ('/angular/z', 'float64') in paths
    assert slot_type_of(Twist, '/linear/x', get_class) == 'float64'
    with pytest.raises(ExpressionError):
        slot_type_of(Twist, '/linear/w', get_class)


def test_rate_echo():
    assert format_rate('2') == '2.00'
