#!/usr/bin/env python3
"""A user of the gazebo_plugins for test_plugins_gazebo_more.py: `plugin_client.py MODE` reads
a plugin's topics / calls its services against a running sim_node, reads the simulated truth
(/gazebo/get_model_state, /gazebo/model_states) and prints one JSON object. A world started
paused (-u) is driven by /gazebo/step_world, commands are in place and messages have arrived
before anything is read (the simulator's bus statistics say so), never after a wall-clock sleep:
what the plugins get and when they are sampled is the same on a busy machine."""
import json
import math
import sys
import time

import rospy
from gazebo_msgs import msg as gm
from gazebo_msgs import srv as gs
from geometry_msgs.msg import Twist, Wrench
from nav_msgs.msg import Odometry
from sensor_msgs.msg import Range
from std_msgs.msg import Bool
from std_srvs.srv import Empty


def svc(name, typ):
    rospy.wait_for_service(name, timeout=60)
    return rospy.ServiceProxy(name, typ)


def sim_time():
    return svc('/gazebo/get_world_properties', gs.GetWorldProperties)().sim_time


def time_step():
    return svc('/gazebo/get_physics_properties', gs.GetPhysicsProperties)().time_step


def step(n):
    """Exactly n physics steps of the paused world (/gazebo/step_world); the sim time after."""
    from ode_sim_msgs.srv import StepWorld
    r = svc('/gazebo/step_world', StepWorld)(n)
    if not r.success:
        raise SystemExit(r.status_message)
    return r.sim_time


def step_to(t_end):
    """The steps of the paused world that bring sim time to t_end; the sim time after."""
    n = int(math.ceil((t_end - sim_time()) / time_step() - 1e-6))
    return step(n) if n > 0 else sim_time()


def step_through(t_end, chunk, flush=()):
    """step_to(t_end) in chunks of at most CHUNK s of sim time, each followed by
    wait_flushed(topic, msgs) for each pair of FLUSH: with no more messages published in a
    chunk than a publisher's queue holds, every one reaches its list, however fast the steps run
    (a queue of 1 would drop all but the last of a burst). The sim time after."""
    t = sim_time()
    while t < t_end - 1e-9:
        t = step_to(min(t_end, t + chunk))
        for topic, msgs in flush:
            wait_flushed(topic, msgs)
    return t


def wait_connected(pub):
    """Until the publisher has a subscriber."""
    wait_until(lambda: pub.get_num_connections() > 0, 'a subscriber of ' + pub.resolved_name)


_GAZEBO = []


def gazebo():
    """The simulator node's XML-RPC API (getBusInfo / getBusStats)."""
    import rosgraph
    from xmlrpc.client import ServerProxy
    if not _GAZEBO:
        rospy.wait_for_service('/gazebo/get_world_properties', timeout=60)     # it is up
        _GAZEBO.append(ServerProxy(rosgraph.Master(rospy.get_name()).lookupNode('/gazebo')))
    return _GAZEBO[0]


def wait_until(cond, what, timeout=60.0):
    """Poll COND until true; the timeout is a hang guard, not a measure."""
    deadline = time.monotonic() + timeout
    while not cond():
        if time.monotonic() > deadline:
            raise SystemExit('timed out waiting for ' + what)
        time.sleep(0.02)


def wait_subscribed(topic):
    """Until the simulator publishes TOPIC to this node (its getBusInfo): every message it
    publishes from then on reaches us."""
    me = rospy.get_name()

    def connected():
        _code, _msg, info = gazebo().getBusInfo(me)
        return any(c[1] == me and c[2] == 'o' and c[4] == topic and c[5] for c in info)
    wait_until(connected, '/gazebo to publish %s to %s' % (topic, me))


