"""Robot Steering command logic without a roscore."""
from rqt_robot_steering.steering import Steering, label, slider_limit


def test_slider_to_twist_values():
    s = Steering()
    s.linear, s.angular = 500, -1250
    assert s.command() == (0.5, -1.25)
    assert s.next_to_send() == (0.5, -1.25)
    assert s.next_to_send() == (0.5, -1.25)      # non-zero: every period


def test_zero_is_sent_once():
    s = Steering()
    assert s.next_to_send() == (0.0, 0.0)
    assert s.next_to_send() is None
    s.linear = 10
    assert s.next_to_send() == (0.01, 0.0)
    s.linear = 0
    assert s.next_to_send() == (0.0, 0.0)
    assert s.next_to_send() is None


def test_stop_resends_zero():
    s = Steering()
    s.next_to_send()
    assert s.next_to_send() is None
    s.stop()
    assert s.next_to_send() == (0.0, 0.0)
    s.linear = 300
    s.stop()
    assert (s.linear, s.angular) == (0, 0) and s.next_to_send() == (0.0, 0.0)


def test_limits_and_labels():
    assert slider_limit(1.0) == 1000 and slider_limit(-3.0) == -3000
    assert label(0.0, 'm/s') == '0.00 m/s' and label(-1.5, 'rad/s') == '-1.50 rad/s'
