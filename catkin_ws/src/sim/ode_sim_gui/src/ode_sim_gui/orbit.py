"""The 3D view's camera as Gazebo's user camera moves it, ROS-free and Qt-free.

The camera orbits a focus point: `yaw` is the heading of its view direction, `pitch` how far
it looks down (positive: down), `distance` from the eye to the focus. Pixels are Qt widget
coordinates (x right, y down, (0, 0) the top-left corner of the view, continuous); the view
is a pinhole camera with the horizontal field of view `hfov` and square pixels, principal point
at the centre of the view, as ode_sim.engine.render.Renderer draws it.

Mouse as in Gazebo: left drag orbits, middle drag (or shift + left) pans so that the ground
under the cursor follows it, the wheel zooms towards the point under the cursor; `reset()` goes
back to Gazebo's default user camera (eye (5, -5, 2) looking at the origin).
"""
import math

import numpy as np

from ode_sim.description.transforms import Pose, quat_from_rpy

DEFAULT_EYE = (5.0, -5.0, 2.0)
DEFAULT_FOCUS = (0.0, 0.0, 0.0)
ORBIT_RAD_PER_PIXEL = 0.01
ZOOM_PER_NOTCH = 0.8            # distance factor per wheel notch (120 eighths of a degree) in
MIN_DISTANCE = 0.05
MAX_DISTANCE = 1000.0
PITCH_LIMIT = math.radians(89.0)


class OrbitCamera:
    def __init__(self, width=640, height=480, hfov=math.radians(60.0)):
        self.hfov = float(hfov)
        self.resize(width, height)
        self.reset()

    # ----------------------------------------------------------------- state
    def resize(self, width, height):
        if width <= 0 or height <= 0:
            raise ValueError('view size must be positive, got %sx%s' % (width, height))
        self.width, self.height = int(width), int(height)

    def reset(self):
        self.look_at(DEFAULT_EYE, DEFAULT_FOCUS)

    def look_at(self, eye, focus):
        eye, focus = np.asarray(eye, float), np.asarray(focus, float)
        d = focus - eye
        dist = float(np.linalg.norm(d))
        if dist < 1e-9:
            raise ValueError('eye and focus coincide')
        self.focus = focus.copy()
        self.distance = dist
        self.yaw = math.atan2(d[1], d[0])
        self.pitch = math.asin(max(-1.0, min(1.0, -d[2] / dist)))
        self.pitch = max(-PITCH_LIMIT, min(PITCH_LIMIT, self.pitch))

    def forward(self):
        cp = math.cos(self.pitch)
        return np.array([cp * math.cos(self.yaw), cp * math.sin(self.yaw), -math.sin(self.pitch)])

    def eye(self):
        return self.focus - self.distance * self.forward()

    def pose(self):
        """The camera pose (Gazebo's camera frame: X forward, Y left, Z up) for Renderer.render."""
        return Pose(self.eye(), quat_from_rpy(0.0, self.pitch, self.yaw))

    def focal(self):
        return self.width / (2.0 * math.tan(self.hfov / 2.0))

    # ------------------------------------------------------------ geometry
    def ray(self, x, y):
        """(origin, unit direction) in the world of the ray through view pixel (x, y)."""
        pose = self.pose()
        d_cam = np.array([self.focal(), self.width / 2.0 - x, self.height / 2.0 - y])
        d = pose.rotate(d_cam)
        return pose.p.copy(), d / np.linalg.norm(d)

    def project(self, point):
        """View pixel (x, y) of a world point, or None when it is behind the camera."""
        pose = self.pose()
        c = pose.inverse().apply(np.asarray(point, float))
        if c[0] <= 1e-9:
            return None
        f = self.focal()
        return (self.width / 2.0 - f * c[1] / c[0], self.height / 2.0 - f * c[2] / c[0])

    def ground_point(self, x, y, z=0.0):
        """Where the ray through pixel (x, y) meets the horizontal plane at height z, or None
        when it does not (looking up, or parallel)."""
        o, d = self.ray(x, y)
        if abs(d[2]) < 1e-9:
            return None
        t = (z - o[2]) / d[2]
        if t <= 0:
            return None
        return o + t * d

    # --------------------------------------------------------------- mouse
    def orbit(self, dx, dy):
        """Left drag by (dx, dy) pixels: turn around the focus (drag right: the scene turns
        right; drag down: look from higher up)."""
        self.yaw -= dx * ORBIT_RAD_PER_PIXEL
        self.yaw = math.atan2(math.sin(self.yaw), math.cos(self.yaw))
        self.pitch = max(-PITCH_LIMIT, min(PITCH_LIMIT, self.pitch + dy * ORBIT_RAD_PER_PIXEL))

    def pan(self, dx, dy):
        """Middle (shift + left) drag by (dx, dy) pixels: move the camera parallel to the view
        plane so that points at the focus distance follow the cursor."""
        s = self.distance / self.focal()
        rot = self.pose().rotation()
        left, up = rot[:, 1], rot[:, 2]
        self.focus = self.focus + s * (dx * left + dy * up)

    def zoom(self, notches, x=None, y=None):
        """Wheel by `notches` (positive: towards the scene) at pixel (x, y) (default: the
        centre): the point under the cursor at the focus depth stays under the cursor."""
        factor = ZOOM_PER_NOTCH ** notches
        new = max(MIN_DISTANCE, min(MAX_DISTANCE, self.distance * factor))
        factor = new / self.distance
        if x is None or y is None:
            x, y = self.width / 2.0, self.height / 2.0
        eye = self.eye()
        o, d = self.ray(x, y)
        # the point under the cursor on the plane through the focus, facing the camera
        fwd = self.forward()
        t = self.distance / max(float(np.dot(d, fwd)), 1e-6)
        target = o + t * d
        new_eye = target + (eye - target) * factor
        self.distance = new
        self.focus = new_eye + new * fwd

    def frame(self, centre, radius):
        """Look at a sphere (centre, radius) from the current direction so that it fills the
        view (View -> Move to / double click)."""
        r = max(float(radius), 0.05)
        self.focus = np.asarray(centre, float).copy()
        self.distance = min(MAX_DISTANCE, max(MIN_DISTANCE, r / math.sin(self.hfov / 2.0) * 1.2))
