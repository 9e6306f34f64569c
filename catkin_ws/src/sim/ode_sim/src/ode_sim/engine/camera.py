"""The maths of Gazebo classic's camera and depth camera sensors and of what gazebo_ros_camera /
gazebo_ros_openni_kinect make of their frames; no ROS (ode_sim.ros.convert builds the
messages, ode_sim.ros.plugins.camera wires them to topics).

`CameraModel(sensor)` holds a <sensor type="camera"> (or "depth", ...) description: image size,
horizontal field of view, clip planes, <image><format> and Gaussian pixel noise; bad values
raise ModelError naming the sensor; the noise is drawn from a generator seeded with 0 unless
one is given. `.image_bytes(rgb)` turns a rendered (h, w, 3) uint8 RGB frame into the bytes of
the published image (noise first, then the encoding).

Pinhole: f = width / (2 tan(hfov / 2)) pixels (`focal_length`); `camera_info_matrix` gives K
and P as gazebo_ros_camera_utils publishes them (cx, cy default to (width + 1) / 2,
(height + 1) / 2, Gazebo's long-standing default; P[0][3] = -f * hackBaseline).

Encodings (<image><format>): L8 mono8, L16 mono16, R8G8B8 rgb8, B8G8R8 bgr8, R16G16B16 rgb16,
BAYER_RGGB8/BGGR8/GBRG8/GRBG8 bayer_*8; any other format is published as bgr8 (the plugin logs
the original's ERROR). Mono is Rec. 601 luma; 16-bit channels are the 8-bit value * 257.

Depth: `cut_depth` makes pixels outside (cutoff, cutoff_max) NaN (cutoff_max None: no upper
cut, +inf stays). `cloud_points` packs an organized cloud as gazebo_ros_openni_kinect fills
it: fields x y z rgb (float32 at offsets 0 4 8 16, CLOUD_POINT_STEP 32 bytes a point), optical
frame (z forward, x right, y down): x = z (i - (w-1)/2) / f, y = z (j - (h-1)/2) / f; the rgb
field holds the image bytes in image order (3 or 1 bytes per pixel, else black).
"""
import math

import numpy as np

from ode_sim.description.model import ModelError

#: <image><format> -> (encoding, channels, bytes per channel)
ENCODINGS = {
    'L8': ('mono8', 1, 1),
    'L16': ('mono16', 1, 2),
    'R8G8B8': ('rgb8', 3, 1),
    'B8G8R8': ('bgr8', 3, 1),
    'R16G16B16': ('rgb16', 3, 2),
    'BAYER_RGGB8': ('bayer_rggb8', 1, 1),
    'BAYER_BGGR8': ('bayer_bggr8', 1, 1),
    'BAYER_GBRG8': ('bayer_gbrg8', 1, 1),
    'BAYER_GRBG8': ('bayer_grbg8', 1, 1),
}

# Bayer patterns: colour channel (0 R, 1 G, 2 B) at (row % 2, col % 2)
_BAYER = {
    'bayer_rggb8': ((0, 1), (1, 2)),
    'bayer_bggr8': ((2, 1), (1, 0)),
    'bayer_gbrg8': ((1, 2), (0, 1)),
    'bayer_grbg8': ((1, 0), (2, 1)),
}

#: (name, byte offset) of the cloud's FLOAT32 fields, and the bytes of one point
CLOUD_FIELDS = (('x', 0), ('y', 4), ('z', 8), ('rgb', 16))
CLOUD_POINT_STEP = 32


def focal_length(width, hfov):
    """Focal length in pixels for `width` pixels over the horizontal field of view `hfov`."""
    return width / (2.0 * math.tan(hfov / 2.0))


def camera_info_matrix(width, height, hfov, cx=None, cy=None, focal=None, hack_baseline=0.0):
    """(K 3x3, P 3x4) as gazebo_ros_camera_utils publishes them in sensor_msgs/CameraInfo.

    Defaults as the plugin's: focal (`focalLength` 0) = width / (2 tan(hfov/2)) for both axes,
    cx (`Cx`) = (width + 1) / 2, cy (`Cy`) = (height + 1) / 2, P[0,3] = -focal * hackBaseline.
    """
    f = focal_length(width, hfov) if not focal else float(focal)
    cx = (width + 1) / 2.0 if cx is None else float(cx)
    cy = (height + 1) / 2.0 if cy is None else float(cy)
    K = np.array([[f, 0.0, cx], [0.0, f, cy], [0.0, 0.0, 1.0]])
    P = np.array([[f, 0.0, cx, -f * hack_baseline], [0.0, f, cy, 0.0], [0.0, 0.0, 1.0, 0.0]])
    return K, P


def encoding_of(fmt):
    """(encoding, channels, bytes per channel, known) for a Gazebo image format name."""
    if fmt in ENCODINGS:
        return ENCODINGS[fmt] + (True,)
    return ('bgr8', 3, 1, False)


