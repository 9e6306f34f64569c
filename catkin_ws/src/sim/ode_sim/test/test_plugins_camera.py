"""libgazebo_ros_camera.so, libgazebo_ros_openni_kinect.so, libgazebo_ros_depth_camera.so on a
hand-built scene (no roscore, fake publishers, real offscreen rendering), and one run against a
real roscore with rospy subscribers."""
import json
import math
import os
import subprocess
import sys

import numpy as np
import pytest
import rospy

from ode_sim.ros import plugins
from ode_sim.description.model import (Collision, Geometry, Inertial, Light, Link, Model, ModelError,
                                       Physics, Plugin as PluginDesc, Sensor, Visual, World)
from ode_sim.engine.physics import PhysicsWorld
from ode_sim.ros.plugins import camera as camera_plugin
from ode_sim.ros.plugins.base import PluginContext
from ode_sim.ros.plugins.rosio import MemoryPublisher, RosIO
from ode_sim.description.transforms import Pose

W, H = 64, 48
HFOV = 1.047
F = W / (2 * math.tan(HFOV / 2))
D = 3.0                 # distance from the camera to the red box's front face
HALF = 0.5              # the box is 1 m: its face spans +-0.5 m around the optical axis
CAM_Z = 0.5


@pytest.fixture(autouse=True)
def fake_publishers(monkeypatch):
    # no rospy node here: plugins get MemoryPublishers; nobody subscribes until a test says so
    monkeypatch.setattr(MemoryPublisher, 'DEFAULT_CONNECTIONS', 0)


def scene_models():
    red = Geometry('box', size=(1, 1, 1))
    box = Model('red_box', static=True, pose=Pose((D + HALF, 0, CAM_Z)), links=[Link(
        'link', collisions=[Collision('c', red)], visuals=[Visual('v', red, color=(1, 0, 0, 1))])])
    return [box]


def camera_robot(kind='camera', plugin='libgazebo_ros_camera.so', tags=None, fmt='R8G8B8',
                 update_rate=30.0, **sp):
    params = {'horizontal_fov': HFOV, 'width': W, 'height': H, 'format': fmt, 'near': 0.1,
              'far': 100.0, 'noise_mean': 0.0, 'noise_stddev': 0.0}
    params.update(sp)
    sensor = Sensor('cam', kind, 'base_link', pose=Pose((0.1, 0, 0.2)), update_rate=update_rate,
                    params=params)
    t = {'cameraName': 'cam1', 'frameName': 'camera_optical'} if tags is None else tags
    desc = PluginDesc('camera_controller', plugin, dict(t))
    sensor.plugins.append(desc)
    link = Link('base_link', inertial=Inertial(1.0, ixx=0.01, iyy=0.01, izz=0.01),
                gravity=False, sensors=[sensor])
    # the sensor ends up at (0, 0, CAM_Z): the link sits 0.1 m behind and 0.2 m below it
    return Model('bot', pose=Pose((-0.1, 0, CAM_Z - 0.2)), links=[link]), sensor, desc


def setup(**kw):
    io = kw.pop('io', None)     # not a parameter: pytest would take setup(x) for a module hook
    pw = PhysicsWorld(Physics())
    for m in scene_models():
        pw.add_model(m)
    desc, sensor, pdesc = camera_robot(**kw)
    m = pw.add_model(desc)
    world = World(lights=[Light('sun', direction=(1.0, 0.0, 0.0))])
    ctx = PluginContext(pw, world, io=io)
    p = plugins.lookup(pdesc.filename)(ctx, m, pdesc, sensor)
    return pw, ctx, p


@pytest.fixture
def release():
    made = []
    yield made.append
    for p in made:
        p.shutdown()