def next_message(topic, typ):
    """One more step of the paused world and the message the simulator published on TOPIC in
    it (a fresh subscription, connected before that step; for a topic published every step,
    whose queue may drop older messages, and for messages without a header.seq)."""
    me = rospy.get_name()

    def links():
        _code, _msg, info = gazebo().getBusInfo(me)
        return {c[0] for c in info if c[1] == me and c[2] == 'o' and c[4] == topic and c[5]}
    before = links()
    got = []
    sub = rospy.Subscriber(topic, typ, got.append)
    wait_until(lambda: links() - before, '/gazebo to publish %s to %s' % (topic, me))
    t = step(1)
    wait_until(lambda: got, 'a message on ' + topic)
    sub.unregister()
    return got[0], t


def received(topic):
    """Bytes the simulator has read on TOPIC (its getBusStats): rospy counts them as it reads
    them off the socket, before it runs the callback, and a subscriber's queue_size may drop
    messages that came in one read, so bytes, not messages."""
    _code, _msg, (_pubs, subs, _srvs) = gazebo().getBusStats(rospy.get_name())
    return sum(c[1] for name, conns in subs if name == topic for c in conns)


def wire_size(msg):
    from io import BytesIO
    buff = BytesIO()
    msg.serialize(buff)
    return buff.tell() + 4


def send(pub, msg, topic):
    """Publish MSG and wait until the simulator has read it off its socket."""
    want = received(topic) + wire_size(msg)
    pub.publish(msg)
    wait_until(lambda: received(topic) >= want, '/gazebo to read a message on ' + topic)


def command(pub, msg, topic):
    """MSG in place before the next step, whatever the load: sent twice, the second only once
    the simulator has read the first; it reads the second in its next read, after the first's
    callback returned (the repeat's own callback sets the same command again)."""
    send(pub, msg, topic)
    send(pub, msg, topic)


def wait_flushed(topic, msgs):
    """Until the last message the (paused) simulator published on TOPIC has reached MSGS (a
    subscriber's list; a queue may drop older ones, never the last): the publisher's bytes sent
    over one message's size is the number it published, the last one's header.seq the number
    of the last that arrived. Stamped messages of a fixed size."""
    def flushed():
        _code, _msg, (pubs, _subs, _srvs) = gazebo().getBusStats(rospy.get_name())
        sent = sum(p[1] for p in pubs if p[0] == topic)
        return sent == (msgs[-1].header.seq * wire_size(msgs[-1]) if msgs else 0)
    wait_until(flushed, 'the messages on %s' % topic)


def state(name):
    r = svc('/gazebo/get_model_state', gs.GetModelState)(name, '')
    p, v = r.pose.position, r.twist.linear
    return {'xyz': [p.x, p.y, p.z], 'vel': [v.x, v.y, v.z], 'w': r.twist.angular.z,
            'q': [r.pose.orientation.x, r.pose.orientation.y, r.pose.orientation.z,
                  r.pose.orientation.w]}


def latest(topic, typ, timeout=60.0):
    return rospy.wait_for_message(topic, typ, timeout=timeout)


def mode_range():
    out = {}
    svc('/gazebo/unpause_physics', Empty)()
    m = latest('/sonar/range', Range)
    out['near'] = [m.range, m.min_range, m.max_range, m.field_of_view, m.radiation_type,
                   m.header.frame_id]
    req = gm.ModelState(model_name='wall', reference_frame='world')
    req.pose.position.z = 0.5
    req.pose.orientation.w = 1.0

    def range_with_wall_at(x):
        """The sonar's range once the wall stands at x (a message measured 0.1 s after)."""
        req.pose.position.x = x
        svc('/gazebo/set_model_state', gs.SetModelState)(req)
        t0 = sim_time()
        while True:
            m = latest('/sonar/range', Range)
            if m.header.stamp.to_sec() > t0 + 0.1:
                return m.range

    out['moved'] = range_with_wall_at(1.2)
    out['nothing'] = range_with_wall_at(20.0)
    ir = latest('/ir/range', Range)
    out['ir'] = [ir.radiation_type, ir.header.frame_id]
    return out


