"""engine/camera.py without ROS and without a renderer: the sensor's checks, the encodings,
the noise, the depth cut and the organized cloud's geometry and colours."""
import math
import struct
import subprocess
import sys

import numpy as np
import pytest

from ode_sim.description.model import ModelError, Sensor
from ode_sim.engine.camera import (CLOUD_POINT_STEP, CameraModel, camera_info_matrix,
                                   cloud_points, convert_image, cut_depth, encoding_of)


def sensor(**params):
    s = Sensor(name='cam', type='camera', link='link')
    s.params.update(params)
    return s


def test_imports_no_ros():
    code = ('import sys, ode_sim.engine.camera\n'
            'print(sorted(m for m in sys.modules if m.split(".")[0] in '
            '("rospy", "sensor_msgs", "genpy")))')
    out = subprocess.run([sys.executable, '-c', code], capture_output=True, text=True,
                         timeout=120)
    assert out.returncode == 0, out.stderr
    assert out.stdout.strip() == '[]'


def test_defaults_and_focal_length():
    c = CameraModel(sensor())
    assert (c.width, c.height, c.encoding, c.channels, c.bytes) == (320, 240, 'rgb8', 3, 1)
    assert c.focal == pytest.approx(320 / (2 * math.tan(1.047 / 2)))
    K, P = camera_info_matrix(320, 240, 1.047)
    assert K[0, 2] == pytest.approx(160.5) and K[1, 2] == pytest.approx(120.5)
    assert P[0, 3] == 0.0


@pytest.mark.parametrize('params, match', [
    ({'width': 0}, r"sensor 'cam': <image><width> must be a positive integer"),
    ({'height': 'x'}, r'<image><height> must be a positive integer'),
    ({'horizontal_fov': 3.2}, r'<horizontal_fov> must be in \(0, pi\)'),
    ({'near': 2.0, 'far': 1.0}, r'<clip> needs 0 < near < far'),
])
def test_bad_values_name_the_sensor(params, match):
    with pytest.raises(ModelError, match=match):
        CameraModel(sensor(**params))


def test_unknown_format_is_bgr8():
    assert encoding_of('RGB_INT8') == ('bgr8', 3, 1, False)
    c = CameraModel(sensor(format='RGB_INT8'))
    assert not c.known_format and c.encoding == 'bgr8'


def test_encodings_of_one_pixel():
    rgb = np.array([[[200, 100, 50], [0, 0, 0]], [[10, 20, 30], [255, 255, 255]]], np.uint8)
    assert convert_image(rgb, 'rgb8')[:3] == bytes([200, 100, 50])
    assert convert_image(rgb, 'bgr8')[:3] == bytes([50, 100, 200])
    assert convert_image(rgb, 'rgb16')[:2] == struct.pack('<H', 200 * 257)
    assert convert_image(rgb, 'mono8')[0] == round(0.299 * 200 + 0.587 * 100 + 0.114 * 50)
    # RGGB: R at (0, 0), G at (0, 1) and (1, 0), B at (1, 1)
    assert convert_image(rgb, 'bayer_rggb8') == bytes([200, 0, 20, 255])
    with pytest.raises(ValueError):
        convert_image(rgb, 'yuv422')


def test_noise_is_seeded_and_clipped():
    rgb = np.full((4, 4, 3), 128, np.uint8)
    a = CameraModel(sensor(noise_stddev=0.05), rng=np.random.default_rng(3)).image_bytes(rgb)
    b = CameraModel(sensor(noise_stddev=0.05), rng=np.random.default_rng(3)).image_bytes(rgb)
    assert a == b and a != rgb.tobytes()
    assert CameraModel(sensor()).image_bytes(rgb) == rgb.tobytes()
    # without a generator given: seeded, the same frames run after run
    c, d = CameraModel(sensor(noise_stddev=0.05)), CameraModel(sensor(noise_stddev=0.05))
    assert c.image_bytes(rgb) == d.image_bytes(rgb) != rgb.tobytes()


def test_depth_cut_and_cloud():
    w, h, hfov = 4, 2, math.pi / 2            # f = 2 px
    depth = np.array([[0.3, 1.0, 2.0, np.inf], [1.0, 1.0, 6.0, 1.0]], np.float32)
    cut = cut_depth(depth, 0.4, 5.0)
    assert np.isnan(cut[0, 0]) and np.isnan(cut[0, 3]) and np.isnan(cut[1, 2])
    assert np.isposinf(cut_depth(depth, 0.4)[0, 3])           # no upper cutoff: inf stays
    image = bytes(range(w * h * 3))
    data, dense = cloud_points(cut, image, w, h, hfov)
    assert not dense and len(data) == w * h * CLOUD_POINT_STEP
    pts = np.frombuffer(data, np.uint8).reshape(h, w, CLOUD_POINT_STEP)
    x, y, z = struct.unpack('<3f', pts[0, 1, 0:12].tobytes())
    # pixel (i 1, j 0): x = z (1 - 1.5) / 2, y = z (0 - 0.5) / 2
    assert (x, y, z) == pytest.approx((-0.25, -0.25, 1.0))
    assert bytes(pts[0, 1, 16:19]) == image[3:6]
    assert all(math.isnan(v) for v in struct.unpack('<3f', pts[0, 0, 0:12].tobytes()))
    _, dense = cloud_points(np.ones((h, w), np.float32), None, w, h, hfov)
    assert dense
