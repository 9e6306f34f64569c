"""The GPS of hector_gazebo_plugins (libhector_gazebo_ros_gps.so; also answers to the name
libgazebo_ros_gps.so): sensor_msgs/NavSatFix and geometry_msgs/Vector3Stamped velocity of a
link, from its simulated pose, as GazeboRosGps computes them.

Model plugin tags (hector's names and defaults): `robotNamespace` (root), `bodyName` (the
model's first link), `frameId` ("/world"), `topicName` ("fix"), `velocityTopicName`
("fix_velocity"), `referenceLatitude` (49.9 deg), `referenceLongitude` (8.9 deg),
`referenceHeading` (0 deg), `referenceAltitude` (0 m), `status` (STATUS_FIX 0), `service` (0),
`updateRate` (4 Hz); error models for the position (`offset`, `drift`, `driftFrequency`
(1/3600 Hz), `gaussianNoise`) and the velocity (the same with the prefix `velocity`:
`velocityOffset`, ...), each a number or "x y z", all 0 by default (exact readings).

The local x/y/z of the link (plus the error) is turned into latitude / longitude / altitude
on the WGS84 ellipsoid's radii at the reference latitude: lat = lat0 + (cos h x + sin h y) /
R_north, lon = lon0 - (-sin h x + cos h y) / R_east (degrees), alt = alt0 + z; the velocity
is rotated by the heading the same way. position_covariance is diagonal (drift^2 + noise^2).
Not provided: hector's dynamic_reconfigure servers of the error models and status.
"""
import math
import random

import numpy as np

from geometry_msgs.msg import Vector3Stamped
from sensor_msgs.msg import NavSatFix, NavSatStatus

from ode_sim.ros.plugins.base import Plugin
from ode_sim.ros.plugins.rosio import close

EQUATORIAL_RADIUS = 6378137.0             # WGS84
FLATTENING = 1.0 / 298.257223563
EXCENTRITY2 = 2 * FLATTENING - FLATTENING * FLATTENING


def earth_radii(latitude_deg):
    """(radius north, radius east) in metres at a latitude, on the WGS84 ellipsoid."""
    s = math.sin(math.radians(latitude_deg))
    temp = 1.0 / (1.0 - EXCENTRITY2 * s * s)
    prime_vertical = EQUATORIAL_RADIUS * math.sqrt(temp)
    return (prime_vertical * (1 - EXCENTRITY2) * temp,
            prime_vertical * math.cos(math.radians(latitude_deg)))


class ErrorModel:
    """hector's SensorModel3: error = offset + drift (first-order Gauss-Markov) + noise."""

    def __init__(self, plugin, prefix, rng):
        def tag(name):
            return (prefix + name[0].upper() + name[1:]) if prefix else name
        self.offset = self._vec(plugin, tag('offset'), 0.0)
        self.drift = self._vec(plugin, tag('drift'), 0.0)
        self.drift_frequency = self._vec(plugin, tag('driftFrequency'), 1.0 / 3600.0)
        self.gaussian_noise = self._vec(plugin, tag('gaussianNoise'), 0.0)
        self.rng = rng
        self.reset()

    @staticmethod
    def _vec(plugin, tag, default):
        if not plugin.has(tag):
            return np.full(3, default)
        try:
            vals = [float(v) for v in plugin.params[tag].replace(',', ' ').split()]
        except ValueError:
            vals = []
        if len(vals) == 1:
            vals = vals * 3
        if len(vals) != 3:
            raise plugin.error('<%s> must be a number or three numbers, got %r'
                               % (tag, plugin.params[tag]))
        return np.array(vals)

    def reset(self):
        self.current_drift = np.zeros(3)
        self.current_error = np.zeros(3)

    def _gauss(self, sigma):
        return np.array([self.rng.gauss(0.0, s) if s > 0 else 0.0 for s in sigma])

    def __call__(self, value, dt):
        self.current_drift = self.current_drift - dt * (
            self.current_drift * self.drift_frequency
            + self._gauss(np.sqrt(2 * self.drift_frequency) * np.abs(self.drift)))
        self.current_error = self.offset + self.current_drift + self._gauss(self.gaussian_noise)
        return np.asarray(value, dtype=float) + self.current_error