def mode_planar():
    """planar_move driven by cmd_vel; odometry and p3d against the model's true state."""
    out = {}
    odoms, truths = [], []
    rospy.Subscriber('/odom', Odometry, odoms.append)
    rospy.Subscriber('/mover/ground_truth', Odometry, truths.append)
    for topic in ('/odom', '/mover/ground_truth'):
        wait_subscribed(topic)
    pub = rospy.Publisher('/cmd_vel', Twist, queue_size=10)
    wait_connected(pub)
    cmd = Twist()
    cmd.linear.x, cmd.linear.y = 0.5, 0.2
    command(pub, cmd, '/cmd_vel')
    start, out['t_start'] = state('mover'), sim_time()
    # odometry every 0.051 s from a queue of 1 (as the original's): flushed every 0.05 s
    flush = (('/odom', odoms), ('/mover/ground_truth', truths))
    step_through(out['t_start'] + 2.0 - time_step(), 0.05, flush)
    ms, t_end = next_message('/gazebo/model_states', gm.ModelStates)     # of the last step
    end = state('mover')
    for topic, msgs in flush:
        wait_flushed(topic, msgs)
    o, g = odoms[-1], truths[-1]
    out['start'], out['end'], out['t_end'] = start, end, t_end
    out['odom'] = {'stamp': o.header.stamp.to_sec(), 'frame': o.header.frame_id,
                   'child': o.child_frame_id,
                   'xy': [o.pose.pose.position.x, o.pose.pose.position.y],
                   'vel': [o.twist.twist.linear.x, o.twist.twist.linear.y,
                           o.twist.twist.angular.z]}
    out['p3d'] = {'stamp': g.header.stamp.to_sec(), 'frame': g.header.frame_id,
                  'child': g.child_frame_id,
                  'xyz': [g.pose.pose.position.x, g.pose.pose.position.y,
                          g.pose.pose.position.z],
                  'vel': [g.twist.twist.linear.x, g.twist.twist.linear.y]}
    out['odom_n'] = len(odoms)
    out['odom_stamps'] = [m.header.stamp.to_sec() for m in odoms[-5:]]
    i = ms.name.index('mover')
    out['model_states'] = [ms.pose[i].position.x, ms.pose[i].position.y, ms.pose[i].position.z]
    # turn on the spot
    cmd = Twist()
    cmd.angular.z = 0.5
    command(pub, cmd, '/cmd_vel')
    step_to(t_end + 1.0)
    out['turned'] = state('mover')
    wait_flushed('/odom', odoms)
    out['odom_w'] = odoms[-1].twist.twist.angular.z
    return out


def mode_force():
    out = {}
    pub = rospy.Publisher('/push', Wrench, queue_size=10)
    wait_connected(pub)
    w = Wrench()
    w.force.x = 2.0
    command(pub, w, '/push')
    s1, t1 = state('puck'), sim_time()
    t2 = step_to(t1 + 1.0)
    s2 = state('puck')
    out['accel'] = (s2['vel'][0] - s1['vel'][0]) / (t2 - t1)
    command(pub, Wrench(), '/push')
    s3, t3 = state('puck'), sim_time()
    step_to(t3 + 0.5)
    s4 = state('puck')
    out['coast'] = [s3['vel'][0], s4['vel'][0]]
    return out


def mode_gripper():
    """The parcel's state and the grasping flag the plugin publishes at the next step."""
    out = {}

    def grasping():
        return next_message('/gripper/grasping', Bool)[0].data
    svc('/gripper/on', Empty)()
    step_to(sim_time() + 1.0)
    out['held'] = state('parcel')['xyz']
    out['grasping_on'] = grasping()
    svc('/gripper/off', Empty)()
    step_to(sim_time() + 1.0)
    out['dropped'] = state('parcel')['xyz']
    out['grasping_off'] = grasping()
    # on again with the parcel far below: nothing within reach, it stays on the ground
    svc('/gripper/on', Empty)()
    step_to(sim_time() + 0.5)
    out['out_of_reach'] = state('parcel')['xyz']
    out['grasping_far'] = grasping()
    return out


