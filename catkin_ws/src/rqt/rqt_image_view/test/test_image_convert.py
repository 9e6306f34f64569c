"""Image View conversions without a roscore."""
import numpy as np
import pytest

from rqt_image_view.image_convert import (ConversionError, click_to_image, depth_to_gray,
                                          image_to_rgb, rotate, topic_entries)


def test_rgb_bgr_and_row_padding():
    px = np.array([[[255, 0, 0], [0, 255, 0]]], np.uint8)           # 1x2 red, green
    data = px.tobytes() + b'\0\0'                                     # step 8: 2 bytes padding
    assert (image_to_rgb('rgb8', 1, 2, 8, data) == px).all()
    assert (image_to_rgb('bgr8', 1, 2, 8, data)[0, 0] == [0, 0, 255]).all()


def test_mono_and_depth():
    assert (image_to_rgb('mono8', 1, 1, 1, b'\x80')[0, 0] == [128, 128, 128]).all()
    depth = np.array([[0.0, 5.0, 10.0, 20.0]], np.float32)
    rgb = image_to_rgb('32FC1', 1, 4, 16, depth.tobytes())
    assert list(rgb[0, :, 0]) == [0, 127, 255, 255]
    mm = np.array([[0, 5000]], np.uint16)                              # 16UC1 in millimetres
    assert list(image_to_rgb('16UC1', 1, 2, 4, mm.tobytes())[0, :, 0]) == [0, 127]


def test_dynamic_range_and_uniform_image():
    d = np.array([[1.0, 2.0, 3.0]])
    assert list(depth_to_gray(d, dynamic=True)[0]) == [0, 127, 255]
    assert list(depth_to_gray(np.ones((1, 2)), dynamic=True)[0]) == [127, 127]


def test_colour_scheme_changes_gray():
    rgb = image_to_rgb('mono8', 1, 1, 1, b'\xff', scheme='Jet')
    assert not (rgb[0, 0, 0] == rgb[0, 0, 1] == rgb[0, 0, 2])


def test_unknown_encoding_and_short_data():
    with pytest.raises(ConversionError, match="could not convert image from 'yuv422' to 'rgb8'"):
        image_to_rgb('yuv422', 1, 1, 2, b'\0\0')
    with pytest.raises(ConversionError, match='too short'):
        image_to_rgb('rgb8', 2, 2, 6, b'\0' * 6)


def test_rotation_and_click_mapping():
    img = np.arange(6).reshape(2, 3)[:, :, None]
    r = rotate(img, 1)
    assert r.shape[:2] == (3, 2)
    for turns in range(4):
        rot = rotate(img, turns)
        h, w = rot.shape[:2]
        for y in range(h):
            for x in range(w):
                ox, oy = click_to_image(x, y, 3, 2, turns)
                assert img[oy, ox, 0] == rot[y, x, 0]


def test_topic_entries():
    e = topic_entries({'/cam/image_raw': 'sensor_msgs/Image',
                       '/cam/image_raw/compressed': 'sensor_msgs/CompressedImage',
                       '/scan': 'sensor_msgs/LaserScan'})
    assert [d for d, _ in e] == ['', '/cam/image_raw', '/cam/image_raw/compressed']
    assert e[2][1] == ('/cam/image_raw', 'compressed')
