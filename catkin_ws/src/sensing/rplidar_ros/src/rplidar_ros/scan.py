"""From one 360-degree scan of nodes to the LaserScan layout of rplidarNode. No ROS imports.

Device angles are clockwise degrees; the published angle is pi - device angle, and the data
are reversed (unless `inverted`) so that the index grows with counter-clockwise angle.
"""
import math

from .protocol import node_angle_deg

RANGE_MIN = 0.15


class ScanData:
    __slots__ = ('angle_min', 'angle_max', 'angle_increment', 'time_increment', 'scan_time',
                 'range_min', 'range_max', 'ranges', 'intensities')


def ascend(nodes):
    """Nodes sorted by angle; None if every node is invalid (the SDK's ascendScanData fails)."""
    if not any(n.dist_mm_q2 for n in nodes):
        return None
    return sorted(nodes, key=lambda n: n.angle_z_q14)


def compensate_multiple(us_per_sample, scan_frequency):
    return (1e6 / us_per_sample / scan_frequency) / 360.0 + 1.0


def compensate(nodes, multiple):
    """Resample into int(360 * multiple) fixed bins; each valid node fills ceil(multiple) bins."""
    count = int(360 * multiple)
    bins = [None] * count
    reps = int(math.ceil(multiple))
    for n in nodes:
        if n.dist_mm_q2:
            start = int(node_angle_deg(n) * multiple)
            for j in range(reps):
                bins[min(start + j, count - 1)] = n
    return bins


def build(nodes, scan_time, inverted, angle_compensate, multiple, max_distance):
    """-> ScanData, following rplidarNode's publish_scan."""
    sorted_nodes = ascend(nodes)
    if sorted_nodes is None:
        # publish the raw nodes over 0..359 degrees, as the original does
        return _publish(nodes, scan_time, inverted, 0.0, math.radians(359.0), max_distance)
    if angle_compensate:
        bins = compensate(sorted_nodes, multiple)
        return _publish(bins, scan_time, inverted, 0.0, math.radians(360.0), max_distance)
    start = 0
    while sorted_nodes[start].dist_mm_q2 == 0:
        start += 1
    end = len(sorted_nodes) - 1
    while sorted_nodes[end].dist_mm_q2 == 0:
        end -= 1
    used = sorted_nodes[start:end + 1]
    return _publish(used, scan_time, inverted, math.radians(node_angle_deg(used[0])),
                    math.radians(node_angle_deg(used[-1])), max_distance)


def _publish(nodes, scan_time, inverted, angle_min, angle_max, max_distance):
    s = ScanData()
    n = len(nodes)
    reversed_ = angle_max > angle_min
    if reversed_:
        s.angle_min, s.angle_max = math.pi - angle_max, math.pi - angle_min
    else:
        s.angle_min, s.angle_max = math.pi - angle_min, math.pi - angle_max
    s.angle_increment = (s.angle_max - s.angle_min) / (n - 1) if n > 1 else 0.0
    s.scan_time = scan_time
    s.time_increment = scan_time / (n - 1) if n > 1 else 0.0
    s.range_min = RANGE_MIN
    s.range_max = max_distance
    ranges = [math.inf] * n
    intens = [0.0] * n
    reverse_data = (not inverted and reversed_) or (inverted and not reversed_)
    for i, node in enumerate(nodes):
        j = n - 1 - i if reverse_data else i
        if node is None or node.dist_mm_q2 == 0:
            continue
        ranges[j] = node.dist_mm_q2 / 4.0 / 1000.0
        intens[j] = float(node.quality >> 2)
    s.ranges, s.intensities = ranges, intens
    return s