def mode_block():
    from sensor_msgs.msg import PointCloud
    svc('/gazebo/unpause_physics', Empty)()
    m = latest('/block/cloud', PointCloud)
    return {'frame': m.header.frame_id, 'points': [[p.x, p.y, p.z] for p in m.points],
            'channels': [list(c.values) for c in m.channels]}


def mode_trajectory():
    """The joint's position step by step (/gazebo/step_world of the paused world) once the
    simulator has read the trajectory: the sim times the points are applied at are counted in
    steps, whatever the machine's speed."""
    from trajectory_msgs.msg import JointTrajectory, JointTrajectoryPoint
    out = {}
    joint = svc('/gazebo/get_joint_properties', gs.GetJointProperties)

    def swivel():
        return joint('swivel').position[0]

    pub = rospy.Publisher('/set_joint_trajectory', JointTrajectory, queue_size=1, latch=True)
    wait_connected(pub)
    traj = JointTrajectory()
    traj.header.frame_id = 'world'
    traj.joint_names = ['swivel']
    traj.points = [JointTrajectoryPoint(positions=[0.5], time_from_start=rospy.Duration(0.2)),
                   JointTrajectoryPoint(positions=[1.0], time_from_start=rospy.Duration(0.3))]
    dt = time_step()
    t0, rest = sim_time(), swivel()
    send(pub, traj, '/set_joint_trajectory')
    base = state('turret')['xyz']
    out['dt'], out['rest'], out['unstepped'] = dt, rest, swivel()
    # one step at a time until the first point is set (at most 0.2 s of sim time)
    q, t = rest, t0
    while abs(q - rest) < 1e-9 and t - t0 < 0.2:
        t = step(1)
        q = swivel()
    out['first'] = [t - t0, q]
    # the second point: due 0.2 s (the first point's time_from_start) after the step that set
    # the first; the joint holds the first point until that step, the second is set by it
    t_due = t - dt + 0.2
    t = step_to(t_due)
    out['held'] = [t - t0, swivel()]
    t = step(1)
    out['second'] = [t - t0, swivel()]
    t = step_to(t0 + 0.8)               # past the trajectory's end (its last point: 0.3 s)
    out['after'] = [t - t0, swivel()]
    out['base_kept'] = [base, state('turret')['xyz']]
    return out


def mode_triggered():
    from sensor_msgs.msg import Image
    from std_msgs.msg import Empty as EmptyMsg
    out = {}
    images = []
    rospy.Subscriber('/cam/image_raw', Image, images.append)
    trig = rospy.Publisher('/cam/image_trigger', EmptyMsg, queue_size=10)
    svc('/gazebo/unpause_physics', Empty)()
    deadline = time.monotonic() + 30
    while trig.get_num_connections() == 0 and time.monotonic() < deadline:
        time.sleep(0.1)
    time.sleep(2.0)
    out['before'] = len(images)             # nothing without a trigger
    counts = []
    for _ in range(3):
        trig.publish(EmptyMsg())
        deadline = time.monotonic() + 60
        n = len(counts) + 1
        while len(images) < n and time.monotonic() < deadline:
            time.sleep(0.05)
        time.sleep(1.5)                     # a second frame would come within this
        counts.append(len(images))
    out['counts'] = counts
    out['stamps'] = [m.header.stamp.to_sec() for m in images]
    out['size'] = [images[0].width, images[0].height, images[0].encoding] if images else None
    return out


