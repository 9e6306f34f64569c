"""The accelerometer's ellipsoid calibration of the diploma (section 3.2, formulas 3-4):
the measurement model M ~ A m + b (A: scale factors and cross-axis sensitivity, b: offsets),
inverted as m = A^-1 (M - b). At rest every true acceleration m is gravity, |m| = g, so the
measurements M of a sensor turned through many orientations lie on the ellipsoid
|A^-1 (M - b)| = g; a least-squares fit of that ellipsoid gives b and A.

Only A A^T is observable from magnitudes (a rotation of the sensor axes leaves |m| unchanged),
so A is taken symmetric, as the diploma's fitting method does.

The firmware (firmware/sketches/space_scanner_base) applies the result from its
accel_calibration.h: ACCEL_CAL_MATRIX = A^-1, ACCEL_CAL_OFFSET = b (m/s^2), to
imu/data_raw's linear_acceleration (the raw reading in m/s^2 at +-2 g).
"""
import math
import re

import numpy as np

G = 9.80665
MIN_SAMPLES = 9          # nine unknowns of the general ellipsoid


class CalibrationError(Exception):
    """Bad input or data that does not determine an ellipsoid: one line saying which."""


def as_samples(samples):
    a = np.asarray(samples, dtype=float)
    if a.ndim != 2 or a.shape[1] != 3:
        raise CalibrationError('samples must be N x 3 accelerations (got shape %s)' % (a.shape,))
    if not np.all(np.isfinite(a)):
        raise CalibrationError('samples contain NaN or infinite values')
    if len(a) < MIN_SAMPLES:
        raise CalibrationError('need at least %d samples to fit an ellipsoid, got %d' % (MIN_SAMPLES, len(a)))
    return a


def fit_ellipsoid(samples, g=G):
    """(A, b): symmetric A and offset b with |A^-1 (M - b)| = g for the samples M (N x 3) in the
    least-squares sense (algebraic fit of x'Qx + p'x = 1)."""
    if not g > 0:
        raise CalibrationError('gravity must be positive, got %r' % (g,))
    m = as_samples(samples)
    # centre and scale the data so the design matrix is well conditioned
    c0 = m.mean(axis=0)
    s0 = np.sqrt(np.mean(np.sum((m - c0) ** 2, axis=1)))
    if not s0 > 1e-9 * (1.0 + np.linalg.norm(c0)):
        raise CalibrationError('all samples are the same reading: turn the sensor through many orientations')
    x, y, z = ((m - c0) / s0).T
    d = np.column_stack([x * x, y * y, z * z, 2 * x * y, 2 * x * z, 2 * y * z, 2 * x, 2 * y, 2 * z])
    sv = np.linalg.svd(d, compute_uv=False)
    if sv[-1] < 1e-6 * sv[0]:
        raise CalibrationError('the samples do not determine an ellipsoid (they cover too few '
                               'orientations): record the sensor turned through every direction')
    v, *_ = np.linalg.lstsq(d, np.ones(len(m)), rcond=None)
    q = np.array([[v[0], v[3], v[4]], [v[3], v[1], v[5]], [v[4], v[5], v[2]]])
    p = v[6:9]
    try:
        centre = -np.linalg.solve(q, p)
    except np.linalg.LinAlgError:
        raise CalibrationError('the samples do not determine an ellipsoid (singular fit)')
    k = 1.0 + centre @ q @ centre
    w, u = np.linalg.eigh(q / k) if abs(k) > 1e-12 else (np.zeros(3), None)
    if not np.all(w > 0):
        raise CalibrationError('the fitted surface is not an ellipsoid: the samples cover too few '
                               'orientations or are not taken at rest')
    # unit-sphere map in the scaled frame: |S (x - centre)| = 1, S = sqrt(Q/k)
    s = u @ np.diag(np.sqrt(w)) @ u.T
    a_inv = g / s0 * s                 # back to the data's units: |A^-1 (M - b)| = g
    b = c0 + s0 * centre
    a = np.linalg.inv(a_inv)
    return (a + a.T) / 2, b


