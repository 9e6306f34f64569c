"""slam_gmapping_replay: the same SLAM core as slam_gmapping, fed from a bag file instead of the
live graph (the original's offline node, replay.cpp + SlamGMapping::startReplay).

    rosrun gmapping slam_gmapping_replay --bag_filename run.bag [--scan_topic /scan] [--seed 0]
        [--max_duration_buffer 99999] [--on_done "rosrun map_server map_saver -f office"]

The bag's /tf and /tf_static fill a TF buffer (kept max_duration_buffer seconds); each scan with
a non-zero stamp waits in a queue of at most 5 until its odometry transform is in the buffer, then
goes through slam_gmapping's laser callback, which publishes map, map_metadata, ~entropy and TF
map->odom as it goes. At the end the final map is published; then --on_done is run with the
shell and the node exits with its status, or without --on_done the node keeps serving map and
dynamic_map until shut down. Options as the original's (boost::program_options): `--opt value`
or `--opt=value`, unambiguous prefixes accepted (so `--max_duration` works)."""
import argparse
import collections
import subprocess
import sys

TF_TOPICS = ('/tf', '/tf_static')
QUEUE = 5   # scans waiting for their odometry, as the original


class OptionError(Exception):
    pass


class _Parser(argparse.ArgumentParser):
    def error(self, message):
        raise OptionError(message)


def parser():
    p = _Parser(prog='slam_gmapping_replay', add_help=False, allow_abbrev=True,
                description='Options')
    p.add_argument('--help', action='store_true', help='Print help messages')
    p.add_argument('--scan_topic', default='/scan',
                   help='topic that contains the laserScan in the rosbag')
    p.add_argument('--bag_filename', help='ros bag filename (required)')
    p.add_argument('--seed', default=0, type=_unsigned, help='seed')
    p.add_argument('--max_duration_buffer', default=99999, type=_unsigned,
                   help='max tf buffer duration')
    p.add_argument('--on_done', default=None, help='command to execute when done')
    return p


def _unsigned(text):
    try:
        v = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError('%r is not an unsigned integer' % text)
    if v < 0:
        raise argparse.ArgumentTypeError('%r is not an unsigned integer' % text)
    return v


def parse_args(argv):
    """argv without the program name and without ROS remappings -> options; OptionError with
    one line naming what is wrong."""
    opts = parser().parse_args(argv)
    if not opts.help and not opts.bag_filename:
        raise OptionError("the option '--bag_filename' is required but missing")
    return opts


def bag_topic(name):
    return name if name.startswith('/') else '/' + name


class ScanQueue(object):
    """The original's ordering: scans wait (at most QUEUE of them, the oldest dropped with a
    warning naming why it waited) until `ready(scan)` holds, then go to `process` in order."""

    def __init__(self, ready, process, warn):
        self.ready = ready
        self.process = process
        self.warn = warn
        self.items = collections.deque()
        self.dropped = 0

    def push(self, scan):
        if scan.header.stamp.secs == 0 and scan.header.stamp.nsecs == 0:
            return                        # un-timestamped: ignored, as the original
        self.items.append([scan, ''])
        if len(self.items) > QUEUE:
            _, why = self.items.popleft()
            self.dropped += 1
            self.warn('Dropping old scan: %s' % why)

    def drain(self):
        while self.items:
            scan = self.items[0][0]
            ok, why = self.ready(scan)
            if not ok:
                self.items[0][1] = why
                return
            self.items.popleft()
            self.process(scan)


def replay(node, bag_filename, scan_topic, log=None):
    """Feed the bag to `node` (a SlamGMapping with live=False). Returns (scans read, dropped)."""
    import rosbag
    import rospy
    log = log or rospy.logwarn
    buf = node.tf_buffer
    odom = node.p.odom_frame

    def ready(scan):
        ok, why = buf.can_transform(odom, scan.header.frame_id, scan.header.stamp,
                                    return_debug_tuple=True)
        return ok, why

    q = ScanQueue(ready, node.laser_callback, log)
    topic = bag_topic(scan_topic)
    n = 0
    with rosbag.Bag(bag_filename, 'r') as bag:
        for name, msg, _t in bag.read_messages(topics=[topic] + list(TF_TOPICS)):
            if rospy.is_shutdown():
                break
            if name in TF_TOPICS:
                for tr in msg.transforms:
                    if name == '/tf_static':
                        buf.set_transform_static(tr, 'bag')
                    else:
                        buf.set_transform(tr, 'bag')
            else:
                n += 1
                q.push(msg)
            q.drain()
    return n, q.dropped


def main(argv=None):
    import rospy
    argv = rospy.myargv(sys.argv if argv is None else argv)[1:]
    try:
        opts = parse_args(argv)
    except OptionError as e:
        sys.stderr.write('ERROR: %s\n\n%s' % (e, parser().format_help()))
        return 255
    if opts.help:
        sys.stdout.write('Basic Command Line Parameter App\n' + parser().format_help())
        return 0
    import os
    if not os.path.isfile(opts.bag_filename):
        sys.stderr.write('ERROR: --bag_filename %s: no such file\n' % opts.bag_filename)
        return 255

    from gmapping.node import SlamGMapping, read_params
    from gmapping.params import ParamError
    rospy.init_node('slam_gmapping')
    try:
        params = read_params()
    except ParamError as e:
        rospy.logerr('slam_gmapping_replay: %s', e)
        return 1
    node = SlamGMapping(params, live=False, seed=opts.seed, tf_cache=float(opts.max_duration_buffer))
    try:
        n, dropped = replay(node, opts.bag_filename, opts.scan_topic)
    except Exception as e:    # a bag rosbag cannot read: one line naming it
        rospy.logerr('slam_gmapping_replay: cannot read %s: %s', opts.bag_filename, e)
        return 1
    if node.slam.count:
        node.update_map()     # the map of every processed scan, not only the last interval's
    rospy.loginfo('replay stopped.')
    rospy.loginfo('slam_gmapping_replay: %d scans on %s in the bag, %d processed, %d dropped',
                  n, bag_topic(opts.scan_topic), node.slam.count, dropped)
    if n == 0:
        rospy.logwarn('slam_gmapping_replay: no scan on %s in %s', bag_topic(opts.scan_topic),
                      opts.bag_filename)
    if opts.on_done is not None:
        return subprocess.call(opts.on_done, shell=True) & 0xFF
    rospy.spin()    # wait so the user can save the map
    return 0
