"""Command-line probes of a running simulation, for the tests of the simulation packages and
of the course tasks (each probe is a short-lived ROS node; it prints one line of YAML):

    python3 -m course_testing.sim_probe model my_robot_model [--timeout 60]
    python3 -m course_testing.sim_probe drive my_robot_model --topic /cmd_vel --vx 0.2 --seconds 2
    python3 -m course_testing.sim_probe topic /scan [--timeout 60]

`model` waits until /gazebo/get_model_state knows the model and prints its pose; `drive`
publishes a constant Twist for a number of simulated seconds, stops the robot and prints the
model's pose before and after (and the last odometry, when --odom names a topic); `topic`
prints a summary of one message (see `summary`). Exit status 1 with one line on stderr when
something does not arrive in time.
"""
import argparse
import math
import sys
import time

import yaml

from course_runtime.geometry import yaw_of as quat_yaw


def pose_dict(pose):
    p = pose.position
    return {'x': float(p.x), 'y': float(p.y), 'z': float(p.z), 'yaw': float(quat_yaw(pose.orientation))}


def summary(msg):
    """A dict describing one message: its type and the fields the tests look at
    (Image: width height encoding step and mean intensity; LaserScan: sample count, range
    limits, finite readings and the nearest one; PointCloud2: size and fields; Imu:
    orientation, angular velocity, linear acceleration; Odometry: pose; CameraInfo: size and
    K; JointState: position and velocity by joint name). Always includes the header's frame_id
    and stamp when the message has a header."""
    t = msg._type
    out = {'type': t}
    header = getattr(msg, 'header', None)
    if header is not None:
        out['frame_id'] = header.frame_id
        out['stamp'] = header.stamp.to_sec()
    if t == 'sensor_msgs/Image':
        out.update(width=msg.width, height=msg.height, encoding=msg.encoding, step=msg.step,
                   bytes=len(msg.data))
        data = bytes(msg.data)
        out['mean'] = float(sum(data)) / len(data) if data else 0.0
        out['nonzero'] = len(data) - data.count(0)
    elif t == 'sensor_msgs/LaserScan':
        finite = [r for r in msg.ranges if math.isfinite(r) and msg.range_min <= r <= msg.range_max]
        out.update(samples=len(msg.ranges), angle_min=msg.angle_min, angle_max=msg.angle_max,
                   angle_increment=msg.angle_increment, range_min=msg.range_min,
                   range_max=msg.range_max, finite=len(finite),
                   nearest=float(min(finite)) if finite else None)
    elif t == 'sensor_msgs/PointCloud2':
        out.update(width=msg.width, height=msg.height, point_step=msg.point_step,
                   fields=[f.name for f in msg.fields], bytes=len(msg.data))
    elif t == 'sensor_msgs/Imu':
        o, w, a = msg.orientation, msg.angular_velocity, msg.linear_acceleration
        out.update(orientation=[o.x, o.y, o.z, o.w], angular_velocity=[w.x, w.y, w.z],
                   linear_acceleration=[a.x, a.y, a.z])
    elif t == 'sensor_msgs/CameraInfo':
        out.update(width=msg.width, height=msg.height, K=list(msg.K))
    elif t == 'nav_msgs/Odometry':
        out.update(child_frame_id=msg.child_frame_id, pose=pose_dict(msg.pose.pose),
                   vx=msg.twist.twist.linear.x, wz=msg.twist.twist.angular.z)
    elif t == 'sensor_msgs/JointState':
        out.update(position={n: float(v) for n, v in zip(msg.name, msg.position)},
                   velocity={n: float(v) for n, v in zip(msg.name, msg.velocity)})
    return out


def _fail(text):
    sys.stderr.write('sim_probe: %s\n' % text)
    sys.exit(1)


def _model_state(name, timeout):
    import rospy
    from gazebo_msgs.srv import GetModelState
    deadline = time.monotonic() + timeout
    try:
        rospy.wait_for_service('/gazebo/get_model_state', timeout=timeout)
    except rospy.ROSException:
        _fail('service /gazebo/get_model_state did not appear within %.0f s' % timeout)
    get = rospy.ServiceProxy('/gazebo/get_model_state', GetModelState)
    last = ''
    while time.monotonic() < deadline and not rospy.is_shutdown():
        try:
            res = get(model_name=name, relative_entity_name='')
            if res.success:
                return res
            last = res.status_message
        except rospy.ServiceException as e:
            last = str(e)
        time.sleep(0.2)
    _fail('model %r not in the simulation within %.0f s (%s)' % (name, timeout, last))


def _wait_clock(timeout):
    import rospy
    deadline = time.monotonic() + timeout
    while rospy.Time.now().is_zero():
        if time.monotonic() > deadline:
            _fail('no /clock within %.0f s' % timeout)
        time.sleep(0.05)