def correct(samples, a_inv, b):
    """m = A^-1 (M - b) for every sample."""
    return (np.asarray(samples, dtype=float) - b) @ np.asarray(a_inv).T


def residuals(samples, a_inv, b, g=G):
    """|m| - g of the corrected samples."""
    return np.linalg.norm(correct(samples, a_inv, b), axis=1) - g


def compose(current_a_inv, current_b, a, b):
    """The samples were recorded with a calibration (C, d) already applied, m' = C (M - d), and
    fit m' ~ A m + b: the calibration of the raw readings is (A^-1 C, d + C^-1 b)."""
    c = np.asarray(current_a_inv, dtype=float)
    return np.linalg.inv(a) @ c, np.asarray(current_b, dtype=float) + np.linalg.solve(c, b)


HEADER = '''// Accelerometer calibration of the space scanner's MPU6050 (the diploma's ellipsoid model,
// section 3.2: M ~ A m + b, applied as m = A^-1 (M - b) to the reading in m/s^2).
// Written by `rosrun space_scanner_hw calibrate_accel`%(source)s.
%(stats)s#pragma once

// A^-1 (row-major)
const float ACCEL_CAL_MATRIX[3][3] = {
%(matrix)s
};
// b, m/s^2
const float ACCEL_CAL_OFFSET[3] = {%(offset)s};
'''


def _f(v):
    return '%.9g' % v


def header_text(a_inv, b, source='', stats=''):
    """accel_calibration.h for the firmware."""
    rows = ',\n'.join('  {%s}' % ', '.join(_f(v) for v in row) for row in np.asarray(a_inv))
    return HEADER % {'source': (' from %s' % source) if source else '',
                     'stats': ''.join('// %s\n' % line for line in stats.splitlines()) if stats else '',
                     'matrix': rows, 'offset': ', '.join(_f(v) for v in b)}


def parse_header(text):
    """(A^-1, b) from an accel_calibration.h."""
    def numbers(name):
        m = re.search(r'%s\s*(\[3\])+\s*=\s*\{(.*?)\};' % name, text, re.S)
        if not m:
            raise CalibrationError('no %s in the calibration header' % name)
        vals = re.findall(r'[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?', m.group(2))
        return np.array([float(v) for v in vals])
    mat, off = numbers('ACCEL_CAL_MATRIX'), numbers('ACCEL_CAL_OFFSET')
    if mat.size != 9 or off.size != 3:
        raise CalibrationError('calibration header: ACCEL_CAL_MATRIX needs 9 numbers and '
                               'ACCEL_CAL_OFFSET 3 (got %d and %d)' % (mat.size, off.size))
    return mat.reshape(3, 3), off


def coverage(samples, b):
    """Smallest spread of the measurement directions about b along any axis (0: all samples
    in a plane or one orientation; 1/sqrt(3) = 0.577 for directions all over the sphere)."""
    d = np.asarray(samples, dtype=float) - b
    d /= np.linalg.norm(d, axis=1, keepdims=True)
    return float(math.sqrt(max(np.linalg.eigvalsh(d.T @ d / len(d))[0], 0.0)))


def summary(samples, a_inv, b, g=G):
    raw = np.linalg.norm(np.asarray(samples, dtype=float), axis=1) - g
    fit = residuals(samples, a_inv, b, g)
    return ('%d samples, direction coverage %.2f (0.58 = every direction); |M| - g: RMS %.4f m/s^2 '
            'raw, %.4f m/s^2 calibrated' % (len(samples), coverage(samples, b),
                                            float(np.sqrt(np.mean(raw ** 2))), float(np.sqrt(np.mean(fit ** 2)))))


# ---------------------------------------------------------------------------- ROS inputs

