"""Topic Monitor maths without a roscore."""
from rqt_topic.topic_stats import TopicStats, format_bandwidth, format_hz, value_rows


def test_rate_of_a_10hz_topic():
    s = TopicStats()
    for k in range(50):
        s.add(100.0 + 0.1 * k, 8)
    assert abs(s.hz() - 10.0) < 1e-9
    assert format_hz(s.hz()) == '10.00'


def test_rate_window_keeps_the_latest_messages():
    s = TopicStats(hz_window=10)
    for k in range(20):
        s.add(float(k), 1)           # 1 Hz first ...
    for k in range(20):
        s.add(20.0 + 0.5 * k, 1)     # ... then 2 Hz
    assert abs(s.hz() - 2.0) < 1e-9


def test_unknown_before_two_messages():
    s = TopicStats()
    assert s.hz() is None and format_hz(None) == 'unknown'
    s.add(1.0, 10)
    assert s.bandwidth(2.0) is None and format_bandwidth(None) == 'unknown'


def test_bandwidth_and_units():
    s = TopicStats()
    for k in range(10):
        s.add(float(k), 100)
    assert s.bandwidth(10.0) == 100.0       # 1000 bytes over 10 s
    assert format_bandwidth(100.0) == '100.00B/s'
    assert format_bandwidth(2500.0) == '2.50KB/s'
    assert format_bandwidth(3.2e6) == '3.20MB/s'


def test_bandwidth_window_is_99_messages():
    s = TopicStats()
    for k in range(200):
        s.add(float(k), 1)
    assert len(s.bw) == 99
    assert abs(s.bandwidth(200.0) - 99 / (200.0 - 101.0)) < 1e-9


def test_value_rows_of_nested_messages():
    from geometry_msgs.msg import Point, Polygon, Twist
    t = Twist()
    t.linear.x = 1.5
    rows = dict(value_rows(t))
    assert rows['/linear/x'] == '1.5' and rows['/angular/z'] == '0.0'
    p = Polygon(points=[Point(1.0, 2.0, 3.0)])
    assert dict(value_rows(p))['/points[0]/y'] == '2.0'
