#!/usr/bin/env python3
"""A user of the gazebo_plugins for test_plugins_gazebo_more.py: `plugin_client.py MODE` reads
a plugin's topics / calls its services against a running sim_node, reads the simulated truth
(/gazebo/get_model_state, /gazebo/model_states) and prints one JSON object."""
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


def run_for(seconds, timeout=120.0):
    """Unpause for `seconds` of sim time, then pause."""
    t_end = sim_time() + seconds
    svc('/gazebo/unpause_physics', Empty)()
    deadline = time.monotonic() + timeout
    while sim_time() < t_end:
        if time.monotonic() > deadline:
            raise SystemExit('sim time did not advance')
        time.sleep(0.02)
    svc('/gazebo/pause_physics', Empty)()


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


def wait_connected(pub, timeout=60.0):
    """Until the publisher has a subscriber (a hang guard, not a measure)."""
    deadline = time.monotonic() + timeout
    while pub.get_num_connections() == 0:
        if time.monotonic() > deadline:
            raise SystemExit('nobody subscribed to %s' % pub.resolved_name)
        time.sleep(0.02)


def wait_delivered(topic, n, node='/gazebo', timeout=60.0):
    """Until NODE has read N messages of TOPIC (its getBusStats; rospy counts a message when
    it has read it, then runs the callback on the same thread)."""
    import rosgraph
    from xmlrpc.client import ServerProxy
    proxy = ServerProxy(rosgraph.Master(rospy.get_name()).lookupNode(node))
    deadline = time.monotonic() + timeout
    while True:
        _code, _msg, (_pubs, subs, _srvs) = proxy.getBusStats(rospy.get_name())
        read = sum(c[2] for name, conns in subs if name == topic for c in conns)
        if read >= n:
            return
        if time.monotonic() > deadline:
            raise SystemExit('%s read %d of %d messages on %s' % (node, read, n, topic))
        time.sleep(0.02)


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
    odoms, truths, states = [], [], []
    rospy.Subscriber('/gazebo/model_states', gm.ModelStates, states.append)
    rospy.Subscriber('/odom', Odometry, odoms.append)
    rospy.Subscriber('/mover/ground_truth', Odometry, truths.append)
    pub = rospy.Publisher('/cmd_vel', Twist, queue_size=1, latch=True)
    cmd = Twist()
    cmd.linear.x, cmd.linear.y = 0.5, 0.2
    pub.publish(cmd)
    time.sleep(1.0)
    start, out['t_start'] = state('mover'), sim_time()
    run_for(2.0)
    end = state('mover')
    t_end = sim_time()
    time.sleep(0.5)
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
    # /gazebo/model_states of the last step before the pause
    ms = states[-1]
    i = ms.name.index('mover')
    out['model_states'] = [ms.pose[i].position.x, ms.pose[i].position.y, ms.pose[i].position.z]
    # turn on the spot
    cmd = Twist()
    cmd.angular.z = 0.5
    pub.publish(cmd)
    time.sleep(0.5)
    run_for(1.0)
    out['turned'] = state('mover')
    out['odom_w'] = odoms[-1].twist.twist.angular.z
    return out


def mode_force():
    out = {}
    pub = rospy.Publisher('/push', Wrench, queue_size=1, latch=True)
    w = Wrench()
    w.force.x = 2.0
    pub.publish(w)
    time.sleep(1.0)
    s1, t1 = state('puck'), sim_time()
    run_for(1.0)
    s2, t2 = state('puck'), sim_time()
    out['accel'] = (s2['vel'][0] - s1['vel'][0]) / (t2 - t1)
    pub.publish(Wrench())
    time.sleep(1.0)
    s3 = state('puck')
    run_for(0.5)
    s4 = state('puck')
    out['coast'] = [s3['vel'][0], s4['vel'][0]]
    return out


def mode_gripper():
    out = {}
    grasp = []
    rospy.Subscriber('/gripper/grasping', Bool, lambda m: grasp.append(m.data))
    svc('/gripper/on', Empty)()
    run_for(1.0)
    out['held'] = state('parcel')['xyz']
    out['grasping_on'] = grasp[-1] if grasp else None
    svc('/gripper/off', Empty)()
    run_for(1.0)
    out['dropped'] = state('parcel')['xyz']
    time.sleep(0.3)
    run_for(0.1)
    time.sleep(0.3)
    out['grasping_off'] = grasp[-1] if grasp else None
    # on again with the parcel far below: nothing within reach, it stays on the ground
    svc('/gripper/on', Empty)()
    run_for(0.5)
    out['out_of_reach'] = state('parcel')['xyz']
    time.sleep(0.3)
    out['grasping_far'] = grasp[-1] if grasp else None
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
    pub.publish(traj)
    wait_delivered('/set_joint_trajectory', 1)
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
    pub = rospy.Publisher('/rover/cmd_vel', Twist, queue_size=1, latch=True)
    cmd = Twist()
    cmd.linear.x, cmd.linear.y = 1.0, 0.5
    pub.publish(cmd)
    time.sleep(1.0)
    run_for(3.0)
    end, t_end = state('rover'), sim_time()
    time.sleep(0.5)
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
    svc('/gazebo/set_model_state', gs.SetModelState)(req)
    time.sleep(1.0)
    run_for(1.0)
    end, t_end = state('spinner'), sim_time()
    time.sleep(0.5)
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
