"""The amcl node: parameters, topics, services and tf around amcl.localizer (amcl_node.cpp's
job). Messages are converted in amcl.convert only."""
import math
import threading

import numpy as np
import rospy
import tf2_ros
from geometry_msgs.msg import PoseArray, PoseWithCovarianceStamped
from nav_msgs.msg import OccupancyGrid
from nav_msgs.srv import GetMap, SetMap, SetMapResponse
from sensor_msgs.msg import LaserScan
from std_srvs.srv import Empty, EmptyResponse

from . import convert
from .localizer import Config, Localizer
from .sensors import LASER_MODELS, ODOM_MODELS

CHECK_LASER_INTERVAL = 15.0     # s: warn when no scan arrived for this long (as amcl)


class AmclNode:
    def __init__(self):
        self.lock = threading.RLock()
        self.cfg = self.read_params()
        self.loc = Localizer(self.cfg)
        self.tf_buffer = tf2_ros.Buffer(rospy.Duration(30.0))
        self.tf_listener = tf2_ros.TransformListener(self.tf_buffer)
        self.tf_broadcaster = tf2_ros.TransformBroadcaster()
        self.laser_poses = {}
        self.first_map_received = False
        self.last_cloud = None
        self.last_save = None
        self.last_scan = None
        self.latest_tf_valid = False
        self.pose_pub = rospy.Publisher('amcl_pose', PoseWithCovarianceStamped, queue_size=2, latch=True)
        self.cloud_pub = rospy.Publisher('particlecloud', PoseArray, queue_size=2, latch=True)
        rospy.Service('global_localization', Empty, self.global_localization)
        rospy.Service('request_nomotion_update', Empty, self.nomotion_update)
        rospy.Service('set_map', SetMap, self.set_map)
        rospy.Subscriber('initialpose', PoseWithCovarianceStamped, self.initial_pose_received, queue_size=2)
        if self.use_map_topic:
            self.map_sub = rospy.Subscriber('map', OccupancyGrid, self.map_received, queue_size=1)
            rospy.loginfo('Subscribed to map topic.')
        else:
            threading.Thread(target=self.request_map, daemon=True).start()
        rospy.Subscriber('scan', LaserScan, self.laser_received, queue_size=100, buff_size=2 ** 22)
        self.start_time = rospy.Time.now()
        rospy.Timer(rospy.Duration(CHECK_LASER_INTERVAL), self.check_laser)

    # -- parameters ------------------------------------------------------------------------
    def read_params(self):
        p = lambda name, default: rospy.get_param('~' + name, default)  # noqa: E731
        cfg = Config()
        for name in ('min_particles', 'max_particles', 'resample_interval', 'laser_max_beams'):
            setattr(cfg, name, int(p(name, getattr(cfg, name))))
        for name in ('kld_err', 'kld_z', 'update_min_d', 'update_min_a', 'recovery_alpha_slow',
                     'recovery_alpha_fast', 'laser_z_hit', 'laser_z_short', 'laser_z_max', 'laser_z_rand',
                     'laser_sigma_hit', 'laser_lambda_short', 'laser_likelihood_max_dist', 'beam_skip_distance',
                     'beam_skip_threshold', 'beam_skip_error_threshold', 'odom_alpha1', 'odom_alpha2',
                     'odom_alpha3', 'odom_alpha4', 'odom_alpha5'):
            setattr(cfg, name, float(p(name, getattr(cfg, name))))
        cfg.do_beamskip = bool(p('do_beamskip', False))
        cfg.selective_resampling = bool(p('selective_resampling', False))
        if cfg.min_particles > cfg.max_particles:
            rospy.logwarn("You've set min_particles to be greater than max particles, this isn't allowed "
                          "so they'll be set to be equal.")
            cfg.max_particles = cfg.min_particles
        if cfg.resample_interval < 1:
            rospy.logwarn('resample_interval must be >= 1, got %d; using 1', cfg.resample_interval)
            cfg.resample_interval = 1
        if cfg.laser_max_beams < 2:
            rospy.logwarn('laser_max_beams must be >= 2, got %d; using 2', cfg.laser_max_beams)
            cfg.laser_max_beams = 2
        laser_model = p('laser_model_type', 'likelihood_field')
        if laser_model not in LASER_MODELS:
            rospy.logwarn('Unknown laser model type "%s"; defaulting to likelihood_field model', laser_model)
            laser_model = 'likelihood_field'
        cfg.laser_model_type = laser_model
        odom_model = p('odom_model_type', 'diff')
        if odom_model not in ODOM_MODELS:
            rospy.logwarn('Unknown odom model type "%s"; defaulting to diff model', odom_model)
            odom_model = 'diff'
        cfg.odom_model_type = odom_model
        init = [p('initial_pose_x', 0.0), p('initial_pose_y', 0.0), p('initial_pose_a', 0.0)]
        cov = [p('initial_cov_xx', 0.5 * 0.5), p('initial_cov_yy', 0.5 * 0.5), p('initial_cov_aa', (math.pi / 12) ** 2)]
        cfg.initial_pose = tuple(float(v) if not math.isnan(float(v)) else 0.0 for v in init)
        cfg.initial_cov = tuple(float(v) if not math.isnan(float(v)) else d for v, d in zip(cov, Config.initial_cov))
        self.laser_min_range = float(p('laser_min_range', -1.0))
        self.laser_max_range = float(p('laser_max_range', -1.0))
        self.gui_publish_rate = float(p('gui_publish_rate', -1.0))
        self.save_pose_rate = float(p('save_pose_rate', 0.5))
        self.use_map_topic = bool(p('use_map_topic', False))
        self.first_map_only = bool(p('first_map_only', False))
        self.odom_frame_id = p('odom_frame_id', 'odom').lstrip('/')
        self.base_frame_id = p('base_frame_id', 'base_link').lstrip('/')
        self.global_frame_id = p('global_frame_id', 'map').lstrip('/')
        self.transform_tolerance = float(p('transform_tolerance', 0.1))
        self.tf_broadcast = bool(p('tf_broadcast', True))
        return cfg

    # -- map ---------------------------------------------------------------------------------
    def request_map(self):
        rospy.loginfo('Requesting the map...')
        while not rospy.is_shutdown():
            try:
                rospy.wait_for_service('static_map', timeout=0.5)
                resp = rospy.ServiceProxy('static_map', GetMap)()
                self.handle_map(resp.map)
                return
            except (rospy.ROSException, rospy.ServiceException):
                rospy.logwarn('Request for map failed; trying again...')
                threading.Event().wait(0.5)     # wall time: the clock may not run yet

    def map_received(self, msg):
        if self.first_map_only and self.first_map_received:
            return
        self.handle_map(msg)
        self.first_map_received = True

    def handle_map(self, msg, initial=None):
        rospy.loginfo('Received a %d X %d map @ %.3f m/pix', msg.info.width, msg.info.height, msg.info.resolution)
        if msg.header.frame_id.lstrip('/') != self.global_frame_id:
            rospy.logwarn("Frame_id of map received:'%s' doesn't match global_frame_id:'%s'. This could cause "
                          "issues with reading published topics", msg.header.frame_id, self.global_frame_id)
        try:
            gmap = convert.map_from_msg(msg)
        except ValueError as e:
            rospy.logerr('Ignoring the map: %s', e)
            return False
        with self.lock:
            if self.cfg.laser_model_type != 'beam':
                rospy.loginfo('Initializing likelihood field model; this can take some time on large maps...')
            mean, cov = initial if initial is not None else (None, None)
            self.loc.set_map(gmap, mean, cov)
            if self.cfg.laser_model_type != 'beam':
                rospy.loginfo('Done initializing likelihood field model.')
            self.laser_poses.clear()
            self.latest_tf_valid = False
        return True

    def set_map(self, req):
        mean, cov = convert.initial_pose_from_msg(req.initial_pose)
        ok = self.handle_map(req.map, (mean, cov))
        return SetMapResponse(success=ok)

    # -- services and initial pose ---------------------------------------------------------
    def global_localization(self, _req):
        with self.lock:
            if self.loc.map is None:
                rospy.logwarn('global_localization: no map yet')
                return EmptyResponse()
            rospy.loginfo('Initializing with uniform distribution')
            self.loc.global_localization()
            rospy.loginfo('Global initialisation done!')
        return EmptyResponse()

    def nomotion_update(self, _req):
        with self.lock:
            self.loc.request_nomotion_update()
        rospy.loginfo('Requesting no-motion update')
        return EmptyResponse()

    def initial_pose_received(self, msg):
        frame = msg.header.frame_id.lstrip('/')
        if not frame:
            rospy.logwarn('Received initial pose with empty frame_id.  You should always supply a frame_id.')
        elif frame != self.global_frame_id:
            rospy.logwarn('Ignoring initial pose in frame "%s"; initial poses must be in the global frame, "%s"',
                          frame, self.global_frame_id)
            return
        mean, cov = convert.initial_pose_from_msg(msg)
        if not np.all(np.isfinite(mean)) or not np.all(np.isfinite(cov)):
            rospy.logwarn('Ignoring initial pose with NaN or inf values')
            return
        rospy.loginfo('Setting pose (%.6f): %.3f %.3f %.3f', rospy.get_time(), mean[0], mean[1], mean[2])
        with self.lock:
            if self.loc.pf is None:
                self.cfg.initial_pose = tuple(mean)
                self.cfg.initial_cov = (cov[0, 0], cov[1, 1], cov[2, 2])
                return
            self.loc.set_initial_pose(mean, cov)

    # -- scans ---------------------------------------------------------------------------------
    def laser_pose(self, frame):
        if frame not in self.laser_poses:
            try:
                t = self.tf_buffer.lookup_transform(self.base_frame_id, frame, rospy.Time(0))
            except tf2_ros.TransformException as e:
                rospy.logwarn_throttle(5.0, "Couldn't transform from %s to %s, even though the message notifier "
                                       "is in use (%s)" % (frame, self.base_frame_id, e))
                return None
            rospy.loginfo('Setting up laser %d (frame_id=%s)', len(self.laser_poses), frame)
            self.laser_poses[frame] = t
        return self.laser_poses[frame]

    def laser_received(self, scan):
        self.last_scan = rospy.Time.now()
        with self.lock:
            if self.loc.pf is None:
                return
            frame = scan.header.frame_id.lstrip('/')
            laser = self.laser_pose(frame)
            if laser is None:
                return
            try:
                odom = self.tf_buffer.lookup_transform(self.odom_frame_id, self.base_frame_id, scan.header.stamp,
                                                       rospy.Duration(0.2))
            except tf2_ros.TransformException as e:
                rospy.logwarn_throttle(5.0, 'Failed to compute odom pose, skipping scan (%s)' % e)
                return
            data = convert.laser_data(scan, laser, self.laser_min_range, self.laser_max_range)
            res = self.loc.process(convert.pose_from_transform(odom), data)
            stamp = scan.header.stamp
            if res.updated:
                self.publish_cloud(stamp)
                self.pose_pub.publish(convert.pose_with_covariance(res.pose, res.cov, stamp, self.global_frame_id))
                rospy.logdebug('New pose: %6.3f %6.3f %6.3f', res.pose[0], res.pose[1], res.pose[2])
                self.latest_tf_valid = True
                self.save_pose(res.pose, res.cov)
            if self.latest_tf_valid and self.tf_broadcast and res.map_to_odom is not None:
                expiry = stamp + rospy.Duration(self.transform_tolerance)
                self.tf_broadcaster.sendTransform(
                    convert.transform(res.map_to_odom, expiry, self.global_frame_id, self.odom_frame_id))

    def publish_cloud(self, stamp):
        now = rospy.Time.now()
        if (self.gui_publish_rate > 0 and self.last_cloud is not None
                and (now - self.last_cloud).to_sec() < 1.0 / self.gui_publish_rate):
            return
        self.last_cloud = now
        self.cloud_pub.publish(convert.pose_array(self.loc.pf.poses, stamp, self.global_frame_id))

    def save_pose(self, pose, cov):
        if self.save_pose_rate <= 0:
            return
        now = rospy.Time.now()
        if self.last_save is not None and (now - self.last_save).to_sec() < 1.0 / self.save_pose_rate:
            return
        self.last_save = now
        for name, value in (('initial_pose_x', pose[0]), ('initial_pose_y', pose[1]), ('initial_pose_a', pose[2]),
                            ('initial_cov_xx', cov[0, 0]), ('initial_cov_yy', cov[1, 1]),
                            ('initial_cov_aa', cov[2, 2])):
            rospy.set_param('~' + name, float(value))

    def check_laser(self, _event):
        now = rospy.Time.now()
        since = self.last_scan if self.last_scan is not None else self.start_time
        if (now - since).to_sec() > CHECK_LASER_INTERVAL:
            rospy.logwarn('No laser scan received (and thus no pose updates have been published) for %f seconds.  '
                          'Verify that data is being published on the %s topic.',
                          (now - since).to_sec(), rospy.resolve_name('scan'))


def main():
    rospy.init_node('amcl')
    AmclNode()
    rospy.spin()