def box_pixels():
    """(columns, rows) strictly inside and strictly outside the box's image by the pinhole
    model with Gazebo's principal point at the image centre ((n - 1) / 2 in pixel indices)."""
    half_px = HALF / D * F
    cols = np.arange(W) - (W - 1) / 2
    rows = np.arange(H) - (H - 1) / 2
    inside = (np.abs(rows)[:, None] < half_px - 1) & (np.abs(cols)[None, :] < half_px - 1)
    outside = (np.abs(rows)[:, None] > half_px + 1) | (np.abs(cols)[None, :] > half_px + 1)
    return inside, outside


def image_array(msg):
    ch = {'rgb8': 3, 'bgr8': 3, 'mono8': 1}[msg.encoding]
    return np.frombuffer(msg.data, dtype=np.uint8).reshape(msg.height, msg.width, ch)


def one_frame(p, pw, subscribe=('image_pub',)):
    for name in subscribe:
        getattr(p, name).connections = 1
    pw.step(1)
    p.update()
    p.wait(10)


def test_registry():
    assert plugins.lookup('libgazebo_ros_camera.so') is camera_plugin.CameraPlugin
    assert plugins.lookup('libgazebo_ros_openni_kinect.so') is camera_plugin.OpenniKinectPlugin
    assert plugins.lookup('libgazebo_ros_depth_camera.so') is camera_plugin.DepthCameraPlugin


def test_red_box_fills_the_pinhole_pixels(release):
    pw, ctx, p = setup()
    release(p)
    one_frame(p, pw)
    msg = p.image_pub.sent[-1]
    assert (msg.width, msg.height, msg.encoding, msg.step) == (W, H, 'rgb8', 3 * W)
    assert msg.header.frame_id == 'camera_optical'
    img = image_array(msg).astype(int)
    inside, outside = box_pixels()
    red = (img[:, :, 0] > 150) & (img[:, :, 1] < 60) & (img[:, :, 2] < 60)
    assert red[inside].all()
    assert not red[outside].any()
    assert inside.sum() > 200


def test_topics_and_camera_info_as_gazebo_defaults(release):
    pw, ctx, p = setup()
    release(p)
    assert p.image_pub.name == '/cam1/image_raw' and p.image_pub.queue_size == 2
    assert p.info_pub.name == '/cam1/camera_info'
    one_frame(p, pw, ('image_pub', 'info_pub'))
    info = p.info_pub.sent[-1]
    img = p.image_pub.sent[-1]
    assert info.header.stamp == img.header.stamp
    assert info.header.frame_id == 'camera_optical'
    assert (info.width, info.height) == (W, H)
    assert info.distortion_model == 'plumb_bob' and list(info.D) == [0.0] * 5
    assert list(info.K) == pytest.approx([F, 0, (W + 1) / 2, 0, F, (H + 1) / 2, 0, 0, 1])
    assert list(info.P) == pytest.approx([F, 0, (W + 1) / 2, 0, 0, F, (H + 1) / 2, 0, 0, 0, 1, 0])
    assert list(info.R) == [1, 0, 0, 0, 1, 0, 0, 0, 1]


