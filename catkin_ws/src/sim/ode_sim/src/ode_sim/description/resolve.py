"""Where files named in worlds and robots are: `model://`, `package://`, `file://` URIs, plain
paths, and world names such as `worlds/empty.world`.

Lookup order for `model://NAME` (as gzserver with gazebo_ros): the directories given as `extra`,
then the GAZEBO_MODEL_PATH entries (colon separated), ~/.gazebo/models, ode_sim's own model
library `<ode_sim package>/models`, then Gazebo's model database (GAZEBO_MODEL_DATABASE_URI,
modeldb.py: downloaded once into ~/.gazebo/models). World files: the path itself, then
GAZEBO_RESOURCE_PATH entries, then the ode_sim package directory (so `worlds/empty.world` is
ode_sim's `worlds/empty.world`).
"""
import os
import xml.etree.ElementTree as ET

from ode_sim.description import modeldb
from ode_sim.description.model import ModelError

_PKG_DIR_CACHE = []


def package_dir():
    """The ode_sim package directory (catkin_ws/src/sim/ode_sim in a source checkout)."""
    if _PKG_DIR_CACHE:
        return _PKG_DIR_CACHE[0]
    here = os.path.dirname(os.path.abspath(__file__))
    candidate = os.path.dirname(os.path.dirname(os.path.dirname(here)))   # src/ode_sim/description
    found = None
    if os.path.isfile(os.path.join(candidate, 'package.xml')):
        found = candidate
    else:
        try:
            import rospkg
            found = rospkg.RosPack().get_path('ode_sim')
        except Exception:  # rospkg missing or ode_sim not on ROS_PACKAGE_PATH
            found = candidate
    _PKG_DIR_CACHE.append(found)
    return found


def _split_path(value):
    return [p for p in (value or '').split(os.pathsep) if p.strip()]


_PACKAGES = {}
_ROSPACK = []


def find_package(name):
    """Directory of ROS package `name` (rospkg, cached), or ModelError."""
    hit = _PACKAGES.get(name)
    if hit is not None:
        return hit
    try:
        import rospkg
    except ImportError:
        raise ModelError('package://%s: rospkg is not available to find ROS packages' % name)
    if not _ROSPACK:
        _ROSPACK.append(rospkg.RosPack())
    try:
        path = _ROSPACK[0].get_path(name)
    except rospkg.ResourceNotFound:
        raise ModelError('package://%s: ROS package %r not found (ROS_PACKAGE_PATH=%s)'
                         % (name, name, os.environ.get('ROS_PACKAGE_PATH', '')))
    _PACKAGES[name] = path
    return path


def _version_key(text):
    out = []
    for part in (text or '0').split('.'):
        try:
            out.append(int(part))
        except ValueError:
            out.append(0)
    return tuple(out)


