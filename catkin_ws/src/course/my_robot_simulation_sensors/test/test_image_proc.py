"""Camera processing of sensor_data_proc.py without a roscore: cv_bridge conversion of the
encodings a camera publishes, Canny edges of a synthetic scene, clear errors."""
import numpy as np
import pytest
from cv_bridge import CvBridge
from sensor_msgs.msg import Image

from my_robot_simulation_sensors import image_proc as ip


def scene(h=120, w=160):
    """Black frame with a white rectangle (BGR) whose border is at known places."""
    f = np.zeros((h, w, 3), np.uint8)
    f[30:90, 40:120] = (255, 255, 255)
    f[30:90, 40:60] = (0, 0, 255)          # a red strip on its left: BGR order matters
    return f


@pytest.fixture
def bridge():
    return CvBridge()


@pytest.mark.parametrize('encoding', ['bgr8', 'rgb8', 'mono8', 'rgba8'])
def test_to_bgr_from_every_camera_encoding(bridge, encoding):
    bgr = scene()
    if encoding == 'bgr8':
        raw = bgr
    elif encoding == 'rgb8':
        raw = bgr[:, :, ::-1].copy()
    elif encoding == 'mono8':
        raw = bgr[:, :, 1].copy()
    else:
        raw = np.dstack([bgr[:, :, ::-1], np.full(bgr.shape[:2], 255, np.uint8)])
    msg = bridge.cv2_to_imgmsg(raw, encoding=encoding)
    out = ip.to_bgr(bridge, msg)
    assert out.shape == (120, 160, 3) and out.dtype == np.uint8
    if encoding != 'mono8':
        assert tuple(out[50, 45]) == (0, 0, 255)       # red stays red
        assert tuple(out[50, 100]) == (255, 255, 255)
    assert tuple(out[5, 5]) == (0, 0, 0)


def test_canny_finds_the_rectangle_border(bridge):
    frame = scene()
    edges = ip.canny(frame, 100, 200)
    assert edges.shape == frame.shape[:2] and set(np.unique(edges)) <= {0, 255}
    rows, cols = np.nonzero(edges)
    assert 27 <= rows.min() <= 31 and 88 <= rows.max() <= 92
    assert 37 <= cols.min() <= 41 and 118 <= cols.max() <= 122
    assert edges[60, 80] == 0 and edges[5, 5] == 0      # inside and outside are flat
    s = ip.stats(frame, edges)
    assert (s['width'], s['height']) == (160, 120) and 0.01 < s['edge_fraction'] < 0.2


def test_flat_image_has_no_edges():
    frame = np.full((40, 60, 3), 128, np.uint8)
    assert ip.stats(frame, ip.canny(frame))['edge_fraction'] == 0.0


def test_edges_round_trip_as_mono8(bridge):
    edges = ip.canny(scene())
    msg = bridge.cv2_to_imgmsg(edges, encoding='mono8')
    assert (msg.width, msg.height, msg.encoding, msg.step) == (160, 120, 'mono8', 160)


@pytest.mark.parametrize('make,text', [
    (lambda: Image(width=4, height=2, encoding='32FC1', step=16, data=bytes(32)), "encoding '32FC1'"),
    (lambda: Image(width=0, height=0, encoding='rgb8', step=0, data=b''), 'empty image'),
    (lambda: Image(width=4, height=4, encoding='rgb8', step=12, data=bytes(10)), 'cannot convert'),
])
def test_bad_images_give_one_line(bridge, make, text):
    with pytest.raises(ip.ImageError) as e:
        ip.to_bgr(bridge, make())
    assert text in str(e.value) and '\n' not in str(e.value)


def test_bad_thresholds():
    with pytest.raises(ip.ImageError):
        ip.canny(scene(), 200, 100)
