"""What the window's 3D view draws, built from the simulator's world SDF (GetWorldSDF, parsed
with ode_sim.description like the simulator parses it) and the link poses it publishes: every
model's visuals, a ground grid, the world's lights and sky colour, a selection box. ROS-free
and Qt-free: poses come in as plain dicts, the GL drawing is ode_sim.engine.render's.
"""
import xml.etree.ElementTree as ET

import numpy as np

from ode_sim.description.model import Geometry, Material
from ode_sim.description.sdf import parse_world
from ode_sim.description.transforms import Pose
from ode_sim.engine.scene import ShapeInstance

GRID_CELLS = 20                 # Gazebo's grid: 20 x 20 cells of 1 m around the origin
GRID_LINE = 0.015               # line width (m)
GRID_COLOR = (0.52, 0.52, 0.52, 1.0)
SELECT_COLOR = (1.0, 0.55, 0.0, 1.0)
SELECT_LINE = 0.02
HIGHLIGHT_EMISSIVE = (0.25, 0.15, 0.0)


def _strip_pose(el):
    """Serialised element without its own <pose>: a model's identity apart from where it is."""
    copy = ET.Element(el.tag, el.attrib)
    copy.text = el.text
    for child in el:
        if child.tag != 'pose':
            copy.append(child)
    return ET.tostring(copy)


def model_keys(sdf_text):
    """{model name: identity key} of the <model>s and <include>s of a world SDF."""
    root = ET.fromstring(sdf_text)
    world = root.find('world') if root.tag == 'sdf' else root
    keys = {}
    if world is None:
        return keys
    for el in world:
        if el.tag == 'model':
            keys[el.get('name', '')] = _strip_pose(el)
        elif el.tag == 'include':
            name = el.findtext('name') or (el.findtext('uri') or '').split('/')[-1]
            keys[name] = _strip_pose(el)
    return keys


def shape_extent(geometry):
    """(min xyz, max xyz) of a geometry in its own frame, or None (planes, empty meshes)."""
    g = geometry
    if g.kind == 'box':
        h = np.asarray(g.size, float) / 2.0
        return -h, h
    if g.kind == 'sphere':
        r = np.full(3, g.radius)
        return -r, r
    if g.kind == 'cylinder':
        h = np.array([g.radius, g.radius, g.length / 2.0])
        return -h, h
    if g.kind == 'mesh':
        pts = []
        if g.vertices is not None and len(g.vertices):
            pts.append(np.asarray(g.vertices, float))
        for part in g.parts or []:
            if getattr(part, 'positions', None) is not None and len(part.positions):
                pts.append(np.asarray(part.positions, float))
        if pts:
            allp = np.concatenate(pts)
            return allp.min(axis=0), allp.max(axis=0)
    return None


def _box(size):
    return Geometry(kind='box', size=tuple(float(s) for s in size))


