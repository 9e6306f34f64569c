"""Gazebo's online model database, as gzserver uses it (gazebo/common/ModelDatabase).

A model that `model://NAME` does not find in GAZEBO_MODEL_PATH, ~/.gazebo/models or the model
library is looked up in the database at GAZEBO_MODEL_DATABASE_URI (default Gazebo's
http://models.gazebosim.org/): its `database.config` lists the models (`<database><models>
<uri>file://NAME</uri>...`), `URI/NAME/model.tar.gz` is the model, a tarball of the folder NAME
(model.config, model.sdf, meshes/, materials/ ...). It is downloaded once, with a progress line,
and unpacked into ~/.gazebo/models, where every later lookup finds it. The index is read once
per process and database; a database that cannot be reached gives one line saying so, and is
not asked again in this process.
"""
import io
import os
import shutil
import sys
import tarfile
import tempfile
import urllib.error
import urllib.request
import xml.etree.ElementTree as ET

DEFAULT_URI = 'http://models.gazebosim.org/'
TIMEOUT = 30.0                  # seconds per request (connect and every read)


class DatabaseError(Exception):
    """The one line of what went wrong with the database (the caller names the model)."""


def _stderr(line, end='\n'):
    sys.stderr.write(line + end)
    sys.stderr.flush()


_INDEX = {}     # uri -> list of model names, or DatabaseError (unreachable: not asked again)


class ModelDatabase:
    def __init__(self, uri, cache_dir, timeout=TIMEOUT, progress=None):
        self.uri = uri.rstrip('/') + '/'
        self.cache_dir = cache_dir
        self.timeout = float(timeout)
        self.progress = progress or _stderr

    def _open(self, url):
        try:
            return urllib.request.urlopen(url, timeout=self.timeout)
        except urllib.error.HTTPError as e:
            raise DatabaseError('%s: HTTP %d %s' % (url, e.code, e.reason)) from None
        except urllib.error.URLError as e:
            raise DatabaseError('%s' % (getattr(e, 'reason', e),)) from None
        except (OSError, ValueError) as e:       # timeouts, bad URLs
            raise DatabaseError('%s' % (e,)) from None

    def models(self):
        """Names listed by the database's database.config (read once per process)."""
        hit = _INDEX.get(self.uri)
        if isinstance(hit, DatabaseError):
            raise hit
        if hit is not None:
            return hit
        url = self.uri + 'database.config'
        try:
            with self._open(url) as r:
                data = r.read()
            try:
                root = ET.fromstring(data)
            except ET.ParseError as e:
                raise DatabaseError('%s is not a database.config: %s' % (url, e)) from None
            if root.tag != 'database':
                raise DatabaseError('%s is not a database.config: root <%s>, expected '
                                    '<database>' % (url, root.tag))
            names = []
            for u in root.iter('uri'):
                t = (u.text or '').strip()
                if t.startswith('file://'):
                    t = t[len('file://'):]
                t = t.strip('/')
                if t:
                    names.append(t)
        except DatabaseError as e:
            _INDEX[self.uri] = e
            raise
        except OSError as e:               # a timeout while reading
            err = DatabaseError(str(e))
            _INDEX[self.uri] = err
            raise err from None
        _INDEX[self.uri] = names
        return names

    def fetch(self, name):
        """Download model `name` into cache_dir/name (once) and return that directory."""
        dest = os.path.join(self.cache_dir, name)
        if os.path.isdir(dest):
            return dest
        url = '%s%s/model.tar.gz' % (self.uri, name)
        self.progress('model://%s: downloading %s into %s ...' % (name, url, self.cache_dir))
        buf = io.BytesIO()
        try:
            with self._open(url) as r:
                total = int(r.headers.get('Content-Length') or 0)
                while True:
                    chunk = r.read(1 << 16)
                    if not chunk:
                        break
                    buf.write(chunk)
                    if total and sys.stderr.isatty():
                        self.progress('\r  %d / %d kB' % (buf.tell() // 1024, total // 1024),
                                      end='')
        except OSError as e:
            raise DatabaseError('%s: %s' % (url, e)) from None
        os.makedirs(self.cache_dir, exist_ok=True)
        tmp = tempfile.mkdtemp(prefix='.%s-' % name, dir=self.cache_dir)
        try:
            root = _unpack(buf.getvalue(), tmp, url, name)
            try:
                os.rename(root, dest)
            except OSError:
                if not os.path.isdir(dest):    # else: another process was first
                    raise
        finally:
            shutil.rmtree(tmp, ignore_errors=True)
        self.progress('model://%s: %d kB, unpacked into %s' % (name, buf.tell() // 1024, dest))
        return dest


def _unpack(data, tmp, url, name):
    """Unpack a model.tar.gz into tmp; the model's folder (NAME/ inside, or the top)."""
    try:
        tar = tarfile.open(fileobj=io.BytesIO(data), mode='r:*')
    except (tarfile.TarError, EOFError, OSError) as e:
        raise DatabaseError('%s is not a model archive (a tar.gz): %s' % (url, e)) from None
    with tar:
        try:
            members = tar.getmembers()
        except (tarfile.TarError, EOFError, OSError) as e:
            raise DatabaseError('%s is truncated or broken: %s' % (url, e)) from None
        safe = []
        for m in members:
            parts = m.name.replace('\\', '/').split('/')
            if m.name.startswith('/') or '..' in parts:
                raise DatabaseError('%s: refusing the member %r (outside the model folder)'
                                    % (url, m.name))
            if m.isfile() or m.isdir():          # no links, devices
                safe.append(m)
        try:
            for m in safe:
                tar.extract(m, tmp, set_attrs=False)
        except (tarfile.TarError, EOFError, OSError) as e:
            raise DatabaseError('%s is truncated or broken: %s' % (url, e)) from None
    for cand in (os.path.join(tmp, name), tmp):
        if os.path.isfile(os.path.join(cand, 'model.config')) or \
                os.path.isfile(os.path.join(cand, 'model.sdf')):
            if cand == tmp:                      # files at the top: move them to a folder
                inner = os.path.join(tmp, '.' + name)
                os.mkdir(inner)
                for entry in os.listdir(tmp):
                    if entry != '.' + name:
                        shutil.move(os.path.join(tmp, entry), inner)
                return inner
            return cand
    tops = sorted(os.listdir(tmp))
    raise DatabaseError('%s has no %s/model.config (it holds: %s)'
                        % (url, name, ', '.join(tops) or 'nothing'))