def convert_image(rgb, encoding):
    """An (h, w, 3) uint8 RGB array -> the bytes of an image in `encoding`."""
    if encoding == 'rgb8':
        return rgb.tobytes()
    if encoding == 'bgr8':
        return np.ascontiguousarray(rgb[:, :, ::-1]).tobytes()
    if encoding == 'rgb16':
        return (rgb.astype('<u2') * 257).tobytes()
    if encoding in ('mono8', 'mono16'):
        # Rec. 601 luma
        y = rgb.astype(np.float32) @ np.array([0.299, 0.587, 0.114], dtype=np.float32)
        if encoding == 'mono8':
            return np.clip(np.rint(y), 0, 255).astype(np.uint8).tobytes()
        return (np.clip(np.rint(y), 0, 255).astype('<u2') * 257).tobytes()
    if encoding in _BAYER:
        pat = _BAYER[encoding]
        out = np.empty(rgb.shape[:2], dtype=np.uint8)
        for r in (0, 1):
            for c in (0, 1):
                out[r::2, c::2] = rgb[r::2, c::2, pat[r][c]]
        return out.tobytes()
    raise ValueError('unknown encoding %r' % encoding)


def add_noise(rgb, mean, stddev, rng):
    """Gaussian pixel noise as Gazebo's camera noise (in [0, 1] colour units)."""
    if stddev <= 0 and mean == 0:
        return rgb
    n = rng.normal(mean * 255.0, stddev * 255.0, size=rgb.shape)
    return np.clip(rgb + n, 0, 255).astype(np.uint8)


def cut_depth(depth, cutoff, cutoff_max=None):
    """Depth (h, w) float32 with +inf for no return -> NaN outside (cutoff, cutoff_max)."""
    d = depth.astype(np.float32, copy=True)
    bad = ~(d > cutoff)
    if cutoff_max is not None:
        bad |= ~(d < cutoff_max)
    d[bad] = np.nan
    return d


def cloud_points(depth, image_bytes, width, height, hfov):
    """(the packed points of an organized cloud as bytes, is_dense) from `depth` (already cut:
    NaN = no point) and the published image bytes (see the module's docstring)."""
    f = focal_length(width, hfov)
    u = (np.arange(width, dtype=np.float64) - 0.5 * (width - 1)) / f
    v = (np.arange(height, dtype=np.float64) - 0.5 * (height - 1)) / f
    z = depth.astype(np.float64)
    with np.errstate(invalid='ignore'):
        x = z * u[None, :]
        y = z * v[:, None]
    nan = np.isnan(z)
    x[nan] = np.nan
    y[nan] = np.nan
    buf = np.zeros((height, width, CLOUD_POINT_STEP), dtype=np.uint8)
    xyz = np.stack([x, y, z], axis=-1).astype('<f4')
    buf[:, :, 0:12] = xyz.view(np.uint8).reshape(height, width, 12)
    if image_bytes is not None:
        img = np.frombuffer(image_bytes, dtype=np.uint8)
        if img.size == width * height * 3:
            buf[:, :, 16:19] = img.reshape(height, width, 3)
        elif img.size == width * height:
            buf[:, :, 16:19] = img.reshape(height, width, 1)
    return buf.tobytes(), not bool(nan.any())


def _num(params, key, default, cast=float):
    v = params.get(key, default)
    try:
        return cast(v)
    except (TypeError, ValueError):
        return None


class CameraModel:
    """A camera sensor's image: size, field of view, clip, encoding and pixel noise."""

    def __init__(self, sensor, rng=None):
        sp = sensor.params
        where = "sensor '%s'" % sensor.name
        self.width = _num(sp, 'width', 320, int)
        self.height = _num(sp, 'height', 240, int)
        self.hfov = _num(sp, 'horizontal_fov', 1.047)
        self.near = _num(sp, 'near', 0.1)
        self.far = _num(sp, 'far', 100.0)
        for name, v in (('width', self.width), ('height', self.height)):
            if v is None or v <= 0:
                raise ModelError('%s: <image><%s> must be a positive integer, got %r'
                                 % (where, name, sp.get(name)))
        if self.hfov is None or not 0 < self.hfov < math.pi:
            raise ModelError('%s: <horizontal_fov> must be in (0, pi) rad for a pinhole camera, '
                             'got %r' % (where, sp.get('horizontal_fov')))
        if self.near is None or self.far is None or not 0 < self.near < self.far:
            raise ModelError('%s: <clip> needs 0 < near < far, got near %r far %r'
                             % (where, sp.get('near'), sp.get('far')))
        self.format = str(sp.get('format', 'R8G8B8') or 'R8G8B8').strip()
        self.encoding, self.channels, self.bytes, self.known_format = encoding_of(self.format)
        self.noise_mean = _num(sp, 'noise_mean', 0.0) or 0.0
        self.noise_stddev = _num(sp, 'noise_stddev', 0.0) or 0.0
        # seeded as the other sensors' noise (laser, imu, gps): runs repeat exactly
        self.rng = rng if rng is not None else np.random.default_rng(0)

    @property
    def focal(self):
        """The computed focal length in pixels."""
        return focal_length(self.width, self.hfov)

    def image_bytes(self, rgb):
        """A rendered (h, w, 3) uint8 RGB frame -> the published image's bytes."""
        if self.noise_stddev > 0 or self.noise_mean != 0:
            rgb = add_noise(rgb, self.noise_mean, self.noise_stddev, self.rng)
        return convert_image(rgb, self.encoding)
