"""The scene as RViz markers (there is no Gazebo GUI): one Marker per visual shape. This module
decides what each shape looks like (kind, scale, colour, triangles, the plane's offset); the
messages are built by ros/convert.py (marker_msg, place_marker, scene_marker_array)."""
import numpy as np

from ode_sim.description.transforms import Pose, quat_from_axis_angle
from ode_sim.ros.convert import marker_msg, place_marker, scene_marker_array

NS = 'ode_sim'


def marker_spec(shape):
    """(kind, scale, rgba, points, colors, offset) of a shape's marker: kind 'cube' |
    'cylinder' | 'sphere' | 'triangles', points (N, 3) and per-vertex colours of a triangle
    list (else None), offset Pose from the shape frame to the marker frame (None: none); None
    for a geometry RViz cannot show. Depends on the geometry only."""
    g = shape.geometry
    color = tuple(float(c) for c in shape.color)
    if g.kind == 'box':
        return 'cube', tuple(max(float(v), 1e-4) for v in g.size), color, None, None, None
    if g.kind == 'cylinder':
        d = 2 * float(g.radius)
        return 'cylinder', (d, d, float(g.length)), color, None, None, None
    if g.kind == 'sphere':
        d = 2 * float(g.radius)
        return 'sphere', (d, d, d), color, None, None, None
    if g.kind == 'plane':
        # a thin slab whose top face is the plane, a millimetre low so RViz's grid stays visible
        sx, sy = (float(v) for v in g.plane_size)
        n = np.asarray(g.normal, dtype=float)
        n = n / np.linalg.norm(n)
        z = np.array([0.0, 0.0, 1.0])
        axis = np.cross(z, n)
        if np.linalg.norm(axis) < 1e-9:
            rot = Pose()
        else:
            rot = Pose((0, 0, 0), quat_from_axis_angle(axis, np.arccos(np.clip(n @ z, -1, 1))))
        return 'cube', (sx, sy, 0.001), color, None, None, rot * Pose((0, 0, -0.0015))
    if g.kind == 'mesh':
        if g.vertices is None or g.faces is None:
            return None
        parts = getattr(g, 'parts', None)
        if not parts:
            return 'triangles', (1.0, 1.0, 1.0), color, g.vertices[g.faces.reshape(-1)], None, None
        # a mesh file's parts, each in its material's colour (the visual's own material over
        # them; a texture as its mean colour): per-vertex colours
        own = getattr(shape, 'material', None)
        points, colors = [], []
        for part in parts:
            rgba = _material_rgba(own or part.material, shape.color)
            tri = part.positions[part.faces.reshape(-1)]
            points.append(tri)
            colors += [rgba] * len(tri)
        return ('triangles', (1.0, 1.0, 1.0), (1.0, 1.0, 1.0, 1.0), np.concatenate(points),
                colors, None)
    return None


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


def _marker_body(shape):
    """(Marker with everything but header, id and pose, offset Pose) or None."""
    spec = marker_spec(shape)
    if spec is None:
        return None
    kind, scale, color, points, colors, offset = spec
    return marker_msg('%s/%s' % (NS, shape.model), kind, scale, color, points, colors), offset


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
    pose = shape.world_pose()
    return place_marker(m, marker_id, frame, stamp, pose if offset is None else pose * offset)


class SceneMarkers:
    """Builds the scene's MarkerArray, keeping every shape's geometry part between builds."""

    def __init__(self, frame):
        self.frame = frame
        self._cache = {}

    def build(self, shapes, stamp, include=None):
        """A DELETEALL first (removed models disappear), then one Marker per shape (optionally
        filtered by include(shape))."""
        markers = []
        live = set()
        for i, s in enumerate(shapes):
            if include is not None and not include(s):
                continue
            live.add((s.key, id(s.geometry)))
            mk = shape_marker(s, i, self.frame, stamp, self._cache)
            if mk is not None:
                markers.append(mk)
        for key in [k for k in self._cache if k not in live]:
            del self._cache[key]
        return scene_marker_array(self.frame, markers)
