"""Lidar scan processing of sensor_data_proc.py, without ROS: the nearest obstacle and the
free distance in three sectors (right, front, left) of a sensor_msgs/LaserScan."""
import math


def valid(ranges, range_min, range_max):
    """Indices and values of readings inside [range_min, range_max] (inf/nan = no echo)."""
    return [(i, r) for i, r in enumerate(ranges) if math.isfinite(r) and range_min <= r <= range_max]


def nearest(scan):
    """(distance m, bearing rad) of the nearest echo, or None when nothing is in range."""
    pts = valid(scan.ranges, scan.range_min, scan.range_max)
    if not pts:
        return None
    i, r = min(pts, key=lambda p: p[1])
    return r, scan.angle_min + i * scan.angle_increment


def sectors(scan, n=3):
    """Minimum distance in n equal angular sectors from angle_min to angle_max (right to left
    for a scan counter-clockwise); inf where a sector has no echo."""
    out = [math.inf] * n
    total = len(scan.ranges)
    if total == 0:
        return out
    for i, r in valid(scan.ranges, scan.range_min, scan.range_max):
        k = min(n - 1, i * n // total)
        out[k] = min(out[k], r)
    return out


def describe(scan):
    """One log line about a scan."""
    near = nearest(scan)
    right, front, left = sectors(scan, 3)
    head = ('nearest %.2f m at %+.0f deg' % (near[0], math.degrees(near[1]))) if near else 'nothing in range'
    return '%d rays: %s; right %.2f front %.2f left %.2f m' % (len(scan.ranges), head, right, front, left)