def samples_from_bag(path, topic='imu/data_raw'):
    """linear_acceleration of every sensor_msgs/Imu on `topic` (with or without a leading
    slash) in a bag file."""
    import rosbag
    try:
        bag = rosbag.Bag(path)
    except Exception as e:
        raise CalibrationError('cannot read bag %s: %s' % (path, e))
    want = {topic.lstrip('/'), '/' + topic.lstrip('/')}
    out = []
    with bag:
        for _, msg, _ in bag.read_messages(topics=list(want)):
            a = msg.linear_acceleration
            out.append((a.x, a.y, a.z))
    if not out:
        raise CalibrationError('bag %s has no messages on %s' % (path, topic))
    return np.array(out)


def samples_from_topic(topic='imu/data_raw', count=300, timeout=600.0):
    """`count` sensor_msgs/Imu messages from a live topic (rospy must be initialised)."""
    import threading
    import rospy
    from sensor_msgs.msg import Imu
    got, done = [], threading.Event()

    def on_imu(msg):
        if len(got) < count:
            a = msg.linear_acceleration
            got.append((a.x, a.y, a.z))
            if len(got) == count:
                done.set()
    sub = rospy.Subscriber(topic, Imu, on_imu, queue_size=100)
    try:
        if not done.wait(timeout):
            raise CalibrationError('%d of %d messages on %s after %.0f s' % (len(got), count, topic, timeout))
    finally:
        sub.unregister()
    return np.array(got)


def main(argv=None):
    import argparse
    import sys
    ap = argparse.ArgumentParser(
        prog='calibrate_accel',
        description='Fit the accelerometer ellipsoid M ~ A m + b (diploma section 3.2) to '
                    'imu/data_raw recorded at rest in many orientations and write the '
                    'firmware\'s accel_calibration.h.')
    src = ap.add_mutually_exclusive_group(required=True)
    src.add_argument('--bag', help='bag file with sensor_msgs/Imu on --topic')
    src.add_argument('--live', action='store_true', help='read --count messages from the live topic')
    ap.add_argument('--topic', default='imu/data_raw')
    ap.add_argument('-n', '--count', type=int, default=300, help='messages to read with --live (default 300)')
    ap.add_argument('--timeout', type=float, default=600.0, help='seconds to wait for them (--live)')
    ap.add_argument('--gravity', type=float, default=G)
    ap.add_argument('--current', help='accel_calibration.h the firmware applied while recording '
                                      '(default: none, the readings are raw)')
    ap.add_argument('-o', '--out', help='header to write (default: print it)')
    args = ap.parse_args(argv)
    try:
        if args.bag:
            samples = samples_from_bag(args.bag, args.topic)
            source = '%s (%s)' % (args.bag, args.topic)
        else:
            if args.count < MIN_SAMPLES:
                raise CalibrationError('--count must be at least %d' % MIN_SAMPLES)
            import rospy
            rospy.init_node('calibrate_accel', anonymous=True, disable_signals=True)
            sys.stderr.write('reading %d messages on %s: turn the robot slowly through every '
                             'orientation, holding each still\n' % (args.count, rospy.resolve_name(args.topic)))
            samples = samples_from_topic(args.topic, args.count, args.timeout)
            source = rospy.resolve_name(args.topic)
        a, b = fit_ellipsoid(samples, args.gravity)
        a_inv = np.linalg.inv(a)
        stats = summary(samples, a_inv, b, args.gravity)
        if args.current:
            with open(args.current) as f:
                c, d = parse_header(f.read())
            a_inv, b = compose(c, d, a, b)
            stats += '\ncomposed with %s' % args.current
        text = header_text(a_inv, b, source, stats)
    except (CalibrationError, OSError) as e:
        sys.stderr.write('calibrate_accel: %s\n' % e)
        return 1
    sys.stderr.write(stats + '\n')
    if args.out:
        with open(args.out, 'w') as f:
            f.write(text)
        sys.stderr.write('wrote %s\n' % args.out)
    else:
        sys.stdout.write(text)
    return 0