def cmd_model(a):
    import rospy
    rospy.init_node('sim_probe', anonymous=True, disable_signals=True)
    res = _model_state(a.name, a.timeout)
    return {'name': a.name, 'pose': pose_dict(res.pose)}


def cmd_drive(a):
    import rospy
    from geometry_msgs.msg import Twist
    rospy.init_node('sim_probe', anonymous=True, disable_signals=True)
    before = _model_state(a.name, a.timeout)
    _wait_clock(a.timeout)
    pub = rospy.Publisher(a.topic, Twist, queue_size=1)
    odom = []
    if a.odom:
        from nav_msgs.msg import Odometry
        rospy.Subscriber(a.odom, Odometry, lambda m: odom.append(m))
    deadline = time.monotonic() + a.timeout
    while pub.get_num_connections() == 0:
        if time.monotonic() > deadline:
            _fail('nobody subscribes to %s within %.0f s' % (a.topic, a.timeout))
        time.sleep(0.05)
    cmd = Twist()
    cmd.linear.x, cmd.angular.z = a.vx, a.wz
    start = rospy.Time.now()
    wall_end = time.monotonic() + a.timeout
    while (rospy.Time.now() - start).to_sec() < a.seconds:
        if time.monotonic() > wall_end:
            _fail('simulated time advanced only %.2f of %.2f s within %.0f s of wall time'
                  % ((rospy.Time.now() - start).to_sec(), a.seconds, a.timeout))
        pub.publish(cmd)
        time.sleep(0.02)
    sim_seconds = (rospy.Time.now() - start).to_sec()
    pub.publish(Twist())
    time.sleep(0.3)
    after = _model_state(a.name, a.timeout)
    out = {'name': a.name, 'before': pose_dict(before.pose), 'after': pose_dict(after.pose),
           'sim_seconds': sim_seconds}
    if a.odom:
        out['odom'] = summary(odom[-1]) if odom else None
    return out


def cmd_topic(a):
    import rospy
    import rostopic
    rospy.init_node('sim_probe', anonymous=True, disable_signals=True)
    deadline = time.monotonic() + a.timeout
    cls = None
    while cls is None:
        cls, _, _ = rostopic.get_topic_class(a.topic, blocking=False)
        if cls is None:
            if time.monotonic() > deadline:
                _fail('topic %s is not published within %.0f s' % (a.topic, a.timeout))
            time.sleep(0.2)
    got = []
    sub = rospy.Subscriber(a.topic, cls, lambda m: got.append(m), queue_size=1)
    while len(got) < a.skip + 1:
        if time.monotonic() > deadline:
            _fail('no message on %s within %.0f s' % (a.topic, a.timeout))
        time.sleep(0.05)
    sub.unregister()
    if a.save and got[-1]._type == 'sensor_msgs/Image':
        save_image(got[-1], a.save)
    return summary(got[-1])


def save_image(msg, path):
    """Write a sensor_msgs/Image to an image file (PNG) with OpenCV; depth images are scaled
    to 0-255 over their finite range."""
    import cv2
    import numpy as np
    from cv_bridge import CvBridge
    img = CvBridge().imgmsg_to_cv2(msg, desired_encoding='passthrough')
    if msg.encoding == 'rgb8':
        img = cv2.cvtColor(img, cv2.COLOR_RGB2BGR)
    elif img.dtype != np.uint8:
        f = np.nan_to_num(img.astype(np.float64), nan=0.0, posinf=0.0)
        img = (255 * f / f.max()).astype(np.uint8) if f.max() > 0 else f.astype(np.uint8)
    cv2.imwrite(path, img)


def main(argv=None):
    ap = argparse.ArgumentParser(prog='sim_probe', description=__doc__.splitlines()[0])
    sp = ap.add_subparsers(dest='cmd', required=True)
    p = sp.add_parser('model')
    p.add_argument('name')
    p.add_argument('--timeout', type=float, default=60.0)
    p = sp.add_parser('drive')
    p.add_argument('name')
    p.add_argument('--topic', default='/cmd_vel')
    p.add_argument('--odom', default='')
    p.add_argument('--vx', type=float, default=0.0)
    p.add_argument('--wz', type=float, default=0.0)
    p.add_argument('--seconds', type=float, default=2.0)
    p.add_argument('--timeout', type=float, default=60.0)
    p = sp.add_parser('topic')
    p.add_argument('topic')
    p.add_argument('--skip', type=int, default=0, help='messages to skip before the one summarised')
    p.add_argument('--save', default='', help='write an Image message to this file (PNG)')
    p.add_argument('--timeout', type=float, default=60.0)
    a = ap.parse_args(argv)
    out = {'model': cmd_model, 'drive': cmd_drive, 'topic': cmd_topic}[a.cmd](a)
    print(yaml.safe_dump(out, default_flow_style=True, width=10 ** 9).strip())
    return 0


if __name__ == '__main__':
    sys.exit(main())
