"""Camera plugins: libgazebo_ros_camera.so, libgazebo_ros_openni_kinect.so and
libgazebo_ros_depth_camera.so (gazebo_plugins noetic-devel 2.9.2 behaviour).

libgazebo_ros_camera.so (in a <sensor type="camera"> or "depth"):
  topics <robotNamespace>/<cameraName>/<imageTopicName> (sensor_msgs/Image, default
  `image_raw`) and .../<cameraInfoTopicName> (sensor_msgs/CameraInfo, default `camera_info`),
  each queue 2; absolute topic names stay as written. The image encoding follows the sensor's
  <image><format>: L8 mono8, L16 mono16, R8G8B8 rgb8 (default), B8G8R8 bgr8, R16G16B16 rgb16,
  BAYER_RGGB8/BGGR8/GBRG8/GRBG8 bayer_*8; any other format logs an ERROR and publishes bgr8,
  as the original. Tags: cameraName, imageTopicName, cameraInfoTopicName, frameName (default
  "", the original's member default), updateRate (0 = the sensor's <update_rate>; a positive
  value only throttles further), focalLength / Cx / Cy (0 = computed, as the original:
  f = width / (2 tan(hfov / 2)), cx = (width + 1) / 2, cy = (height + 1) / 2), hackBaseline
  (P[0][3] = -f * hackBaseline), distortionK1..K3 / distortionT1..T2 (CameraInfo D =
  [k1, k2, t1, t2, k3], "plumb_bob"; the image itself is not distorted), CxPrime, borderCrop,
  triggerTopicName, robotNamespace (read and ignored where the original has no visible effect).
  Not provided: dynamic_reconfigure (<cameraName>/set_parameters), camera_info_manager's
  set_camera_info service, image_transport's compressed sub-topics.

libgazebo_ros_openni_kinect.so / libgazebo_ros_depth_camera.so (in a <sensor type="depth">):
  the camera's image and camera_info, plus <depthImageTopicName> (default `depth/image_raw`,
  32FC1 metres along the optical axis, queue 1), <depthImageCameraInfoTopicName>
  (`depth/camera_info`, queue 1) and <pointCloudTopicName> (`points`, sensor_msgs/PointCloud2,
  queue 1), all under <robotNamespace>/<cameraName>/. Depth pixels outside
  (pointCloudCutoff 0.4, pointCloudCutoffMax 5.0) are NaN in the depth image and NaN points in
  the cloud (is_dense false then); libgazebo_ros_depth_camera.so has no upper cutoff (nothing
  hit stays +inf, as Gazebo's depth camera reports it). The cloud is organized (height x width),
  fields x y z rgb (FLOAT32 at offsets 0 4 8 16, point_step 32), points in the optical frame
  convention (z forward along the view axis, x right, y down): x = z (i - (w-1)/2) / f,
  y = z (j - (h-1)/2) / f. The rgb field holds the image bytes in image order (for rgb8:
  R at byte 0, G at 1, B at 2), exactly what the original writes, so with R8G8B8 RViz shows
  red and blue swapped (gazebo_ros_pkgs issue #484, still open); B8G8R8 is the known
  workaround and works here the same way. `baseline` and the other openni tags without an
  effect in the original are ignored.

Frames: the sensor frame (link pose * sensor pose) looks along +X with +Z up (Gazebo's camera
convention); the published header.frame_id is frameName resolved as tf::resolve does with the
namespace as tf_prefix: a leading '/' is stripped ("/camera" -> "camera", so tf2 and RViz accept
it), a relative name gets "<robotNamespace>/" in front when the namespace is not empty/"/".
The `tf_prefix` parameter is not consulted.

Rendering happens only while someone subscribes to the image, the depth image or the cloud
(a camera_info subscriber alone gets camera_info without a render). It runs on a worker thread
of the plugin: update() (simulation thread) takes the camera pose and the sim-time stamp and
hands the frame over; the physics keeps stepping while the frame is rendered, converted and
published (Gazebo renders on its own thread too). A new frame starts only when the previous one
is done, so an update rate above what the renderer sustains yields as many frames as it can.
`wait()` blocks until the frame in flight is published (tests); `sync = True` renders inline.

The image, noise, encoding, depth-cut and point-cloud maths are ROS-free in engine/camera.py
(CameraModel), the messages are built in ros/convert.py; this module wires them to topics.
"""
import concurrent.futures
import threading

