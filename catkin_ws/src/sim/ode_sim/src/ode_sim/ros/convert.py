"""The one conversion module between ROS messages and engine / description types.

Engine and description code work with ode_sim.description.transforms.Pose (p: xyz, q: xyzw as
ROS orders it), numpy 3-vectors and plain floats; everything that builds or reads a message
field goes through the functions here."""
import struct

import numpy as np
from geometry_msgs.msg import Pose as PoseMsg, Twist, Vector3

from course_runtime.transforms import transform_stamped
from ode_sim.description.transforms import Pose


def pose_msg(pose):
    """A new geometry_msgs/Pose from a Pose."""
    m = PoseMsg()
    fill_pose(m, pose)
    return m


def fill_pose(msg_pose, pose):
    """Write a Pose into a geometry_msgs/Pose (or any object with position / orientation)."""
    msg_pose.position.x, msg_pose.position.y, msg_pose.position.z = (float(v) for v in pose.p)
    q = msg_pose.orientation
    q.x, q.y, q.z, q.w = (float(v) for v in pose.q)


def fill_pose_tuples(msg_pose, p, q):
    """fill_pose from float tuples p (x, y, z) and q (x, y, z, w)."""
    pos = msg_pose.position
    pos.x, pos.y, pos.z = p
    o = msg_pose.orientation
    o.x, o.y, o.z, o.w = q


def fill_vector(msg_vec, v):
    msg_vec.x, msg_vec.y, msg_vec.z = (float(x) for x in v)


def vector(msg_vec):
    """geometry_msgs/Vector3 or Point -> numpy 3-vector."""
    return np.array((msg_vec.x, msg_vec.y, msg_vec.z), dtype=float)


def pose_from_msg(msg_pose):
    """geometry_msgs/Pose -> Pose; an all-zero quaternion (an unset field) means identity, as
    gazebo_ros reads requests."""
    p = msg_pose.position
    o = msg_pose.orientation
    q = (o.x, o.y, o.z, o.w)
    if q == (0.0, 0.0, 0.0, 0.0):
        q = (0.0, 0.0, 0.0, 1.0)
    return Pose((p.x, p.y, p.z), q)


def twist_msg(lin, ang):
    t = Twist()
    t.linear = Vector3(*[float(v) for v in lin])
    t.angular = Vector3(*[float(v) for v in ang])
    return t


def transform_msg(stamp, parent, child, pose):
    """geometry_msgs/TransformStamped parent -> child at `pose`."""
    return transform_stamped(stamp, parent, child, pose.p, pose.q)


def odometry_msg(stamp, frame, child, p, q, vx, vy, wz, pose_covariance=(),
                 twist_covariance=()):
    """nav_msgs/Odometry of a planar base: pose p (x, y, z), q (x, y, z, w) in `frame`, twist
    vx, vy, wz in `child`'s axes; covariances as (index, value) pairs (the rest 0)."""
    from nav_msgs.msg import Odometry
    msg = Odometry()
    msg.header.stamp = stamp
    msg.header.frame_id = frame
    msg.child_frame_id = child
    fill_pose_tuples(msg.pose.pose, p, q)
    t = msg.twist.twist
    t.linear.x, t.linear.y, t.angular.z = vx, vy, wz
    for i, v in pose_covariance:
        msg.pose.covariance[i] = v
    for i, v in twist_covariance:
        msg.twist.covariance[i] = v
    return msg


def planar_twist(msg):
    """(linear.x, angular.z) of a geometry_msgs/Twist as floats: a drive's command."""
    return float(msg.linear.x), float(msg.angular.z)


def joint_state_msg(stamp, names, positions):
    """sensor_msgs/JointState with names and positions (no velocities, no efforts)."""
    from sensor_msgs.msg import JointState
    msg = JointState()
    msg.header.stamp = stamp
    msg.name = list(names)
    msg.position = [float(v) for v in positions]
    return msg


def imu_msg(stamp, frame, q, angular_velocity, linear_acceleration, variance):
    """sensor_msgs/Imu: orientation q (x, y, z, w), angular velocity and linear acceleration
    (3-sequences); `variance` on the diagonal of all three covariances."""
    from sensor_msgs.msg import Imu
    msg = Imu()
    msg.header.stamp = stamp
    msg.header.frame_id = frame
    o = msg.orientation
    o.x, o.y, o.z, o.w = q
    fill_vector(msg.angular_velocity, angular_velocity)
    fill_vector(msg.linear_acceleration, linear_acceleration)
    for cov in (msg.orientation_covariance, msg.angular_velocity_covariance,
                msg.linear_acceleration_covariance):
        cov[0] = cov[4] = cov[8] = variance
    return msg