class SceneModel:
    """The world as the view knows it. `update_world(sdf)` after models come or go;
    `set_poses(link_poses, model_poses)` with the latest published poses; `shapes()` the
    visuals for Renderer.set_scene; `collisions()` for picking with a RayCaster."""

    def __init__(self):
        self.world = None
        self.sdf = ''
        self.link_poses = {}        # 'model::link' -> Pose (world)
        self.model_poses = {}       # model -> Pose (world)
        self.selected = None
        self._keys = {}
        self._models = {}           # name -> description Model (kept while its key holds)
        self._grid = self._make_grid()
        self.extra = []             # ShapeInstances the window adds (the wall tool's preview)

    # ------------------------------------------------------------- inputs
    def update_world(self, sdf_text, source='<get_world_sdf>'):
        world = parse_world(sdf_text, source)
        keys = model_keys(sdf_text)
        models = {}
        for m in world.models:
            old = self._models.get(m.name)
            if old is not None and self._keys.get(m.name) == keys.get(m.name):
                old.pose = m.pose
                models[m.name] = old
            else:
                models[m.name] = m
        world.models = [models[m.name] for m in world.models]
        self.world, self.sdf, self._keys, self._models = world, sdf_text, keys, models
        if self.selected not in models:
            self.selected = None
        return world

    def set_poses(self, link_poses=None, model_poses=None):
        if link_poses is not None:
            self.link_poses = link_poses
        if model_poses is not None:
            self.model_poses = model_poses

    def model_names(self):
        return [m.name for m in self.world.models] if self.world else []

    def model(self, name):
        return self._models.get(name)

    # ------------------------------------------------------------- poses
    def model_pose(self, name):
        p = self.model_poses.get(name)
        if p is not None:
            return p
        m = self._models.get(name)
        return m.pose if m is not None else Pose()

    def link_pose(self, model, link):
        p = self.link_poses.get('%s::%s' % (model.name, link.name))
        if p is not None:
            return p
        return self.model_pose(model.name) * link.pose

    def _pose_fn(self, model, link):
        return lambda: self.link_pose(model, link)

    # ------------------------------------------------------------- shapes
    def _make_grid(self):
        shapes = []
        n, half = GRID_CELLS, GRID_CELLS / 2.0
        length = float(GRID_CELLS)
        along_x, along_y = _box((length, GRID_LINE, 0.002)), _box((GRID_LINE, length, 0.002))
        for i in range(n + 1):
            c = -half + i
            shapes.append(ShapeInstance(key='grid::x%d' % i, model='', link='grid', geometry=along_x,
                                        static_pose=Pose((0.0, c, 0.002)), color=GRID_COLOR))
            shapes.append(ShapeInstance(key='grid::y%d' % i, model='', link='grid', geometry=along_y,
                                        static_pose=Pose((c, 0.0, 0.002)), color=GRID_COLOR))
        return shapes

    def shapes(self):
        """Visuals of every model (the selected one tinted) + the grid + the selection box."""
        out = list(self._grid) + list(self.extra)
        if self.world is None:
            return out
        for m in self.world.models:
            sel = m.name == self.selected
            for link in m.links:
                fn = self._pose_fn(m, link)
                for v in link.visuals:
                    mat = v.material
                    if sel:
                        base = mat or Material(name='selected', diffuse=tuple(v.color),
                                               specular=(0.2, 0.2, 0.2))
                        mat = Material(**{**base.__dict__, 'emissive': HIGHLIGHT_EMISSIVE})
                    out.append(ShapeInstance(key='%s::%s::%s' % (m.name, link.name, v.name),
                                             model=m.name, link=link.name, geometry=v.geometry,
                                             local=v.pose, color=tuple(v.color), link_pose=fn,
                                             material=mat))
        out += self._selection_box()
        return out

    def collisions(self):
        """Collision ShapeInstances of every model (planes left out), for picking."""
        out = []
        if self.world is None:
            return out
        for m in self.world.models:
            for link in m.links:
                fn = self._pose_fn(m, link)
                for c in link.collisions:
                    if c.geometry.kind == 'plane':
                        continue
                    out.append(ShapeInstance(key='%s::%s::%s' % (m.name, link.name, c.name),
                                             model=m.name, link=link.name, geometry=c.geometry,
                                             local=c.pose, link_pose=fn))
        return out

    def bounds(self, name, frame=None):
        """(min, max) corners of a model's visuals (collisions when it has none) now, in the
        world or in `frame` (a world Pose), or None."""
        m = self._models.get(name)
        if m is None:
            return None
        to_frame = frame.inverse() if frame is not None else Pose()
        pts = []
        for link in m.links:
            lp = to_frame * self.link_pose(m, link)
            items = [(v.geometry, v.pose) for v in link.visuals] or \
                [(c.geometry, c.pose) for c in link.collisions]
            for g, local in items:
                ext = shape_extent(g)
                if ext is None:
                    continue
                lo, hi = ext
                corners = np.array([[x, y, z] for x in (lo[0], hi[0]) for y in (lo[1], hi[1])
                                    for z in (lo[2], hi[2])])
                pts.append((lp * local).apply(corners))
        if not pts:
            return None
        allp = np.concatenate(pts)
        return allp.min(axis=0), allp.max(axis=0)

    def _selection_box(self):
        """Twelve thin orange bars on the edges of the selected model's bounding box, in the
        frame of its first link (so that the box follows the model)."""
        m = self._models.get(self.selected) if self.selected else None
        if m is None or not m.links:
            return []
        key = (id(m), self.selected)
        if getattr(self, '_sel_key', None) == key:
            return self._sel_shapes
        link = m.links[0]
        fn = self._pose_fn(m, link)
        b = self.bounds(self.selected, frame=fn())
        out = []
        if b is not None:
            lo, hi = b[0] - 0.01, b[1] + 0.01
            size, c = hi - lo, (lo + hi) / 2.0
            w = SELECT_LINE
            mat = Material(name='selection', diffuse=SELECT_COLOR, emissive=(0.6, 0.3, 0.0))
            for axis in range(3):
                dims = [w, w, w]
                dims[axis] = size[axis] + w
                g = _box(dims)
                others = [a for a in range(3) if a != axis]
                for s0 in (lo, hi):
                    for s1 in (lo, hi):
                        p = c.copy()
                        p[others[0]] = s0[others[0]]
                        p[others[1]] = s1[others[1]]
                        out.append(ShapeInstance(key='selection::%d' % len(out), model=m.name,
                                                 link='selection', geometry=g, local=Pose(p),
                                                 link_pose=fn, color=SELECT_COLOR, material=mat))
        self._sel_key, self._sel_shapes = key, out
        return out

    def lights(self):
        return list(self.world.lights) if self.world else []

    def ambient(self):
        return tuple(self.world.scene.ambient) if self.world else (0.4, 0.4, 0.4, 1.0)

    def background(self):
        return tuple(self.world.scene.background) if self.world else (0.7, 0.7, 0.7, 1.0)
