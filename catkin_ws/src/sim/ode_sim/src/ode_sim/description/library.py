"""The Insert tab's model list (gzclient's Insert: the model paths and the model database) and
each model's thumbnail, rendered by the simulator's own OpenGL renderer (the one the cameras
use). ROS-free: the desktop window (ode_sim_gui) and course_web's HTTP server import it.

  list_models()      -> [ModelEntry(name, uri, path, source, title)], sorted by source then name
  thumbnail(entry)   -> path of a PNG, cached under ~/.cache/ode_sim/thumbnails (or
                        $XDG_CACHE_HOME/ode_sim/thumbnails), keyed by the model's modification
                        time (its folder, model.config and SDF file): rendered once per change

Sources, in the order they are listed: 'library' (this package's models/), 'GAZEBO_MODEL_PATH'
(each of its folders), '~/.gazebo/models' (where the model database's downloads go), then
'database' (Gazebo's model database, GAZEBO_MODEL_DATABASE_URI, only with
list_models(database=True): it needs the network; its thumbnail downloads the model first, as
inserting it does). A model is a folder with a model.config (Gazebo's rule); a folder that is on
several of the paths is listed once, under its first source.
"""
import math
import os
import tempfile
import threading
import xml.etree.ElementTree as ET
from dataclasses import dataclass

import numpy as np

from ode_sim.description.model import Geometry, Light, ModelError, Visual
from ode_sim.description.resolve import ModelPaths, model_sdf_file, package_dir
from ode_sim.description.transforms import Pose

SOURCES = ('library', 'GAZEBO_MODEL_PATH', '~/.gazebo/models', 'database')
BACKGROUND = (0.86, 0.87, 0.9, 1.0)
HFOV = 0.7


@dataclass(frozen=True)
class ModelEntry:
    name: str           # folder name: model://NAME
    uri: str            # 'model://NAME'
    path: str           # the model's folder ('' for a database model not downloaded yet)
    source: str         # one of SOURCES
    title: str = ''     # model.config <name> (the name shown in Gazebo's Insert tab)


def _title(folder):
    try:
        return (ET.parse(os.path.join(folder, 'model.config')).getroot().findtext('name')
                or '').strip()
    except (ET.ParseError, OSError):
        return ''


def _models_in(root):
    """(name, folder) of every model folder (with a model.config) directly in `root`."""
    try:
        names = sorted(os.listdir(root))
    except OSError:
        return []
    return [(n, os.path.join(root, n)) for n in names
            if os.path.isfile(os.path.join(root, n, 'model.config'))]


def list_models(env=None, database=False, library=None):
    """Every model the Insert tab offers, sorted by source (SOURCES order) then name.
    env: the environment (default os.environ: GAZEBO_MODEL_PATH, HOME,
    GAZEBO_MODEL_DATABASE_URI); library: the model library folder (default this package's
    models/). database=True adds the model database's models not found locally (network;
    a database that cannot be reached raises ModelError with the reason)."""
    env = os.environ if env is None else env
    library = os.path.join(package_dir(), 'models') if library is None else library
    paths = ModelPaths(env=env, library=library)
    home = env.get('HOME')
    cache = os.path.join(home, '.gazebo', 'models') if home else ''
    gmp = [p for p in paths.env if p != cache]
    roots = [('library', library)] + [('GAZEBO_MODEL_PATH', p) for p in gmp] + \
        ([('~/.gazebo/models', cache)] if cache else [])
    seen, names, out = set(), set(), []
    for source, root in roots:
        if not root:
            continue
        for name, folder in _models_in(root):
            real = os.path.realpath(folder)
            if real in seen:
                continue
            seen.add(real)
            names.add(name)
            out.append(ModelEntry(name, 'model://' + name, folder, source, _title(folder)))
    if database and paths.database:
        from ode_sim.description import modeldb
        db = modeldb.ModelDatabase(paths.database, cache or tempfile.gettempdir())
        try:
            remote = db.models()
        except modeldb.DatabaseError as e:
            raise ModelError('the model database %s cannot be reached: %s' % (db.uri, e)) \
                from None
        for name in sorted(set(remote) - names):
            out.append(ModelEntry(name, 'model://' + name, '', 'database', name))
    order = {s: i for i, s in enumerate(SOURCES)}
    out.sort(key=lambda e: (order[e.source], e.name))
    return out


# ------------------------------------------------------------------------------------------
# thumbnails

def cache_dir(env=None):
    env = os.environ if env is None else env
    home = env.get('HOME') or tempfile.gettempdir()
    base = env.get('XDG_CACHE_HOME') or os.path.join(home, '.cache')
    return os.path.join(base, 'ode_sim', 'thumbnails')


def _model_folder(entry, env=None):
    """The entry's folder; a database model is downloaded first (as inserting it would)."""
    if entry.path:
        return entry.path
    return ModelPaths(env=env).model_dir(entry.name)


def _stamp(folder):
    """Modification time of the model: its folder, model.config and SDF file (ns)."""
    files = [folder, os.path.join(folder, 'model.config')]
    try:
        files.append(model_sdf_file(folder))
    except ModelError:
        pass
    return max(os.stat(f).st_mtime_ns for f in files if os.path.exists(f))


def thumbnail_file(entry, size, folder, env=None):
    safe = ''.join(c if c.isalnum() or c in '-_.' else '_' for c in entry.source + '-' + entry.name)
    return os.path.join(cache_dir(env), '%s-%d-%d.png' % (safe, int(size), _stamp(folder)))


