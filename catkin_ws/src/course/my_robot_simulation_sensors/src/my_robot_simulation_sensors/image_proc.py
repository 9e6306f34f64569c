"""Camera image processing of sensor_data_proc.py, without ROS: a sensor_msgs/Image becomes an
OpenCV BGR array (cv_bridge), Canny finds its edges, `stats` summarises both.

    bridge = CvBridge()
    frame = to_bgr(bridge, msg)              # numpy uint8 (h, w, 3), BGR
    edges = canny(frame, 100, 200)           # numpy uint8 (h, w), 0 or 255
    s = stats(frame, edges)                  # {'width', 'height', 'mean', 'edge_fraction'}
"""
import cv2
import numpy as np

# encodings a camera plugin may publish, and how to turn each into BGR
_TO_BGR = {
    'bgr8': None,
    'rgb8': cv2.COLOR_RGB2BGR,
    'mono8': cv2.COLOR_GRAY2BGR,
    'bgra8': cv2.COLOR_BGRA2BGR,
    'rgba8': cv2.COLOR_RGBA2BGR,
}


class ImageError(ValueError):
    """An image that cannot be processed: the message is one line saying why."""


def to_bgr(bridge, msg):
    """sensor_msgs/Image -> numpy uint8 array (h, w, 3) in OpenCV's BGR order."""
    enc = msg.encoding.lower()
    if enc not in _TO_BGR:
        raise ImageError('image encoding %r is not supported (use one of %s)'
                         % (msg.encoding, ', '.join(sorted(_TO_BGR))))
    if msg.width == 0 or msg.height == 0:
        raise ImageError('empty image (%dx%d)' % (msg.width, msg.height))
    try:
        frame = bridge.imgmsg_to_cv2(msg, desired_encoding='passthrough')
    except Exception as e:    # cv_bridge raises CvBridgeError/TypeError on inconsistent sizes
        raise ImageError('cannot convert the %dx%d %s image: %s'
                         % (msg.width, msg.height, msg.encoding, str(e).splitlines()[0]))
    code = _TO_BGR[enc]
    return np.ascontiguousarray(frame if code is None else cv2.cvtColor(frame, code))


def canny(frame, low=100, high=200, blur=3):
    """Canny edges of a BGR (or grey) frame: uint8 (h, w), 255 on edges. `blur` is the size of
    a Gaussian pre-filter (0 or 1 = none) that keeps noise out of the edges."""
    if not 0 <= low <= high:
        raise ImageError('Canny thresholds must satisfy 0 <= low <= high (got %s, %s)' % (low, high))
    grey = frame if frame.ndim == 2 else cv2.cvtColor(frame, cv2.COLOR_BGR2GRAY)
    if blur and blur > 1:
        k = int(blur) | 1
        grey = cv2.GaussianBlur(grey, (k, k), 0)
    return cv2.Canny(grey, low, high)


def stats(frame, edges):
    """Summary of a frame and its edges: size, mean brightness (0-255), share of edge pixels."""
    h, w = frame.shape[:2]
    return {'width': int(w), 'height': int(h), 'mean': float(frame.mean()),
            'edge_fraction': float(np.count_nonzero(edges)) / float(h * w)}