import rospy
from sensor_msgs.msg import CameraInfo, Image, PointCloud2

from ode_sim.description.model import ModelError
from ode_sim.engine.camera import CameraModel, camera_info_matrix, cut_depth
from ode_sim.ros.convert import (camera_info_msg, depth_image_msg, image_msg,
                                 point_cloud_msg)
from ode_sim.ros.plugins.base import Plugin
from ode_sim.ros.plugins.laser import sensor_frame_name, sensor_namespace, sensor_world_pose


_LOCKS_GUARD = threading.Lock()


def _render_lock(ctx):
    """One lock per PluginContext: held while rendering and while scenes are rebuilt."""
    lock = getattr(ctx, 'camera_render_lock', None)
    if lock is None:
        with _LOCKS_GUARD:
            lock = getattr(ctx, 'camera_render_lock', None)
            if lock is None:
                lock = ctx.camera_render_lock = threading.Lock()
    return lock


class CameraPlugin(Plugin):
    """libgazebo_ros_camera.so"""

    sensor_plugin = True
    depth_outputs = False            # openni_kinect / depth_camera
    cutoff_max_default = None
    sensor_types = ('camera', 'depth', 'multicamera', 'wideanglecamera')

    def __init__(self, ctx, model, desc, sensor=None):
        super().__init__(ctx, model, desc, sensor)
        if sensor is None or sensor.type not in self.sensor_types:
            raise self.error('must be inside a <sensor type="%s">'
                             % ('depth' if self.depth_outputs else 'camera'))
        self.ns = sensor_namespace(self)
        try:
            self.camera = CameraModel(sensor)
        except ModelError as e:
            raise self.error(str(e)) from None
        if not self.camera.known_format:
            rospy.logerr('%s(ns = %s): Unsupported Gazebo ImageFormat %r, publishing bgr8'
                         % (self.label, self.ns or '/', self.camera.format))
        # plugin tags (the original logs their absence at DEBUG level only)
        self.camera_name = self._tag('cameraName', '').strip()
        if not self.camera_name:
            rospy.logwarn('%s(ns = %s): dynamic reconfigure is not enabled for this image topic '
                          '[%s] because <cameraName> is not specified'
                          % (self.label, self.ns or '/', self._tag('imageTopicName', 'image_raw')))
        self.frame_id = sensor_frame_name(self.ns, self._tag('frameName', '').strip())
        self.plugin_rate = max(0.0, self._tag('updateRate', 0.0, float))
        self._read_intrinsics()
        self._advertise()
        self.link_obj = self.link(sensor.link)
        self.set_rate(sensor.update_rate)
        self._last_pub = None          # sim time of the last published frame (plugin throttle)
        self._seen_version = None
        self._renderer = None
        self._executor = None
        self._future = None
        self.sync = False
        self.frames = 0                # frames rendered and published

    def _tag(self, tag, default, cast=str):
        return self.param(tag, default, cast, warn=False)

    @property
    def rng(self):
        """The random generator of the image noise."""
        return self.camera.rng

    @rng.setter
    def rng(self, rng):
        self.camera.rng = rng

    def _read_intrinsics(self):
        """K, P, D of the camera_info from focalLength, Cx, Cy, hackBaseline, distortion*."""
        cam = self.camera
        focal = self._tag('focalLength', 0.0, float)
        cx = self._tag('Cx', 0.0, float)
        cy = self._tag('Cy', 0.0, float)
        baseline = self._tag('hackBaseline', 0.0, float)
        k1, k2, k3 = (self._tag('distortionK%d' % i, 0.0, float) for i in (1, 2, 3))
        t1, t2 = (self._tag('distortionT%d' % i, 0.0, float) for i in (1, 2))
        computed = cam.focal
        if focal and abs(focal - computed) > 1e-6 * max(1.0, computed):
            rospy.logwarn('%s: The <focal_length>[%f] you have provided for camera [%s] is '
                          'inconsistent with specified image_width [%d] and HFOV [%f]. Please '
                          'double check to see that focal_length = width / (2.0 * tan(HFOV/2.0)), '
                          'the expected focal_length value is [%f]'
                          % (self.label, focal, self.sensor.name, cam.width, cam.hfov, computed))
        self.K, self.P = camera_info_matrix(cam.width, cam.height, cam.hfov,
                                            cx=cx or None, cy=cy or None, focal=focal or None,
                                            hack_baseline=baseline)
        self.D = [k1, k2, t1, t2, k3]

    def _advertise(self):
        """The image and camera_info publishers, and the depth ones for a depth camera."""
        p = self._tag
        base = self.topic(self.camera_name) if self.camera_name else self.topic('')
        base = base.rstrip('/')

        def under(name):
            return name if name.startswith('/') else base + '/' + name

        self.image_topic = under(p('imageTopicName', 'image_raw').strip())
        self.info_topic = under(p('cameraInfoTopicName', 'camera_info').strip())
        self.image_pub = self.ctx.io.publisher(self.image_topic, Image, queue_size=2)
        self.info_pub = self.ctx.io.publisher(self.info_topic, CameraInfo, queue_size=2)
        self.depth_pub = self.depth_info_pub = self.cloud_pub = None
        if not self.depth_outputs:
            return
        self.depth_topic = under(p('depthImageTopicName', 'depth/image_raw').strip())
        self.depth_info_topic = under(p('depthImageCameraInfoTopicName',
                                        'depth/camera_info').strip())
        self.cloud_topic = under(p('pointCloudTopicName', 'points').strip())
        self.cutoff = p('pointCloudCutoff', 0.4, float)
        self.cutoff_max = (p('pointCloudCutoffMax', self.cutoff_max_default, float)
                           if self.cutoff_max_default is not None else None)
        self.depth_pub = self.ctx.io.publisher(self.depth_topic, Image, queue_size=1)
        self.depth_info_pub = self.ctx.io.publisher(self.depth_info_topic, CameraInfo,
                                                    queue_size=1)
        self.cloud_pub = self.ctx.io.publisher(self.cloud_topic, PointCloud2, queue_size=1)

    # ------------------------------------------------------------------ helpers
    def _renderer_get(self):
        if self._renderer is None:
            cam = self.camera
            self._renderer = self.ctx.renderer(cam.width, cam.height, cam.hfov, cam.near,
                                               cam.far, depth=self.depth_outputs)
        return self._renderer

    @staticmethod
    def _subscribed(pub):
        return pub is not None and pub.get_num_connections() > 0

    def camera_pose(self):
        return sensor_world_pose(self.link_obj, self.sensor)

    # ------------------------------------------------------------------ update
    def update(self):
        fut = self._future
        if fut is not None:
            if not fut.done():
                return                  # the previous frame is still in flight: try next step
            self._future = None
            fut.result()                # re-raise a rendering error on the simulation thread
        want_image = self._subscribed(self.image_pub)
        want_info = self._subscribed(self.info_pub)
        want_depth = self._subscribed(self.depth_pub)
        want_cloud = self._subscribed(self.cloud_pub)
        want_dinfo = self._subscribed(self.depth_info_pub)
        if not (want_image or want_info or want_depth or want_cloud or want_dinfo):
            return
        if not self.due():
            return
        t = self.ctx.time
        if self.plugin_rate > 0 and self._last_pub is not None \
                and t - self._last_pub < 1.0 / self.plugin_rate - 1e-9:
            return
        self._last_pub = t
        stamp = self.ctx.now()
        job = (self.camera_pose(), stamp, want_image, want_info, want_depth, want_cloud,
               want_dinfo)
        if not (want_image or want_depth or want_cloud):
            self._publish_infos(stamp, want_info, want_dinfo)
            return
        version = self.ctx.physics.version
        if version != self._seen_version:
            # models came or went: rebuild every renderer's scene, but not while another
            # camera's worker is drawing with its (the update would free meshes in use)
            with _render_lock(self.ctx):
                self.ctx.refresh_renderers()
            self._seen_version = version
        self._renderer_get()
        if self.sync:
            self._produce(*job)
            return
        if self._executor is None:
            self._executor = concurrent.futures.ThreadPoolExecutor(
                max_workers=1, thread_name_prefix='ode_sim-camera-%s' % self.sensor.name)
        self._future = self._executor.submit(self._produce, *job)

    def wait(self, timeout=None):
        """Block until the frame in flight (if any) is published; re-raises its error."""
        fut = self._future
        if fut is not None:
            self._future = None
            fut.result(timeout)

    def _publish_infos(self, stamp, info, dinfo):
        cam = self.camera
        if info:
            self.info_pub.publish(camera_info_msg(cam.width, cam.height, self.K, self.P,
                                                  self.D, self.frame_id, stamp))
        if dinfo:
            self.depth_info_pub.publish(camera_info_msg(
                cam.width, cam.height, self.K, self.P, self.D, self.frame_id, stamp))

    def _produce(self, pose, stamp, want_image, want_info, want_depth, want_cloud, want_dinfo):
        cam = self.camera
        with _render_lock(self.ctx):
            rgb, depth = self._renderer.render(pose)
        data = cam.image_bytes(rgb)
        if want_image:
            self.image_pub.publish(image_msg(data, cam.width, cam.height, cam.encoding,
                                             cam.channels, cam.bytes, self.frame_id, stamp))
        if depth is not None and (want_depth or want_cloud):
            cut = cut_depth(depth, self.cutoff, self.cutoff_max)
            if want_cloud:
                self.cloud_pub.publish(point_cloud_msg(cut, data, cam.width, cam.height,
                                                       cam.hfov, self.frame_id, stamp))
            if want_depth:
                self.depth_pub.publish(depth_image_msg(cut, self.frame_id, stamp))
        self._publish_infos(stamp, want_info, want_dinfo)
        self.frames += 1

    # ---------------------------------------------------------------- lifecycle
    def reset(self):
        super().reset()
        self._last_pub = None

    def shutdown(self):
        try:
            self.wait(5.0)
        except Exception:  # noqa: BLE001 - shutting down anyway
            pass
        if self._executor is not None:
            self._executor.shutdown(wait=True)
            self._executor = None
        for pub in (self.image_pub, self.info_pub, self.depth_pub, self.depth_info_pub,
                    self.cloud_pub):
            if pub is not None:
                try:
                    pub.unregister()
                except Exception:  # noqa: BLE001
                    pass
        if self._renderer is not None:
            self._renderer.release()
            self._renderer = None


class OpenniKinectPlugin(CameraPlugin):
    """libgazebo_ros_openni_kinect.so"""
    depth_outputs = True
    cutoff_max_default = 5.0
    sensor_types = ('depth',)


class DepthCameraPlugin(CameraPlugin):
    """libgazebo_ros_depth_camera.so: as openni_kinect, without pointCloudCutoffMax."""
    depth_outputs = True
    cutoff_max_default = None
    sensor_types = ('depth',)


PLUGINS = {
    'libgazebo_ros_camera.so': CameraPlugin,
    'libgazebo_ros_openni_kinect.so': OpenniKinectPlugin,
    'libgazebo_ros_depth_camera.so': DepthCameraPlugin,
}