def thumbnail(entry, size=128, env=None):
    """Path of a size x size PNG of the model (rendered on first use, then cached). A model
    that does not load raises ModelError with the loader's one line."""
    size = int(size)
    if size <= 0:
        raise ModelError('thumbnail size must be positive, got %d' % size)
    folder = _model_folder(entry, env)
    path = thumbnail_file(entry, size, folder, env)
    if os.path.isfile(path):
        return path
    rgb = render_model(folder, size, env)
    os.makedirs(os.path.dirname(path), exist_ok=True)
    from PIL import Image
    fd, tmp = tempfile.mkstemp(suffix='.png', dir=os.path.dirname(path))
    os.close(fd)
    try:
        Image.fromarray(rgb).save(tmp, 'PNG')
        os.chmod(tmp, 0o644)
        os.replace(tmp, path)          # atomic: a concurrent reader sees all or nothing
    finally:
        if os.path.exists(tmp):
            os.unlink(tmp)
    return path


def model_shapes(folder, env=None):
    """(ShapeInstances of the model's visuals at its own pose, lights of a light model) of a
    model folder: what the renderer draws for its thumbnail. Its model:// URIs are looked up
    beside the folder first, then as sim_node looks them up (env: the environment)."""
    from ode_sim.description import sdf
    from ode_sim.engine.scene import ShapeInstance
    path = model_sdf_file(folder)
    with open(path, 'rb') as f:
        text = f.read()
    paths = ModelPaths(extra=[os.path.dirname(os.path.abspath(folder))], env=env)
    light = sdf.parse_sdf_light(text, path, paths)
    if light is not None:
        # a light model (model://sun): a small lamp of the light's colour
        v = Visual('lamp', Geometry('sphere', radius=0.1), color=tuple(light.diffuse))
        return [ShapeInstance(key='light::lamp', model='light', link='lamp',
                              geometry=v.geometry, color=v.color)], []
    desc = sdf.parse_sdf_model(text, path, paths)
    shapes = []
    for link in desc.links:
        base = desc.pose * link.pose
        for v in link.visuals:
            shapes.append(ShapeInstance(key='%s::%s::%s' % (desc.name, link.name, v.name),
                                        model=desc.name, link=link.name, geometry=v.geometry,
                                        local=v.pose, color=tuple(v.color), static_pose=base,
                                        material=v.material))
    return shapes, []


def _corners(g):
    """Local bounding box corners of a geometry (8 x 3)."""
    if g.kind == 'box':
        h = np.asarray(g.size, dtype=float) / 2
    elif g.kind == 'sphere':
        h = np.full(3, g.radius)
    elif g.kind == 'cylinder':
        h = np.array([g.radius, g.radius, g.length / 2])
    elif g.kind == 'plane':
        h = np.array([g.plane_size[0] / 2, g.plane_size[1] / 2, 0.0])
    elif g.kind == 'mesh' and g.vertices is not None and len(g.vertices):
        lo, hi = g.vertices.min(axis=0), g.vertices.max(axis=0)
        return np.array([[x, y, z] for x in (lo[0], hi[0]) for y in (lo[1], hi[1])
                         for z in (lo[2], hi[2])])
    else:
        h = np.full(3, 0.1)
    return np.array([[x, y, z] for x in (-h[0], h[0]) for y in (-h[1], h[1])
                     for z in (-h[2], h[2])])


def camera_for(shapes, hfov=HFOV):
    """A camera pose (Gazebo's camera frame: looks along +X, Z up) that sees every shape from
    the front right and above, as Gazebo's Insert thumbnails look at a model."""
    pts = [s.world_pose().apply(_corners(s.geometry)) for s in shapes]
    pts = np.vstack(pts) if pts else np.zeros((1, 3))
    lo, hi = pts.min(axis=0), pts.max(axis=0)
    center = (lo + hi) / 2
    radius = max(float(np.linalg.norm(hi - lo)) / 2, 0.05)
    view = np.array([-1.0, -0.8, -0.7])           # from front right, above
    view /= np.linalg.norm(view)
    dist = radius / math.sin(hfov / 2) * 1.05
    eye = center - view * dist
    x = view
    y = np.cross([0.0, 0.0, 1.0], x)
    y /= np.linalg.norm(y)
    z = np.cross(x, y)
    m = np.eye(4)
    m[:3, 0], m[:3, 1], m[:3, 2], m[:3, 3] = x, y, z, eye
    return Pose.from_matrix(m), dist + radius


_RENDERERS = {}
_LOCK = threading.Lock()


def render_model(folder, size=128, env=None):
    """RGB uint8 (size, size, 3) of the model in `folder`."""
    from ode_sim.engine.render import Renderer
    shapes, lights = model_shapes(folder, env)
    pose, far = camera_for(shapes)
    sun = Light('thumbnail_sun', type='directional', diffuse=(0.8, 0.8, 0.8, 1.0),
                specular=(0.2, 0.2, 0.2, 1.0), direction=(-0.4, 0.5, -0.8))
    with _LOCK:
        r = _RENDERERS.get(size)
        if r is None or r.far < far:
            if r is not None:
                r.release()
            r = _RENDERERS[size] = Renderer(size, size, HFOV, near=0.01, far=max(far * 2, 10.0))
        r.set_scene(shapes, [sun] + list(lights), ambient=(0.5, 0.5, 0.5, 1.0),
                    background=BACKGROUND)
        rgb, _ = r.render(pose)
        r.set_scene([])
    return rgb
