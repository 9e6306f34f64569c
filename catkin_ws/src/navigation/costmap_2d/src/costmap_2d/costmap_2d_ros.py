"""Costmap2DROS: the ROS wrapper around LayeredCostmap (parameters, TF, sensors, publishers,
the update thread)."""
import threading

import rospy
import tf2_ros
from geometry_msgs.msg import PolygonStamped
from map_msgs.msg import OccupancyGridUpdate
from nav_msgs.msg import OccupancyGrid
from sensor_msgs.msg import LaserScan, PointCloud, PointCloud2

from . import conversions as conv
from .costmap import (FootprintError, make_footprint_from_radius, pad_footprint,
                      parse_footprint, transform_footprint)
from .layers import InflationLayer, LayeredCostmap, Observation, ObstacleLayer, StaticLayer
from .params import COSTMAP_DEFAULTS, layer_specs, observation_sources


class ObservationSource:
    """One sensor of an obstacle layer: the latest observation in the global frame."""

    def __init__(self, owner, name, p):
        self.owner = owner
        self.name = name
        self.p = p
        self.lock = threading.Lock()
        self.observations = []
        self.last_update = None
        topic = p['topic']
        kind = {'LaserScan': LaserScan, 'PointCloud2': PointCloud2,
                'PointCloud': PointCloud}[p['data_type']]
        self.sub = rospy.Subscriber(topic, kind, self.callback, queue_size=1)
        self.resolved_topic = self.sub.resolved_name

    def callback(self, msg):
        p = self.p
        try:
            if isinstance(msg, LaserScan):
                pts = conv.scan_to_points(msg, p['inf_is_valid'])
            elif isinstance(msg, PointCloud2):
                pts = conv.cloud2_to_points(msg)
            else:
                pts = conv.cloud_to_points(msg)
        except ValueError as e:
            rospy.logerr_throttle(5.0, '%s: %s' % (self.name, e))
            return
        frame = msg.header.frame_id
        origin_frame = p['sensor_frame'] or frame
        g = self.owner.global_frame
        try:
            # the original holds observations in a tf message filter until TF has caught up
            wait = rospy.Duration(max(0.1, self.owner.transform_tolerance))
            t_pts = self.owner.tf_buffer.lookup_transform(g, frame, msg.header.stamp, wait)
            t_org = t_pts if origin_frame == frame else self.owner.tf_buffer.lookup_transform(
                g, origin_frame, msg.header.stamp, wait)
        except (tf2_ros.LookupException, tf2_ros.ConnectivityException,
                tf2_ros.ExtrapolationException) as e:
            rospy.logwarn_throttle(
                5.0, 'Transform from %s to %s failed for observation source %s (topic %s): %s'
                % (frame, g, self.name, self.resolved_topic, e))
            return
        m = conv.transform_to_matrix(t_pts.transform)
        world = conv.apply_matrix(m, pts)
        z = world[:, 2]
        world = world[(z >= p['min_obstacle_height']) & (z <= p['max_obstacle_height'])]
        o = t_org.transform.translation
        obs = Observation((o.x, o.y, o.z), world, p['obstacle_range'], p['raytrace_range'])
        now = rospy.Time.now()
        with self.lock:
            if p['observation_persistence'] > 0:
                keep = rospy.Duration(p['observation_persistence'])
                self.observations = [(t, ob) for t, ob in self.observations if now - t <= keep]
                self.observations.append((now, obs))
            else:
                self.observations = [(now, obs)]
            self.last_update = now

    def get(self):
        with self.lock:
            return [ob for _, ob in self.observations]

    def is_current(self):
        rate = self.p['expected_update_rate']
        if rate <= 0:
            return True
        if self.last_update is None:
            return False
        age = (rospy.Time.now() - self.last_update).to_sec()
        if age > rate:
            rospy.logwarn_throttle(
                5.0, 'The %s observation buffer has not been updated for %.2f seconds, and it '
                'should be updated every %.2f seconds.' % (self.resolved_topic, age, rate))
            return False
        return True


def _get(d, key, default):
    v = d.get(key, default)
    return default if v is None else v


