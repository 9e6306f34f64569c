"""Lab 2 reference, ROS-free part: variants, route order, go-to-point and path following."""
import math
import re

# last ISU digit -> the distinct points (x, y) turtle 1 visits: textbook table 10.1 as printed
# (labs/lab2/variants.yaml; rows 7, 8, 9, 0 print a point twice, visited once here)
POINTS = {
    1: [(2, 3), (4, 2), (7, 1)], 2: [(2, 3), (4, 2)], 3: [(2, 3), (7, 1), (8, 4)],
    4: [(4, 2), (8, 4)], 5: [(2, 3), (7, 1), (8, 4)], 6: [(4, 2), (7, 1)],
    7: [(2, 3), (5, 4)], 8: [(7, 1), (5, 4)], 9: [(2, 3), (4, 2), (7, 1)],
    0: [(2, 3), (4, 2), (7, 1)],
}
V_MAX = 2.5         # m/s
W_MAX = 5.0         # rad/s
K_V = 2.0           # 1/s, speed per metre still to go
K_W = 6.0           # 1/s, turn rate per radian of heading error
TURN_FIRST = 0.25   # rad: turn in place above this heading error
REACHED = 0.08      # m: a point counts as reached
FOLLOW_STEP = 0.05  # m: spacing of the recorded leader path
FOLLOW_REACHED = 0.12


def parse_namespace(ns):
    """'/ns1_123451/' -> (1, '123451'); None if the namespace is not nsK_<ISU>."""
    m = re.match(r'^/?ns([12])_(\d+)/?$', ns)
    return (int(m.group(1)), m.group(2)) if m else None


def route(start, points):
    """Greedy nearest-neighbour order of the points from start."""
    left, here, out = list(points), start, []
    while left:
        nxt = min(left, key=lambda p: math.hypot(p[0] - here[0], p[1] - here[1]))
        left.remove(nxt)
        out.append(nxt)
        here = nxt
    return out


def wrap(a):
    return math.atan2(math.sin(a), math.cos(a))


def steer(x, y, theta, tx, ty, to_go=None, v_max=V_MAX):
    """(linear, angular) towards (tx, ty); to_go = path length left (default: the distance)."""
    dist = math.hypot(tx - x, ty - y)
    err = wrap(math.atan2(ty - y, tx - x) - theta)
    w = max(-W_MAX, min(W_MAX, K_W * err))
    if abs(err) > TURN_FIRST:
        return 0.0, w
    v = min(v_max, K_V * (dist if to_go is None else to_go))
    return v * math.cos(err), w


class Leader:
    """Drives through the points; `done` once every point was reached."""

    def __init__(self, points):
        self.points = list(points)
        self.todo = None
        self.done = False

    def command(self, x, y, theta):
        if self.todo is None:
            self.todo = route((x, y), self.points)
        while self.todo and math.hypot(self.todo[0][0] - x, self.todo[0][1] - y) < REACHED:
            self.todo.pop(0)
        if not self.todo:
            self.done = True
            return 0.0, 0.0
        return steer(x, y, theta, *self.todo[0])


class Follower:
    """Records the leader's positions and drives along them."""

    def __init__(self):
        self.path = []

    def leader_at(self, x, y):
        if not self.path or math.hypot(x - self.path[-1][0], y - self.path[-1][1]) >= FOLLOW_STEP:
            self.path.append((x, y))

    def command(self, x, y, theta):
        while self.path and math.hypot(self.path[0][0] - x, self.path[0][1] - y) < FOLLOW_REACHED:
            self.path.pop(0)
        if not self.path:
            return 0.0, 0.0
        tx, ty = self.path[0]
        to_go = math.hypot(tx - x, ty - y) + sum(
            math.hypot(b[0] - a[0], b[1] - a[1]) for a, b in zip(self.path, self.path[1:]))
        return steer(x, y, theta, tx, ty, to_go, V_MAX * 1.2)
