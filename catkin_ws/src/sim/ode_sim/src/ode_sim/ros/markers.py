"""The scene as RViz markers (there is no Gazebo GUI): one Marker per visual shape."""
import numpy as np
from geometry_msgs.msg import Point
from std_msgs.msg import ColorRGBA
from visualization_msgs.msg import Marker, MarkerArray

from ode_sim.description.transforms import Pose, quat_from_axis_angle
from ode_sim.ros.convert import pose_msg

NS = 'ode_sim'


def _marker_body(shape):
    """(Marker with type, scale, colour and points set, offset Pose from the shape frame to the
    marker frame), or None for a geometry RViz cannot show. Depends on the geometry only."""
    g = shape.geometry
    m = Marker()
    m.action = Marker.ADD
    m.ns = '%s/%s' % (NS, shape.model)
    m.color = ColorRGBA(*[float(c) for c in shape.color])
    m.frame_locked = False
    offset = None
    if g.kind == 'box':
        m.type = Marker.CUBE
        m.scale.x, m.scale.y, m.scale.z = (max(float(v), 1e-4) for v in g.size)
    elif g.kind == 'cylinder':
        m.type = Marker.CYLINDER
        m.scale.x = m.scale.y = 2 * float(g.radius)
        m.scale.z = float(g.length)
    elif g.kind == 'sphere':
        m.type = Marker.SPHERE
        m.scale.x = m.scale.y = m.scale.z = 2 * float(g.radius)
    elif g.kind == 'plane':
        # a thin slab whose top face is the plane, a millimetre low so RViz's grid stays visible
        m.type = Marker.CUBE
        sx, sy = (float(v) for v in g.plane_size)
        m.scale.x, m.scale.y, m.scale.z = sx, sy, 0.001
        n = np.asarray(g.normal, dtype=float)
        n = n / np.linalg.norm(n)
        z = np.array([0.0, 0.0, 1.0])
        axis = np.cross(z, n)
        if np.linalg.norm(axis) < 1e-9:
            rot = Pose()
        else:
            rot = Pose((0, 0, 0), quat_from_axis_angle(axis, np.arccos(np.clip(n @ z, -1, 1))))
        offset = rot * Pose((0, 0, -0.0015))
    elif g.kind == 'mesh':
        if g.vertices is None or g.faces is None:
            return None
        m.type = Marker.TRIANGLE_LIST
        m.scale.x = m.scale.y = m.scale.z = 1.0
        parts = getattr(g, 'parts', None)
        if not parts:
            tri = g.vertices[g.faces.reshape(-1)]
            m.points = [Point(float(x), float(y), float(z)) for x, y, z in tri]
        else:
            # a mesh file's parts, each in its material's colour (the visual's own material
            # over them; a texture as its mean colour): per-vertex colours
            own = getattr(shape, 'material', None)
            for part in parts:
                rgba = ColorRGBA(*_material_rgba(own or part.material, shape.color))
                tri = part.positions[part.faces.reshape(-1)]
                m.points += [Point(float(x), float(y), float(z)) for x, y, z in tri]
                m.colors += [rgba] * len(tri)
            m.color = ColorRGBA(1.0, 1.0, 1.0, 1.0)
    else:
        return None
    return m, offset


def _material_rgba(mat, fallback):
    """RGBA of a model.Material for a marker: diffuse x the texture's mean colour, opacity."""
    if mat is None:
        return tuple(float(c) for c in fallback)
    rgb = np.array([float(c) for c in mat.diffuse[:3]])
    if mat.texture:
        from ode_sim.engine.gl import texture_image
        _, img = texture_image(mat.texture)
        if img is not None:
            rgb = rgb * img[..., :3].reshape(-1, 3).mean(axis=0) / 255.0
    return tuple(float(c) for c in rgb) + (float(mat.opacity),)


def shape_marker(shape, marker_id, frame, stamp, cache=None):
    """A Marker for one ShapeInstance (box, cylinder, sphere, plane, mesh) at its current pose,
    or None. `cache` (a dict) keeps the geometry part between calls: a mesh's triangle list is
    built once, later calls only set the pose."""
    key = (shape.key, id(shape.geometry))
    body = cache.get(key) if cache is not None else None
    if body is None:
        body = _marker_body(shape)
        if body is None:
            return None
        if cache is not None:
            cache[key] = body
    m, offset = body
    m.header.frame_id = frame
    m.header.stamp = stamp
    m.id = marker_id
    pose = shape.world_pose()
    m.pose = pose_msg(pose if offset is None else pose * offset)
    return m


class SceneMarkers:
    """Builds the scene's MarkerArray, keeping every shape's geometry part between builds."""

    def __init__(self, frame):
        self.frame = frame
        self._cache = {}

    def build(self, shapes, stamp, include=None):
        """A DELETEALL first (removed models disappear), then one Marker per shape (optionally
        filtered by include(shape))."""
        arr = MarkerArray()
        clear = Marker()
        clear.header.frame_id = self.frame
        clear.action = Marker.DELETEALL
        arr.markers.append(clear)
        live = set()
        for i, s in enumerate(shapes):
            if include is not None and not include(s):
                continue
            live.add((s.key, id(s.geometry)))
            mk = shape_marker(s, i, self.frame, stamp, self._cache)
            if mk is not None:
                arr.markers.append(mk)
        for key in [k for k in self._cache if k not in live]:
            del self._cache[key]
        return arr