def fill_laserscan(msg, model, ranges, intensities, stamp=None, frame=None):
    """Fill a sensor_msgs/LaserScan (or any object with its fields; None: a new LaserScan)
    from an engine LaserModel the way gazebo_ros_laser does. Returns the message."""
    if msg is None:
        from sensor_msgs.msg import LaserScan
        msg = LaserScan()
    if stamp is not None:
        msg.header.stamp = stamp
    if frame is not None:
        msg.header.frame_id = frame
    msg.angle_min = float(model.min_angle)
    msg.angle_max = float(model.max_angle)
    msg.angle_increment = float(model.angle_increment)
    msg.time_increment = 0.0
    msg.scan_time = 0.0
    msg.range_min = float(model.range_min)
    msg.range_max = float(model.range_max)
    msg.ranges = np.asarray(ranges, dtype=float).tolist()
    msg.intensities = np.asarray(intensities, dtype=float).tolist()
    return msg


def ros_time_text(t):
    """ros::Time as roscpp streams it: seconds, a dot, nine digits of nanoseconds."""
    ns = int(round(t * 1e9))
    return '%d.%09d' % (ns // 1000000000, ns % 1000000000)


def contacts_state(points, stamp, frame):
    """gazebo_msgs/ContactsState from engine ContactPoints (engine/contacts.py) as
    gazebo_ros_bumper builds it: one ContactState per touching pair of collisions and step
    (collision1 = the sensor's), its points' wrenches on collision1's body, positions and
    normals in the world frame, depths, the summed total_wrench, and the original's info line."""
    from gazebo_msgs.msg import ContactsState, ContactState
    from geometry_msgs.msg import Wrench
    groups = []
    for p in points:
        if not groups or (groups[-1][0].time, groups[-1][0].mine, groups[-1][0].other) != \
                (p.time, p.mine, p.other):
            groups.append([])
        groups[-1].append(p)
    msg = ContactsState()
    msg.header.stamp = stamp
    msg.header.frame_id = frame
    for i, g in enumerate(groups):
        s = ContactState()
        s.collision1_name, s.collision2_name = g[0].mine, g[0].other
        s.info = ('Debug:  i:(%d/%d)     my geom:%s   other geom:%s         time:%s\n'
                  % (i, len(groups), s.collision1_name, s.collision2_name,
                     ros_time_text(g[0].time)))
        total = np.zeros(6)
        for p in g:
            w = Wrench()
            fill_vector(w.force, p.force)
            fill_vector(w.torque, p.torque)
            s.wrenches.append(w)
            total += np.r_[p.force, p.torque]
            s.contact_positions.append(Vector3(*(float(v) for v in p.position)))
            s.contact_normals.append(Vector3(*(float(v) for v in p.normal)))
            s.depths.append(float(p.depth))
        fill_vector(s.total_wrench.force, total[:3])
        fill_vector(s.total_wrench.torque, total[3:])
        msg.states.append(s)
    return msg


def image_msg(data, width, height, encoding, channels, depth, frame_id, stamp):
    """sensor_msgs/Image of `data` (bytes): `channels` channels of `depth` bytes per pixel."""
    from sensor_msgs.msg import Image
    msg = Image()
    msg.header.frame_id = frame_id
    msg.header.stamp = stamp
    msg.height, msg.width = height, width
    msg.encoding = encoding
    msg.is_bigendian = 0
    msg.step = width * channels * depth
    msg.data = data
    return msg


def camera_info_msg(width, height, K, P, D, frame_id, stamp):
    """sensor_msgs/CameraInfo ("plumb_bob", R identity) as gazebo_ros_camera_utils fills it."""
    from sensor_msgs.msg import CameraInfo
    msg = CameraInfo()
    msg.header.frame_id = frame_id
    msg.header.stamp = stamp
    msg.width, msg.height = width, height
    msg.distortion_model = 'plumb_bob'
    msg.D = list(D)
    msg.K = [float(v) for v in np.asarray(K).ravel()]
    msg.R = [1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0]
    msg.P = [float(v) for v in np.asarray(P).ravel()]
    return msg


def depth_image_msg(depth, frame_id, stamp):
    """A 32FC1 sensor_msgs/Image of an (h, w) depth array in metres."""
    h, w = depth.shape
    return image_msg(depth.astype('<f4').tobytes(), w, h, '32FC1', 1, 4, frame_id, stamp)


def point_cloud_msg(depth, image_bytes, width, height, hfov, frame_id, stamp):
    """Organized sensor_msgs/PointCloud2 from `depth` (already cut: NaN = no point) and the
    published image bytes, as gazebo_ros_openni_kinect fills it (engine.camera.cloud_points)."""
    from sensor_msgs.msg import PointCloud2, PointField
    from ode_sim.engine.camera import CLOUD_FIELDS, CLOUD_POINT_STEP, cloud_points
    data, dense = cloud_points(depth, image_bytes, width, height, hfov)
    msg = PointCloud2()
    msg.header.frame_id = frame_id
    msg.header.stamp = stamp
    msg.height, msg.width = height, width
    msg.fields = [PointField(name, offset, PointField.FLOAT32, 1)
                  for name, offset in CLOUD_FIELDS]
    msg.is_bigendian = False
    msg.point_step = CLOUD_POINT_STEP
    msg.row_step = CLOUD_POINT_STEP * width
    msg.data = data
    msg.is_dense = dense
    return msg


def xyz(msg_vec):
    """(x, y, z) floats of a geometry_msgs/Vector3 or Point."""
    return float(msg_vec.x), float(msg_vec.y), float(msg_vec.z)


def rgba(msg_color):
    """(r, g, b, a) floats of a std_msgs/ColorRGBA."""
    return float(msg_color.r), float(msg_color.g), float(msg_color.b), float(msg_color.a)


def color_msg(rgba_values):
    """std_msgs/ColorRGBA of (r, g, b, a)."""
    from std_msgs.msg import ColorRGBA
    return ColorRGBA(*[float(v) for v in rgba_values])


class EntityStatesFrame:
    """gazebo_msgs/ModelStates or LinkStates written straight into their wire bytes from float
    tuples: /gazebo/model_states goes out every physics step while someone listens, and building
    one geometry_msgs/Pose and Twist object per entity per step cost more than the physics.
    message(names, states) returns a message of the class whose serialize() writes those bytes
    (its fields stay empty: it is only for a publisher); the names' part is kept while the
    names stay the same."""

    def __init__(self, msg_class):
        self._cls = type('Raw' + msg_class.__name__, (msg_class,), {
            '__slots__': ('raw',), 'serialize': lambda self, buff: buff.write(self.raw)})
        self._names = None

    def message(self, names, states):
        """names: a tuple of str; states: per name ((x, y, z), (qx, qy, qz, qw), (vx, vy, vz),
        (wx, wy, wz)) in the world frame."""
        if names != self._names:
            count = struct.pack('<I', len(names))
            self._head = count + b''.join(struct.pack('<I', len(b)) + b
                                          for b in (n.encode() for n in names))
            self._poses = struct.Struct('<I%dd' % (7 * len(names)))
            self._twists = struct.Struct('<I%dd' % (6 * len(names)))
            self._names = names
        n = len(names)
        poses = [v for p, q, _l, _a in states for v in p + q]
        twists = [v for _p, _q, lin, ang in states for v in lin + ang]
        msg = self._cls()
        msg.raw = self._head + self._poses.pack(n, *poses) + self._twists.pack(n, *twists)
        return msg


def performance_metrics_msg(t, real_time_factor):
    """gazebo_msgs/PerformanceMetrics stamped at sim time t (s)."""
    import rospy
    from gazebo_msgs.msg import PerformanceMetrics
    msg = PerformanceMetrics()
    msg.header.stamp = rospy.Time.from_sec(t)
    msg.real_time_factor = real_time_factor
    return msg


def ode_physics_msg(p, auto_disable, precon_iters):
    """gazebo_msgs/ODEPhysics of a description Physics `p` as get_physics_properties reports
    it (sor_pgs_rms_error_tol 0: Gazebo does not fill it either)."""
    from gazebo_msgs.msg import ODEPhysics
    o = ODEPhysics()
    o.auto_disable_bodies = auto_disable
    o.sor_pgs_precon_iters = int(precon_iters)
    o.sor_pgs_iters = int(p.iters)
    o.sor_pgs_w = float(p.sor)
    o.sor_pgs_rms_error_tol = 0.0
    o.contact_surface_layer = float(p.contact_surface_layer)
    o.contact_max_correcting_vel = float(p.contact_max_correcting_vel)
    o.cfm = float(p.cfm)
    o.erp = float(p.erp)
    o.max_contacts = int(p.max_contacts)
    return o


_MARKER_TYPES = {'cube': 'CUBE', 'cylinder': 'CYLINDER', 'sphere': 'SPHERE',
                 'triangles': 'TRIANGLE_LIST'}


def marker_msg(ns, kind, scale, rgba_values, points=None, colors=None):
    """visualization_msgs/Marker (ADD, not frame-locked) of one shape: kind 'cube' |
    'cylinder' | 'sphere' | 'triangles', scale (x, y, z), colour; a triangle list's vertices
    (N, 3) and per-vertex colours. Header, id and pose: place_marker."""
    from geometry_msgs.msg import Point
    from visualization_msgs.msg import Marker
    m = Marker()
    m.action = Marker.ADD
    m.ns = ns
    m.color = color_msg(rgba_values)
    m.frame_locked = False
    m.type = getattr(Marker, _MARKER_TYPES[kind])
    m.scale.x, m.scale.y, m.scale.z = scale
    if points is not None:
        m.points = [Point(float(x), float(y), float(z)) for x, y, z in points]
    if colors is not None:
        made = {}                       # one ColorRGBA per distinct colour, shared
        m.colors = [made[c] if c in made else made.setdefault(c, color_msg(c)) for c in colors]
    return m


def place_marker(m, marker_id, frame, stamp, pose):
    """Set a Marker's header, id and pose (a Pose); returns it."""
    m.header.frame_id = frame
    m.header.stamp = stamp
    m.id = marker_id
    m.pose = pose_msg(pose)
    return m


def scene_marker_array(frame, markers):
    """visualization_msgs/MarkerArray: a DELETEALL in `frame` first, then `markers`."""
    from visualization_msgs.msg import Marker, MarkerArray
    arr = MarkerArray()
    clear = Marker()
    clear.header.frame_id = frame
    clear.action = Marker.DELETEALL
    arr.markers.append(clear)
    arr.markers.extend(markers)
    return arr