def test_models_spawned_later_show_up(release):
    pw, ctx, p = setup(update_rate=0.0)
    release(p)
    one_frame(p, pw)
    g = Geometry('box', size=(0.3, 0.3, 0.3))
    pw.add_model(Model('green', static=True, pose=Pose((1.5, 0, CAM_Z)), links=[Link(
        'link', visuals=[Visual('v', g, color=(0, 1, 0, 1))])]))
    one_frame(p, pw)
    before, after = (image_array(m)[H // 2, W // 2] for m in p.image_pub.sent[-2:])
    assert before[0] > 150 and before[1] < 60
    assert after[1] > 150 and after[0] < 60
    pw.remove_model('green')
    one_frame(p, pw)
    assert image_array(p.image_pub.sent[-1])[H // 2, W // 2][0] > 150


def test_image_orientation_left_is_plus_y_up_is_plus_z(release):
    pw, ctx, p = setup(update_rate=0.0)
    release(p)
    g = Geometry('box', size=(0.2, 0.2, 0.2))
    # green: left of the axis (+Y in the camera frame); blue: above it (+Z)
    for name, xyz, color in (('g', (2.0, 0.6, CAM_Z), (0, 1, 0, 1)),
                             ('b', (2.0, 0, CAM_Z + 0.6), (0, 0, 1, 1))):
        pw.add_model(Model(name, static=True, pose=Pose(xyz), links=[Link(
            'link', visuals=[Visual('v', g, color=color)])]))
    one_frame(p, pw)
    img = image_array(p.image_pub.sent[-1]).astype(int)
    green = (img[:, :, 1] > 150) & (img[:, :, 0] < 60)
    blue = (img[:, :, 2] > 150) & (img[:, :, 0] < 60)
    rows, cols = np.nonzero(green)
    assert green.sum() > 4 and cols.max() < W / 2 and abs(rows.mean() - (H - 1) / 2) < 2
    rows, cols = np.nonzero(blue)
    assert blue.sum() > 4 and rows.max() < H / 2 and abs(cols.mean() - (W - 1) / 2) < 2


def test_camera_info_tags():
    pw, ctx, p = setup(tags={'cameraName': 'c', 'Cx': '30', 'Cy': '20', 'focalLength': '50',
                             'hackBaseline': '0.07', 'distortionK1': '0.1',
                             'distortionT2': '0.02', 'distortionK3': '0.3',
                             'imageTopicName': 'rgb/image', 'cameraInfoTopicName': '/abs/info',
                             'robotNamespace': 'ns1', 'frameName': 'cam_frame'})
    p.info_pub.connections = 1
    p.update()                               # camera_info alone: published without a render
    assert p._renderer is None and p.frames == 0
    info = p.info_pub.sent[-1]
    assert list(info.K) == pytest.approx([50, 0, 30, 0, 50, 20, 0, 0, 1])
    assert info.P[3] == pytest.approx(-50 * 0.07)
    assert list(info.D) == pytest.approx([0.1, 0, 0, 0.02, 0.3])
    assert p.image_pub.name == '/ns1/c/rgb/image'
    assert p.info_pub.name == '/abs/info'
    assert info.header.frame_id == 'ns1/cam_frame'


def test_no_subscriber_no_render_and_update_rate(release):
    pw, ctx, p = setup(update_rate=10.0)
    release(p)
    for _ in range(200):
        pw.step(1)
        p.update()
    assert p._renderer is None and p.image_pub.sent == []
    p.image_pub.connections = 1
    for _ in range(1000):
        pw.step(1)
        p.update()
        p.wait(10)
    stamps = [m.header.stamp.to_sec() for m in p.image_pub.sent]
    assert len(stamps) == 10
    assert np.diff(stamps) == pytest.approx([0.1] * 9, abs=1.5e-3)


def test_plugin_update_rate_throttles_below_the_sensor_rate(release):
    pw, ctx, p = setup(update_rate=50.0, tags={'cameraName': 'c', 'updateRate': '10'})
    release(p)
    p.image_pub.connections = 1
    for _ in range(1000):
        pw.step(1)
        p.update()
        p.wait(10)
    assert len(p.image_pub.sent) == 10


def test_encodings(release):
    for fmt, enc, ch in (('B8G8R8', 'bgr8', 3), ('L8', 'mono8', 1), ('R16G16B16', 'rgb16', 6),
                         ('BAYER_RGGB8', 'bayer_rggb8', 1), ('NOPE', 'bgr8', 3)):
        pw, ctx, p = setup(fmt=fmt)
        release(p)
        one_frame(p, pw)
        msg = p.image_pub.sent[-1]
        assert msg.encoding == enc and msg.step == ch * W and len(msg.data) == ch * W * H
        if enc == 'bgr8':
            img = image_array(msg)
            assert img[H // 2, W // 2, 2] > 150 and img[H // 2, W // 2, 0] < 60   # red in bgr
        if enc == 'bayer_rggb8':
            b = np.frombuffer(msg.data, np.uint8).reshape(H, W)
            assert b[H // 2, W // 2] > 150          # an R site (even row, even column)
            assert b[H // 2, W // 2 + 1] < 60        # a G site


def test_image_noise(release):
    pw, ctx, p = setup(noise_stddev=0.02)
    release(p)
    p.rng = np.random.default_rng(1)
    one_frame(p, pw)
    img = image_array(p.image_pub.sent[-1]).astype(float)
    assert img[:5, :, 1].std() > 2


def kinect(**kw):
    kw.setdefault('kind', 'depth')
    kw.setdefault('plugin', 'libgazebo_ros_openni_kinect.so')
    return setup(**kw)


def test_kinect_depth_image_and_topics(release):
    pw, ctx, p = kinect()
    release(p)
    assert p.depth_pub.name == '/cam1/depth/image_raw'
    assert p.depth_info_pub.name == '/cam1/depth/camera_info'
    assert p.cloud_pub.name == '/cam1/points'
    assert p.image_pub.name == '/cam1/image_raw'
    one_frame(p, pw, ('depth_pub', 'depth_info_pub'))
    msg = p.depth_pub.sent[-1]
    assert msg.encoding == '32FC1' and msg.step == 4 * W and msg.is_bigendian == 0
    assert msg.header.frame_id == 'camera_optical'
    d = np.frombuffer(msg.data, dtype='<f4').reshape(H, W)
    inside, outside = box_pixels()
    assert d[inside] == pytest.approx(D, rel=0.02)
    assert np.isnan(d[outside]).all()               # nothing hit: NaN, as the original
    assert p.depth_info_pub.sent and p.image_pub.sent == []
    assert p.depth_info_pub.sent[-1].header.stamp == msg.header.stamp


def test_kinect_cutoffs(release):
    pw, ctx, p = kinect(tags={'cameraName': 'k', 'pointCloudCutoffMax': '2.5'})
    release(p)
    one_frame(p, pw, ('depth_pub',))
    d = np.frombuffer(p.depth_pub.sent[-1].data, dtype='<f4')
    assert np.isnan(d).all()                         # the box at 3 m is beyond 2.5 m
    pw, ctx, p = kinect(tags={'cameraName': 'k', 'pointCloudCutoff': '3.5'})
    release(p)
    one_frame(p, pw, ('depth_pub',))
    assert np.isnan(np.frombuffer(p.depth_pub.sent[-1].data, dtype='<f4')).all()


def test_kinect_point_cloud(release):
    pw, ctx, p = kinect()
    release(p)
    one_frame(p, pw, ('cloud_pub',))
    msg = p.cloud_pub.sent[-1]
    assert (msg.height, msg.width, msg.point_step, msg.row_step) == (H, W, 32, 32 * W)
    assert [(f.name, f.offset, f.datatype, f.count) for f in msg.fields] == [
        ('x', 0, 7, 1), ('y', 4, 7, 1), ('z', 8, 7, 1), ('rgb', 16, 7, 1)]
    assert msg.header.frame_id == 'camera_optical'
    assert not msg.is_dense                          # the background has no points
    raw = np.frombuffer(msg.data, dtype=np.uint8).reshape(H, W, 32)
    xyz = raw[:, :, :12].copy().view('<f4').reshape(H, W, 3)
    j, i = H // 2, W // 2
    x, y, z = xyz[j, i]
    assert z == pytest.approx(D, rel=0.02)
    assert abs(x) < 0.05 and abs(y) < 0.05
    # optical frame: x right, y down. A pixel to the right and below has x > 0, y > 0
    assert xyz[j + 5, i + 5, 0] > 0.1 and xyz[j + 5, i + 5, 1] > 0.1
    assert xyz[j - 5, i - 5, 0] < -0.1 and xyz[j - 5, i - 5, 1] < -0.1
    assert xyz[j + 5, i + 5, 0] == pytest.approx(z * (i + 5 - (W - 1) / 2) / F, rel=0.03)
    assert np.isnan(xyz[0, 0]).all()
    # rgb bytes in image order (R first), as the original writes them
    assert raw[j, i, 16] > 150 and raw[j, i, 17] < 60 and raw[j, i, 18] < 60
    # the cloud needs the image: it is rendered (published only to image subscribers)
    assert p.image_pub.sent == []


def test_depth_camera_has_no_upper_cutoff(release):
    pw, ctx, p = kinect(plugin='libgazebo_ros_depth_camera.so',
                        tags={'cameraName': 'd', 'pointCloudCutoffMax': '2.5'})
    release(p)
    one_frame(p, pw, ('depth_pub',))
    d = np.frombuffer(p.depth_pub.sent[-1].data, dtype='<f4').reshape(H, W)
    inside, outside = box_pixels()
    assert d[inside] == pytest.approx(D, rel=0.02)
    assert np.isposinf(d[outside]).all()


def test_bad_sensor_errors():
    with pytest.raises(ModelError, match='openni_kinect.*sensor type="depth"'):
        setup(plugin='libgazebo_ros_openni_kinect.so')
    with pytest.raises(ModelError, match='horizontal_fov'):
        setup(horizontal_fov=3.5)
    with pytest.raises(ModelError, match='near < far'):
        setup(near=5.0, far=1.0)


def test_shutdown_unregisters_and_releases(release):
    pw, ctx, p = kinect()
    one_frame(p, pw, ('cloud_pub',))
    p.shutdown()
    assert p.image_pub.unregistered and p.cloud_pub.unregistered
    assert p._renderer is None


# ------------------------------------------------------------------ real roscore
def _integration_main():
    import time
    from sensor_msgs.msg import CameraInfo, Image, PointCloud2
    rospy.init_node('camera_plugin_check', disable_signals=True)
    pw, ctx, p = kinect(update_rate=20.0, io=RosIO())
    got = {'image': [], 'info': [], 'depth': [], 'points': []}
    subs = [rospy.Subscriber('/cam1/image_raw', Image, got['image'].append),
            rospy.Subscriber('/cam1/camera_info', CameraInfo, got['info'].append),
            rospy.Subscriber('/cam1/depth/image_raw', Image, got['depth'].append),
            rospy.Subscriber('/cam1/points', PointCloud2, got['points'].append)]
    deadline = time.time() + 20
    while not all(pub.get_num_connections() for pub in
                  (p.image_pub, p.info_pub, p.depth_pub, p.cloud_pub)) and time.time() < deadline:
        time.sleep(0.02)
    while min(len(v) for v in got.values()) < 3 and time.time() < deadline:
        pw.step(5)
        p.update()
        time.sleep(0.005)
    p.shutdown()
    for s in subs:
        s.unregister()
    img = got['image'][0] if got['image'] else None
    centre = list(img.data[(H // 2 * W + W // 2) * 3:(H // 2 * W + W // 2) * 3 + 3]) if img else []
    depth = (float(np.frombuffer(got['depth'][0].data, '<f4').reshape(H, W)[H // 2, W // 2])
             if got['depth'] else None)
    print(json.dumps({k: len(v) for k, v in got.items()} | {
        'centre': centre, 'depth': depth,
        'frame': img.header.frame_id if img else '',
        'stamps': [m.header.stamp.to_sec() for m in got['image']]}))


def test_real_roscore_subscribers_receive_all_topics(roscore):
    out = subprocess.run([sys.executable, os.path.abspath(__file__), 'integration'],
                         env=roscore.env, capture_output=True, text=True, timeout=90)
    assert out.returncode == 0, out.stderr[-3000:]
    res = json.loads(out.stdout.strip().splitlines()[-1])
    assert min(res['image'], res['info'], res['depth'], res['points']) >= 3, res
    assert res['frame'] == 'camera_optical'
    assert res['centre'][0] > 150 and res['centre'][1] < 60
    assert res['depth'] == pytest.approx(D, rel=0.02)
    assert np.diff(res['stamps']) == pytest.approx([0.05] * (len(res['stamps']) - 1), abs=0.006)


if __name__ == '__main__' and sys.argv[1:] == ['integration']:
    _integration_main()
