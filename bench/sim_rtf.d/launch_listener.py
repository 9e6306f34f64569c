#!/usr/bin/python3
"""sim_rtf --launch's listener: drives the launched robot and counts what the graph publishes.

launch_listener.py DRIVE SENSOR... where DRIVE is `twist:TOPIC` (Twist 0.2 m/s, 0.3 rad/s),
`position:TOPIC,TOPIC` (std_msgs/Float64 position targets 2 rad per simulated second ahead,
so position-controlled wheels keep turning) or `none` (the launch drives the robot itself) and
each SENSOR is `TOPIC=pkg/Type`.
Commands are sent every 0.05 simulated s (on /clock), so a controller's cmd_vel_timeout never
stops the robot however fast the simulation runs. Prints `ready`; SIGUSR1 starts the measured
window (counters reset), SIGINT ends it and prints one JSON line: per sensor the messages, the
first/last header stamps and the distinct stamps; /clock messages; /tf messages and transforms
per publishing node.
Messages are received raw (rospy.AnyMsg) and only what is counted is read from the bytes: the
header stamp (bytes 4-11 of a message that starts with a std_msgs/Header) and a TFMessage's
transform count (its first 4 bytes), so the listener's own CPU stays small beside the launch."""
import json
import signal
import struct
import sys

import rospy
from roslib.message import get_message_class
from rosgraph_msgs.msg import Clock

STAMP = struct.Struct('<II')        # Header: uint32 seq, then time (uint32 secs, uint32 nsecs)
COUNT = struct.Struct('<I')         # an array's length prefix

DRIVE_PERIOD = 0.05     # simulated seconds between commands


class Counts:
    def __init__(self, sensors):
        self.sensors = sensors
        self.reset()

    def reset(self):
        self.stamps = {t: [] for t in self.sensors}
        self.clock = 0
        self.tf = {}                # callerid -> [messages, transforms]

    def summary(self):
        out = {'sensors': {}, 'clock': self.clock, 'tf': self.tf}
        for k, v in self.stamps.items():
            v = list(v)         # a snapshot: callbacks may still be appending
            out['sensors'][k] = {'received': len(v), 'first': min(v) * 1e-9 if v else 0.0,
                                 'last': max(v) * 1e-9 if v else 0.0, 'distinct': len(set(v))}
        return out


def on_stamped(counts, topic):
    """A raw-message callback appending the header stamp (ns) to counts.stamps[topic]."""
    def callback(msg):
        secs, nsecs = STAMP.unpack_from(msg._buff, 4)
        counts.stamps[topic].append(secs * 1000000000 + nsecs)
    return callback


def main(argv):
    drive, sensors = argv[1], argv[2:]
    rospy.init_node('sim_rtf_launch_listener', anonymous=True, disable_signals=True)
    types = dict(s.split('=', 1) for s in sensors)
    counts = Counts(list(types))
    for topic, typ in types.items():
        cls = get_message_class(typ)
        if cls is None or 'header' not in getattr(cls, '__slots__', ())[:1]:
            raise SystemExit('launch_listener: %s is not a message type starting with a header' % typ)
        rospy.Subscriber(topic, rospy.AnyMsg, on_stamped(counts, topic), queue_size=10000)

    def on_tf(msg):
        c = counts.tf.setdefault(msg._connection_header.get('callerid', '?'), [0, 0])
        c[0] += 1
        c[1] += COUNT.unpack_from(msg._buff, 0)[0]
    rospy.Subscriber('/tf', rospy.AnyMsg, on_tf, queue_size=10000)

    kind, topics = drive.split(':', 1) if ':' in drive else (drive, '')
    if kind == 'none':
        pubs, make = [], None
    elif kind == 'twist':
        from geometry_msgs.msg import Twist
        pubs = [rospy.Publisher(topics, Twist, queue_size=1)]
        cmd = Twist()
        cmd.linear.x, cmd.angular.z = 0.2, 0.3
        make = lambda t: cmd        # noqa: E731
    elif kind == 'position':
        from std_msgs.msg import Float64
        pubs = [rospy.Publisher(t, Float64, queue_size=1) for t in topics.split(',')]
        make = lambda t: Float64(2.0 * t + 2.0)     # noqa: E731
    else:
        raise SystemExit('launch_listener: drive must be twist:TOPIC, position:TOPIC,... or none')
    last = [-1.0]

    def on_clock(msg):
        counts.clock += 1
        t = msg.clock.to_sec()
        if last[0] < 0 or t - last[0] >= DRIVE_PERIOD or t < last[0]:
            last[0] = t
            for p in pubs:
                try:
                    p.publish(make(t))
                except rospy.ROSException:      # shutting down
                    return
    rospy.Subscriber('/clock', Clock, on_clock, queue_size=1)

    done = []
    signal.signal(signal.SIGUSR1, lambda *_: counts.reset())
    signal.signal(signal.SIGINT, lambda *_: done.append(1))
    print('ready', flush=True)
    while not done:
        signal.pause()
    print(json.dumps(counts.summary()), flush=True)
    rospy.signal_shutdown('done')
    return 0


if __name__ == '__main__':
    sys.exit(main(sys.argv))