class ModelPaths:
    """model:// lookup, in gzserver's (and gazebo_ros spawn_model's) order: `extra` (list or
    colon separated string), GAZEBO_MODEL_PATH, ~/.gazebo/models, this package's models/,
    then the model database (`database`: a URI, default GAZEBO_MODEL_DATABASE_URI or Gazebo's;
    '' for none; a model found there is downloaded into ~/.gazebo/models).
    The one model lookup: gazebo_ros's spawn_model -database uses it too. `env` (default
    os.environ) and `library` (default this package's models/; '' for none) are injectable."""

    def __init__(self, extra=None, env=None, library=None, database=None):
        env = os.environ if env is None else env
        if isinstance(extra, str):
            extra = _split_path(extra)
        self.extra = [os.path.abspath(os.path.expanduser(p)) for p in (extra or [])]
        self.env = [os.path.abspath(os.path.expanduser(p))
                    for p in _split_path(env.get('GAZEBO_MODEL_PATH', ''))]
        home = env.get('HOME')
        self.cache = os.path.join(home, '.gazebo', 'models') if home else ''
        if home:
            self.env.append(self.cache)
        self.library = os.path.join(package_dir(), 'models') if library is None else library
        if database is None:
            database = env.get('GAZEBO_MODEL_DATABASE_URI', modeldb.DEFAULT_URI)
        self.database = (database or '').strip()

    @classmethod
    def only(cls, roots):
        """A lookup in exactly these directories, in this order."""
        return cls(roots, env={}, library='', database='')

    @property
    def roots(self):
        seen, out = set(), []
        for p in self.extra + self.env + ([self.library] if self.library else []):
            if p not in seen:
                seen.add(p)
                out.append(p)
        return out

    def find_model_dir(self, name):
        """Directory of model `name` in the first root that has it, else None."""
        name = name.strip('/')
        for root in self.roots:
            d = os.path.join(root, name)
            if os.path.isdir(d):
                return d
        return None

    def model_dir(self, name):
        """Directory of model `name`: found locally, else downloaded from the model database;
        else ModelError naming the searched directories and what the database said."""
        d = self.find_model_dir(name)
        if d is not None:
            return d
        name = name.strip('/')
        where = 'model://%s: not found in GAZEBO_MODEL_PATH, ~/.gazebo/models and the model ' \
                'library (searched: %s)' % (name, ', '.join(self.roots) or 'nothing')
        if not self.database:
            raise ModelError(where + '; no model database (GAZEBO_MODEL_DATABASE_URI is empty)')
        if not self.cache:
            raise ModelError(where + '; HOME is not set, so the model database %s cannot be '
                             'used (it downloads into ~/.gazebo/models)' % self.database)
        db = modeldb.ModelDatabase(self.database, self.cache)
        try:
            names = db.models()
        except modeldb.DatabaseError as e:
            raise ModelError('%s and the model database %s cannot be reached: %s'
                             % (where, db.uri, e)) from None
        if name not in names:
            raise ModelError('%s nor in the model database %s (its database.config lists %d '
                             'models)' % (where, db.uri, len(names)))
        try:
            return db.fetch(name)
        except modeldb.DatabaseError as e:
            raise ModelError('%s; the model database %s has it but the download failed: %s'
                             % (where, db.uri, e)) from None

    def model_sdf(self, name):
        """The SDF file of model `name` (model_sdf_file of its directory)."""
        return model_sdf_file(self.model_dir(name))

    def resolve_uri(self, uri, base_dir=None):
        """Absolute path of an existing file or directory named by `uri`: model://NAME/...,
        package://PKG/..., file://PATH, an absolute path or one relative to `base_dir`."""
        uri = (uri or '').strip()
        if not uri:
            raise ModelError('empty URI')
        base_dir = base_dir or os.getcwd()
        searched = []
        if uri.startswith('model://'):
            rest = uri[len('model://'):]
            name, _, sub = rest.partition('/')
            d = self.model_dir(name)
            path = os.path.join(d, sub) if sub else d
            searched.append(path)
        elif uri.startswith('package://'):
            rest = uri[len('package://'):]
            pkg, _, sub = rest.partition('/')
            path = os.path.join(find_package(pkg), sub)
            searched.append(path)
        else:
            p = uri[len('file://'):] if uri.startswith('file://') else uri
            p = os.path.expanduser(p)
            if os.path.isabs(p):
                searched.append(p)
            else:
                searched.append(os.path.join(base_dir, p))
                # Gazebo also looks relative to the model path entries
                for root in self.roots:
                    searched.append(os.path.join(root, p))
        for path in searched:
            if os.path.exists(path):
                return os.path.abspath(path)
        raise ModelError('%s: file not found (searched: %s)' % (uri, ', '.join(searched)))

    def resolve_world(self, name):
        """Path of world file `name`: the path itself, else GAZEBO_RESOURCE_PATH entries, else
        the ode_sim package directory."""
        name = (name or '').strip()
        if not name:
            raise ModelError('empty world file name')
        if name.startswith('file://'):
            name = name[len('file://'):]
        name = os.path.expanduser(name)
        searched = [os.path.abspath(name)]
        if not os.path.isabs(name):
            for root in _split_path(os.environ.get('GAZEBO_RESOURCE_PATH', '')):
                searched.append(os.path.join(os.path.abspath(os.path.expanduser(root)), name))
            searched.append(os.path.join(package_dir(), name))
        for path in searched:
            if os.path.isfile(path):
                return path
        raise ModelError('world %s: file not found (searched: %s)' % (name, ', '.join(searched)))


SDF_PARSER_VERSION = (1, 6)      # the newest SDF version the description layer reads


def model_sdf_file(model_dir):
    """The SDF file of a model directory, chosen from model.config as Gazebo does: the <sdf>
    with the highest version that the parser reads (<= SDF_PARSER_VERSION), else the first
    <sdf>; model.sdf when model.config names none. ModelError when model.config is broken
    or names a missing file."""
    config = os.path.join(model_dir, 'model.config')
    if os.path.isfile(config):
        try:
            root = ET.parse(config).getroot()
        except ET.ParseError as e:
            raise ModelError('%s: malformed XML: %s' % (config, e))
        best = first = None
        for el in root.findall('sdf'):
            fname = (el.text or '').strip()
            if not fname:
                continue
            if first is None:
                first = ((0,), fname)
            key = _version_key(el.get('version'))
            if key <= SDF_PARSER_VERSION and (best is None or key > best[0]):
                best = (key, fname)
        best = best or first
        if best is not None:
            path = os.path.join(model_dir, best[1])
            if not os.path.isfile(path):
                raise ModelError('%s: <sdf> names %s, which does not exist' % (config, path))
            return path
    path = os.path.join(model_dir, 'model.sdf')
    if not os.path.isfile(path):
        raise ModelError('%s: no model.sdf and no <sdf> in model.config' % model_dir)
    return path


def resolve_uri(uri, base_dir=None, paths=None):
    return (paths or ModelPaths()).resolve_uri(uri, base_dir)


def resolve_world(name, paths=None):
    return (paths or ModelPaths()).resolve_world(name)