class Costmap2DROS:
    def __init__(self, name, tf_buffer):
        self.name = name
        self.tf_buffer = tf_buffer
        self._map_changed = False
        self.ns = rospy.resolve_name('~' + name)
        params = rospy.get_param(self.ns, {})
        if not isinstance(params, dict):
            params = {}
        for k, v in COSTMAP_DEFAULTS.items():
            params.setdefault(k, v)
        self.params = params
        self.global_frame = str(params['global_frame']).lstrip('/')
        self.robot_base_frame = str(params['robot_base_frame']).lstrip('/')
        self.transform_tolerance = float(params['transform_tolerance'])
        self.update_frequency = float(params['update_frequency'])
        self.publish_frequency = float(params['publish_frequency'])
        self.lock = threading.RLock()
        self.layered = LayeredCostmap(self.global_frame, bool(params['rolling_window']),
                                      bool(params['track_unknown_space']))
        res = float(params['resolution'])
        self.layered.resize_map(int(float(params['width']) / res),
                                int(float(params['height']) / res), res,
                                float(params['origin_x']), float(params['origin_y']))
        self.sources = []
        self.obstacle_layers = []
        self.static_subs = []
        specs, warning = layer_specs(params, self.ns)
        if warning:
            rospy.logwarn('%s: %s' % (self.name, warning))
        for lname, kind, lp in specs:
            self._add_layer(lname, kind, lp)
        self._setup_footprint()
        self.costmap_pub = rospy.Publisher(self.ns + '/costmap', OccupancyGrid, queue_size=1,
                                           latch=True)
        self.update_pub = rospy.Publisher(self.ns + '/costmap_updates', OccupancyGridUpdate,
                                          queue_size=1)
        self.footprint_pub = rospy.Publisher(self.ns + '/footprint', PolygonStamped,
                                             queue_size=1)
        self.stopped = False
        self.initialized = False
        self._last_publish = None
        self._published_once = False
        self._stop_event = threading.Event()
        self.thread = threading.Thread(target=self._loop, name=name, daemon=True)
        self.thread.start()

    # ---- construction ------------------------------------------------------------------
    def _add_layer(self, lname, kind, lp):
        lns = '%s/%s' % (self.ns, lname)
        if kind == 'static':
            layer = StaticLayer(lname, bool(_get(lp, 'track_unknown_space', True)),
                                bool(_get(lp, 'use_maximum', False)),
                                int(_get(lp, 'lethal_cost_threshold', 100)),
                                int(_get(lp, 'unknown_cost_value', -1)),
                                bool(_get(lp, 'trinary_costmap', True)))
            layer.enabled = bool(_get(lp, 'enabled', True))
            self.layered.add_plugin(layer)
            topic = _get(lp, 'map_topic', 'map')
            self.first_map_only = bool(_get(lp, 'first_map_only', False))
            rospy.loginfo('%s: requesting the map on %s' % (self.name, rospy.resolve_name(topic)))
            self.static_subs.append(rospy.Subscriber(
                topic, OccupancyGrid, lambda m, lay=layer: self._map_cb(lay, m), queue_size=1))
        elif kind == 'obstacle':
            layer = ObstacleLayer(lname, bool(_get(lp, 'track_unknown_space',
                                                   self.params['track_unknown_space'])),
                                  int(_get(lp, 'combination_method', 1)),
                                  bool(_get(lp, 'footprint_clearing_enabled', True)),
                                  float(_get(lp, 'max_obstacle_height', 2.0)))
            layer.enabled = bool(_get(lp, 'enabled', True))
            self.layered.add_plugin(layer)
            srcs = []
            for sname, sp in observation_sources(lp, lns).items():
                srcs.append(ObservationSource(self, sname, sp))
                rospy.logdebug('%s: observation source %s on %s' % (self.name, sname, sp['topic']))
            self.obstacle_layers.append((layer, srcs))
            self.sources.extend(srcs)
        else:
            layer = InflationLayer(lname, float(_get(lp, 'inflation_radius', 0.55)),
                                   float(_get(lp, 'cost_scaling_factor', 10.0)),
                                   bool(_get(lp, 'inflate_unknown', False)))
            layer.enabled = bool(_get(lp, 'enabled', True))
            self.layered.add_plugin(layer)

    def _setup_footprint(self):
        p = self.params
        fp = p.get('footprint')
        try:
            pts = parse_footprint(fp, self.ns + '/footprint') if fp is not None else []
        except FootprintError as e:
            rospy.logerr(str(e))
            pts = []
        if not pts:
            pts = make_footprint_from_radius(float(p['robot_radius']))
        else:
            pts = pad_footprint(pts, float(p['footprint_padding']))
        self.unpadded = pts
        self.layered.set_footprint(pts)

    def _map_cb(self, layer, msg):
        if layer.map is not None and self.first_map_only:
            return
        rospy.loginfo('%s: received a %d X %d map at %f m/pix' % (
            self.name, msg.info.width, msg.info.height, msg.info.resolution))
        with self.lock:
            layer.map_frame = msg.header.frame_id.lstrip('/') or self.global_frame
            layer.set_map(*conv.map_to_static_args(msg))
            self._map_changed = True

    # ---- pose and state ----------------------------------------------------------------
    def get_robot_pose(self):
        """(x, y, yaw) of robot_base_frame in global_frame, or None (logged)."""
        try:
            t = self.tf_buffer.lookup_transform(self.global_frame, self.robot_base_frame,
                                                rospy.Time(0), rospy.Duration(0.1))
        except (tf2_ros.LookupException, tf2_ros.ConnectivityException,
                tf2_ros.ExtrapolationException) as e:
            rospy.logwarn_throttle(
                1.0, '%s: unable to get the robot pose (%s in %s): %s'
                % (self.name, self.robot_base_frame, self.global_frame, e))
            return None
        now = rospy.Time.now()
        stamp = t.header.stamp
        if stamp != rospy.Time(0) and (now - stamp).to_sec() > self.transform_tolerance:
            rospy.logwarn_throttle(
                1.0, 'Costmap2DROS transform timeout. Current time: %.4f, global_pose stamp: '
                '%.4f, tolerance: %.4f' % (now.to_sec(), stamp.to_sec(), self.transform_tolerance))
            return None
        tr = t.transform
        return tr.translation.x, tr.translation.y, conv.yaw_of(tr.rotation)

    @property
    def costmap(self):
        return self.layered.costmap

    def get_robot_footprint(self, pose=None):
        pose = pose or self.get_robot_pose()
        if pose is None:
            return []
        return transform_footprint(pose[0], pose[1], pose[2], self.layered.footprint)

    def is_current(self):
        return self.layered.is_current() and all(s.is_current() for s in self.sources)

    def update_map(self):
        pose = self.get_robot_pose()
        if pose is None:
            return False
        for layer in self.layered.plugins:
            frame = getattr(layer, 'map_frame', None)
            if frame is None or frame == self.global_frame:
                continue
            try:
                t = self.tf_buffer.lookup_transform(self.global_frame, frame, rospy.Time(0),
                                                    rospy.Duration(0.1))
            except (tf2_ros.LookupException, tf2_ros.ConnectivityException,
                    tf2_ros.ExtrapolationException) as e:
                rospy.logwarn_throttle(5.0, '%s: no transform from the map frame %s to %s: %s'
                                       % (self.name, frame, self.global_frame, e))
                continue
            tr = t.transform
            layer.map_transform = (tr.translation.x, tr.translation.y, conv.yaw_of(tr.rotation))
        with self.lock:
            self._map_changed_seen = self._map_changed
            for layer, srcs in self.obstacle_layers:
                marking, clearing = [], []
                for s in srcs:
                    obs = s.get()
                    if s.p['marking']:
                        marking.extend(obs)
                    if s.p['clearing']:
                        clearing.extend(obs)
                layer.set_observations(marking, clearing)
            self.layered.update_map(*pose)
            self.initialized = True
        self._pose = pose
        return True

    def reset_layers(self):
        with self.lock:
            for p in self.layered.plugins:
                p.reset()
            self.layered.costmap.reset_map()

    def clear_outside(self, reset_distance, pose):
        """clear_costmap_recovery: reset the obstacle layers outside a square of side
        reset_distance around the robot."""
        with self.lock:
            for layer, _ in self.obstacle_layers:
                g = layer.grid
                c = g.world_to_map_array(pose[0], pose[1])
                half = int(reset_distance / 2.0 / g.resolution)
                cx, cy = int(c[0]), int(c[1])
                keep = g.data[max(cy - half, 0):max(cy + half, 0),
                              max(cx - half, 0):max(cx + half, 0)].copy()
                g.reset_map()
                g.data[max(cy - half, 0):max(cy + half, 0),
                       max(cx - half, 0):max(cx + half, 0)] = keep

    # ---- the update thread ---------------------------------------------------------------
    def _loop(self):
        period = 1.0 / self.update_frequency if self.update_frequency > 0 else 0.2
        while not rospy.is_shutdown() and not self._stop_event.is_set():
            start = rospy.Time.now()
            wall0 = rospy.get_time()
            if not self.stopped and self.update_map():
                self._maybe_publish()
            took = rospy.get_time() - wall0
            if self.update_frequency > 0 and took > period:
                rospy.logwarn_throttle(
                    10.0, 'Map update loop missed its desired rate of %.4fHz... the loop '
                    'actually took %.4f seconds' % (self.update_frequency, took))
            try:
                # sleep on ROS time, in small slices so that stop() is prompt
                end = start + rospy.Duration(period)
                while rospy.Time.now() < end and not self._stop_event.is_set():
                    rospy.sleep(min(0.05, period))
            except rospy.ROSInterruptException:
                return

    def _maybe_publish(self):
        """The full grid on <name>/costmap (latched: a late subscriber gets it, as the
        original's on-subscription publish) the first time and whenever the window moved or
        always_send_full_costmap is set; otherwise an update on <name>/costmap_updates.
        publish_frequency 0: only the first full grid."""
        now = rospy.Time.now()
        map_changed = getattr(self, '_map_changed_seen', False)
        self._map_changed_seen = False
        if self._published_once and not map_changed:
            if self.publish_frequency <= 0:
                return
            if (now - self._last_publish).to_sec() < 1.0 / self.publish_frequency - 1e-6:
                return
        with self.lock:
            m = self.layered.costmap
            geom = (m.size_x, m.size_y, m.resolution, m.origin_x, m.origin_y)
            full = (not self._published_once or self.params['always_send_full_costmap'] or
                    map_changed or geom != getattr(self, '_published_geom', None))
            self._map_changed = False
            msg = (conv.costmap_to_grid if full else conv.costmap_to_update)(
                m, self.global_frame, now)
        (self.costmap_pub if full else self.update_pub).publish(msg)
        self._published_geom = geom
        fp = self.get_robot_footprint(getattr(self, '_pose', None))
        self.footprint_pub.publish(conv.footprint_to_polygon(fp, self.global_frame, now))
        self._last_publish = now
        self._published_once = True

    def stop(self):
        self.stopped = True

    def start(self):
        self.stopped = False

    def shutdown(self):
        self._stop_event.set()
