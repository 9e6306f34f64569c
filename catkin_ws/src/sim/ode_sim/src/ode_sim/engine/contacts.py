"""Contact sensors in the engine (Gazebo's ContactSensor): the collisions a sensor watches, and
the contact points the step loop recorded for them, with the contact joints' forces.

The loop (compiled or Python) records, for every contact joint of a watched geom in a step,
the point, the normal (oriented so that moving the watched geom along it by `depth`
separates the two), the depth, and the force and torque the contact put on the watched geom's
body (ODE's joint feedback; torque about the body's centre of mass; a static watched geom gets
the reaction to the force on the other body and no torque). Records of at most MAX_STEPS steps
with contacts are kept per sensor until it takes them (Gazebo keeps the last 100 contact
messages), so a sensor that updates every 0.1 s sees every step's contacts since its last update.
No ROS here."""
from dataclasses import dataclass
from typing import Tuple

MAX_STEPS = 100

Vec3 = Tuple[float, float, float]


@dataclass
class ContactPoint:
    time: float          # sim time after the step that made the contact
    mine: str            # the watched collision, scoped: model::link::collision
    other: str           # the collision it touches
    position: Vec3       # world frame
    normal: Vec3
    depth: float
    force: Vec3          # on the watched collision's body, world frame
    torque: Vec3


def scoped_name(geom):
    """model::link::collision of a geom PhysicsWorld built ('' once its model is removed)."""
    link = getattr(geom, 'link', None)
    shape = getattr(geom, 'shape', None)
    if link is None or shape is None:
        return ''
    return '%s::%s::%s' % (link.model.name, link.name, shape.name)


class ContactWatch:
    """The contact sensors of one PhysicsWorld: watch(key, geoms), take(key)."""

    def __init__(self, loop, time_at_step):
        """loop: the PhysicsWorld's step loop (set_watched, take_contacts); time_at_step(k): the
        sim time after step k."""
        self.loop = loop
        self.time_at_step = time_at_step
        self._geoms = {}            # sensor key -> set of watched geoms
        self._points = {}           # sensor key -> [(step, ContactPoint)]

    def watch(self, key, geoms):
        """Record the contacts of `geoms` for the sensor `key` (replaces its earlier set)."""
        self._geoms[key] = set(geoms)
        self._points.setdefault(key, [])
        self._push()

    def unwatch(self, key):
        self._geoms.pop(key, None)
        self._points.pop(key, None)
        self._push()

    def forget(self, geoms):
        """Geoms of a removed model leave every sensor."""
        gone = set(geoms)
        if any(s & gone for s in self._geoms.values()):
            for s in self._geoms.values():
                s -= gone
            self._push()

    def _push(self):
        self._drain()
        self.loop.set_watched(set().union(*self._geoms.values()) if self._geoms else set())

    def _drain(self):
        recs = self.loop.take_contacts()
        if not recs:
            return
        for step, mine, other, v in recs:
            keys = [k for k, s in self._geoms.items() if mine in s]
            if not keys:
                continue
            a, b = scoped_name(mine), scoped_name(other)
            if not a:
                continue
            p = ContactPoint(time=self.time_at_step(step), mine=a, other=b,
                             position=tuple(v[0:3]), normal=tuple(v[3:6]), depth=float(v[6]),
                             force=tuple(v[7:10]), torque=tuple(v[10:13]))
            for k in keys:
                self._points[k].append((step, p))
        for k, pts in self._points.items():
            steps = sorted({s for s, _ in pts})
            if len(steps) > MAX_STEPS:
                first = steps[-MAX_STEPS]
                self._points[k] = [(s, p) for s, p in pts if s >= first]

    def take(self, key):
        """The ContactPoints of sensor `key` since its last take, oldest first."""
        self._drain()
        pts = self._points.get(key, [])
        self._points[key] = []
        return [p for _, p in pts]