def mode_stereo():
    """The red post's column in the left and right images (centroid of its pixels)."""
    import numpy as np
    from sensor_msgs.msg import CameraInfo, Image
    svc('/gazebo/unpause_physics', Empty)()
    out = {}
    for side in ('left', 'right'):
        img = latest('/stereo/%s/image_raw' % side, Image)
        info = latest('/stereo/%s/camera_info' % side, CameraInfo)
        a = np.frombuffer(img.data, dtype=np.uint8).reshape(img.height, img.width, 3)
        r, g, b = (a[:, :, k].astype(int) for k in range(3))
        red = (r > g + 40) & (r > b + 40)
        cols = np.nonzero(red)[1]
        out[side] = {'col': float(cols.mean()) if len(cols) else None, 'n': int(len(cols)),
                     'P': list(info.P), 'frame': img.header.frame_id,
                     'stamp': img.header.stamp.to_sec(),
                     'centre': a[img.height // 2, img.width // 2].tolist()}
    return out


def mode_gps():
    from geometry_msgs.msg import Vector3Stamped
    from sensor_msgs.msg import NavSatFix
    fixes, vels = [], []
    rospy.Subscriber('/rover/fix', NavSatFix, fixes.append)
    rospy.Subscriber('/rover/fix_velocity', Vector3Stamped, vels.append)
    for topic in ('/rover/fix', '/rover/fix_velocity'):
        wait_subscribed(topic)
    pub = rospy.Publisher('/rover/cmd_vel', Twist, queue_size=10)
    wait_connected(pub)
    cmd = Twist()
    cmd.linear.x, cmd.linear.y = 1.0, 0.5
    command(pub, cmd, '/rover/cmd_vel')
    # 10 Hz from queues of 10: flushed every 0.5 s
    flush = (('/rover/fix', fixes), ('/rover/fix_velocity', vels))
    t_end = step_through(sim_time() + 3.0, 0.5, flush)
    end = state('rover')
    f, v = fixes[-1], vels[-1]
    return {'end': end, 't_end': t_end, 'stamp': f.header.stamp.to_sec(),
            'fix': [f.latitude, f.longitude, f.altitude], 'frame': f.header.frame_id,
            'status': [f.status.status, f.status.service, f.position_covariance_type],
            'vel': [v.vector.x, v.vector.y, v.vector.z],
            'stamps': [m.header.stamp.to_sec() for m in fixes[-4:]]}


def mode_imu_gpu():
    """imu_sensor on a spinning floating box; gpu_laser facing a wall."""
    import math
    from sensor_msgs.msg import Imu, LaserScan
    imus = []
    rospy.Subscriber('/spinner/imu', Imu, imus.append)
    req = gm.ModelState(model_name='spinner', reference_frame='world')
    req.pose.position.z, req.pose.orientation.w = 1.0, 1.0
    req.twist.angular.z = 0.5
    wait_subscribed('/spinner/imu')
    svc('/gazebo/set_model_state', gs.SetModelState)(req)
    t_end = step_to(sim_time() + 1.0)
    end = state('spinner')
    wait_flushed('/spinner/imu', imus)
    m = imus[-1]
    q = m.orientation
    yaw = math.atan2(2 * (q.w * q.z + q.x * q.y), 1 - 2 * (q.y * q.y + q.z * q.z))
    qe = end['q']
    yaw_end = math.atan2(2 * (qe[3] * qe[2] + qe[0] * qe[1]), 1 - 2 * (qe[1] ** 2 + qe[2] ** 2))
    svc('/gazebo/unpause_physics', Empty)()
    scan = latest('/gpu_scan', LaserScan)
    return {'lag': t_end - m.header.stamp.to_sec(), 'yaw': yaw, 'yaw_end': yaw_end,
            'w': [m.angular_velocity.x, m.angular_velocity.y, m.angular_velocity.z],
            'acc': [m.linear_acceleration.x, m.linear_acceleration.y, m.linear_acceleration.z],
            'frame': m.header.frame_id, 'n': len(imus),
            'scan_mid': scan.ranges[len(scan.ranges) // 2], 'scan_frame': scan.header.frame_id}


def main():
    rospy.init_node('plugin_client', anonymous=True)
    out = {'range': mode_range, 'planar': mode_planar, 'force': mode_force,
           'gripper': mode_gripper, 'block': mode_block,
           'trajectory': mode_trajectory, 'triggered': mode_triggered,
           'stereo': mode_stereo, 'gps': mode_gps,
           'imu_gpu': mode_imu_gpu}[sys.argv[1]]()
    print(json.dumps(out))


if __name__ == '__main__':
    main()