class Gps(Plugin):
    """libhector_gazebo_ros_gps.so"""

    def __init__(self, ctx, model, desc, sensor=None):
        super().__init__(ctx, model, desc, sensor)
        self.ns = self.params['robotNamespace'].strip() if self.has('robotNamespace') else ''
        if self.has('bodyName'):
            name = self.params['bodyName'].strip()
        else:
            name = next(iter(model.links), '')
        if name not in model.links:
            raise self.error('GazeboRosGps plugin error: bodyName: %s does not exist' % name)
        self.body = model.links[name]
        p = lambda tag, default, cast=str: self.param(tag, default, cast, warn=False)  # noqa
        self.frame_id = p('frameId', '/world').strip()
        fix_topic = p('topicName', 'fix').strip()
        vel_topic = p('velocityTopicName', 'fix_velocity').strip()
        self.lat0 = p('referenceLatitude', 49.9, float)
        self.lon0 = p('referenceLongitude', 8.9, float)
        self.heading = math.radians(p('referenceHeading', 0.0, float))
        self.alt0 = p('referenceAltitude', 0.0, float)
        self.status = p('status', NavSatStatus.STATUS_FIX, int)
        self.service = p('service', 0, int)
        rate = p('updateRate', 4.0, float)
        self.rng = random.Random(0)
        self.position_error = ErrorModel(self, '', self.rng)
        self.velocity_error = ErrorModel(self, 'velocity', self.rng)
        self.radius_north, self.radius_east = earth_radii(self.lat0)
        self.fix_pub = ctx.io.publisher(self.topic(fix_topic), NavSatFix, queue_size=10)
        self.vel_pub = ctx.io.publisher(self.topic(vel_topic), Vector3Stamped, queue_size=10)
        self.set_rate(rate)
        self.last = ctx.time

    def next_update(self):
        return self._next_due()

    def update(self):
        if not self.due():
            return
        t = self.ctx.time
        dt = t - self.last
        self.last = t
        pose = self.body.pose()
        lin, _ang = self.body.velocity()
        velocity = self.velocity_error(lin, dt)
        position = self.position_error(pose.p, dt)
        # a velocity offset integrates into the position drift for the next reading
        self.position_error.current_drift = (self.position_error.current_drift
                                             + dt * self.velocity_error.current_drift)
        c, s = math.cos(self.heading), math.sin(self.heading)
        fix = NavSatFix()
        fix.header.stamp = self.ctx.now()
        fix.header.frame_id = self.frame_id
        fix.status.status = self.status
        fix.status.service = self.service
        x, y, z = (float(v) for v in position)
        fix.latitude = self.lat0 + (c * x + s * y) / self.radius_north * 180.0 / math.pi
        fix.longitude = self.lon0 - (-s * x + c * y) / self.radius_east * 180.0 / math.pi
        fix.altitude = self.alt0 + z
        pe = self.position_error
        cov = pe.drift * pe.drift + pe.gaussian_noise * pe.gaussian_noise
        fix.position_covariance = [float(cov[0]), 0.0, 0.0, 0.0, float(cov[1]), 0.0, 0.0, 0.0,
                                   float(cov[2])]
        fix.position_covariance_type = NavSatFix.COVARIANCE_TYPE_DIAGONAL_KNOWN
        vel = Vector3Stamped()
        vel.header = fix.header
        vx, vy, vz = (float(v) for v in velocity)
        vel.vector.x = c * vx + s * vy
        vel.vector.y = -s * vx + c * vy
        vel.vector.z = vz
        self.fix_pub.publish(fix)
        self.vel_pub.publish(vel)

    def reset(self):
        super().reset()
        self.last = self.ctx.time
        self.position_error.reset()
        self.velocity_error.reset()

    def shutdown(self):
        close(self.fix_pub, self.vel_pub)


PLUGINS = {'libhector_gazebo_ros_gps.so': Gps, 'libgazebo_ros_gps.so': Gps}
