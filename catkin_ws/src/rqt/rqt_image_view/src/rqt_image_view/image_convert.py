"""Image View conversions (no Qt, no ROS): sensor_msgs/Image fields -> an RGB array."""
import numpy as np

COLOR_SCHEMES = ['Gray', 'Autumn', 'Bone', 'Cool', 'Hot', 'Hsv', 'Jet', 'Ocean', 'Pink', 'Rainbow',
                 'Spring', 'Summer', 'Winter']


class ConversionError(Exception):
    pass


def _array(data, height, width, step, dtype, channels, bigendian=False):
    dt = np.dtype(dtype).newbyteorder('>' if bigendian else '<')
    row_items = step // dt.itemsize
    buf = np.frombuffer(bytes(data), dtype=dt)
    if buf.size < height * row_items:
        raise ConversionError('image data too short: %d bytes for %dx%d with step %d'
                              % (len(data), width, height, step))
    rows = buf[:height * row_items].reshape(height, row_items)
    return rows[:, :width * channels].reshape(height, width, channels) if channels > 1 \
        else rows[:, :width]


def depth_to_gray(depth, max_range=10.0, dynamic=False):
    """float depth (m) -> uint8 over [0, max_range], or over [min, max] when dynamic."""
    d = np.nan_to_num(depth.astype(np.float64), nan=0.0, posinf=0.0, neginf=0.0)
    lo, hi = 0.0, float(max_range)
    if dynamic:
        lo, hi = float(d.min()), float(d.max())
        if hi <= lo:
            lo, hi = 0.0, 2.0
    return np.clip((d - lo) / (hi - lo) * 255.0, 0, 255).astype(np.uint8)


def apply_scheme(gray, scheme):
    if scheme in (None, '', 'Gray'):
        return np.repeat(gray[:, :, None], 3, axis=2)
    import cv2
    code = getattr(cv2, 'COLORMAP_' + scheme.upper())
    return cv2.applyColorMap(gray, code)[:, :, ::-1].copy()


def image_to_rgb(encoding, height, width, step, data, bigendian=False, max_range=10.0,
                 dynamic=False, scheme='Gray'):
    enc = encoding.lower()
    if enc in ('rgb8', 'bgr8', '8uc3'):
        a = _array(data, height, width, step, np.uint8, 3)
        return a[:, :, ::-1].copy() if enc == 'bgr8' else a.copy()
    if enc in ('rgba8', 'bgra8', '8uc4'):
        a = _array(data, height, width, step, np.uint8, 4)[:, :, :3]
        return a[:, :, ::-1].copy() if enc == 'bgra8' else a.copy()
    if enc in ('mono8', '8uc1'):
        return apply_scheme(_array(data, height, width, step, np.uint8, 1), scheme)
    if enc == 'mono16':
        a = _array(data, height, width, step, np.uint16, 1, bigendian)
        return apply_scheme((a >> 8).astype(np.uint8), scheme)
    if enc == '16uc1':
        a = _array(data, height, width, step, np.uint16, 1, bigendian).astype(np.float64) / 1000.0
        return apply_scheme(depth_to_gray(a, max_range, dynamic), scheme)
    if enc == '32fc1':
        a = _array(data, height, width, step, np.float32, 1, bigendian)
        return apply_scheme(depth_to_gray(a, max_range, dynamic), scheme)
    raise ConversionError("could not convert image from '%s' to 'rgb8'" % encoding)


def decode_compressed(data):
    """JPEG/PNG bytes of a sensor_msgs/CompressedImage -> RGB array."""
    import cv2
    img = cv2.imdecode(np.frombuffer(bytes(data), np.uint8), cv2.IMREAD_COLOR)
    if img is None:
        raise ConversionError('could not decode the compressed image')
    return img[:, :, ::-1].copy()


def rotate(rgb, quarter_turns):
    """Rotate clockwise by 90 degrees times `quarter_turns` (0-3)."""
    return np.rot90(rgb, -int(quarter_turns) % 4).copy()


def click_to_image(x, y, width, height, quarter_turns):
    """Pixel in the original image of a click (x, y) on the image rotated by quarter_turns."""
    r = int(quarter_turns) % 4
    if r == 0:
        return x, y
    if r == 1:                      # displayed is rotated clockwise: (x, y) -> (y, H-1-x)
        return y, height - 1 - x
    if r == 2:
        return width - 1 - x, height - 1 - y
    return width - 1 - y, x


def topic_entries(topic_types):
    """Combo entries (display, (topic, transport)) from {topic: type}: raw images and compressed
    sub-topics shown as 'parent/transport'; sorted, empty entry first."""
    out = [('', ('', 'raw'))]
    for topic, t in sorted(topic_types.items()):
        if t == 'sensor_msgs/Image':
            out.append((topic, (topic, 'raw')))
        elif t == 'sensor_msgs/CompressedImage':
            parent, _, transport = topic.rpartition('/')
            out.append(('%s/%s' % (parent, transport), (parent, transport)))
    return [out[0]] + sorted(out[1:])
