"""slam_gmapping_replay without a master: its options as the original's boost::program_options
(required bag, defaults, --opt=value, prefixes, unsigned numbers) and the scan queue's order
(wait for TF, at most 5 waiting, the oldest dropped with the reason it waited, un-stamped scans
ignored)."""
import subprocess

import pytest
from sensor_msgs.msg import LaserScan
import rospy

from gmapping.replay import OptionError, ScanQueue, bag_topic, parse_args


def test_options_as_the_original():
    o = parse_args(['--bag_filename', 'a.bag'])
    assert (o.bag_filename, o.scan_topic, o.seed, o.max_duration_buffer, o.on_done) == \
        ('a.bag', '/scan', 0, 99999, None)
    o = parse_args(['--bag_filename=b.bag', '--scan_topic', '/base_scan', '--seed=42',
                    '--max_duration', '30', '--on_done', 'echo done'])
    assert (o.bag_filename, o.scan_topic, o.seed, o.max_duration_buffer, o.on_done) == \
        ('b.bag', '/base_scan', 42, 30, 'echo done')
    assert parse_args(['--help']).help
    with pytest.raises(OptionError, match='bag_filename'):
        parse_args(['--scan_topic', '/scan'])
    with pytest.raises(OptionError, match='seed'):
        parse_args(['--bag_filename', 'a.bag', '--seed', '-3'])
    with pytest.raises(OptionError, match='unrecognized'):
        parse_args(['--bag_filename', 'a.bag', '--bogus', '1'])
    assert bag_topic('scan') == '/scan' and bag_topic('/scan') == '/scan'


def test_missing_bag_is_one_error_line(tmp_path):
    p = subprocess.run(['rosrun', 'gmapping', 'slam_gmapping_replay', '--bag_filename',
                        str(tmp_path / 'none.bag')], capture_output=True, text=True, timeout=60)
    assert p.returncode == 255
    assert p.stderr.strip() == 'ERROR: --bag_filename %s: no such file' % (tmp_path / 'none.bag')


def scan(t):
    s = LaserScan()
    s.header.stamp = rospy.Time(t)
    return s


def test_scan_queue_waits_for_tf_and_drops_the_oldest():
    done, warned = [], []
    tf_until = [0.0]
    q = ScanQueue(lambda s: (s.header.stamp.to_sec() <= tf_until[0], 'no tf at %g'
                             % s.header.stamp.to_sec()),
                  lambda s: done.append(s.header.stamp.to_sec()), warned.append)
    q.push(scan(0))           # un-stamped: ignored
    for t in (1, 2, 3, 4, 5, 6):
        q.push(scan(t))
        q.drain()
    assert done == [] and warned == ['Dropping old scan: no tf at 1']
    tf_until[0] = 4.5
    q.drain()
    assert done == [2, 3, 4]
    tf_until[0] = 10
    q.push(scan(7))
    q.drain()
    assert done == [2, 3, 4, 5, 6, 7] and q.dropped == 1
