"""model:// as gzserver resolves it: GAZEBO_MODEL_PATH, ~/.gazebo/models, the model library, then
the model database (GAZEBO_MODEL_DATABASE_URI: database.config, NAME/model.tar.gz) downloaded
once into ~/.gazebo/models. The database is served from 127.0.0.1 by the test, HOME is a temp
folder: nothing touches the real ~/.gazebo or the internet."""
import http.server
import io
import os
import shutil
import socket
import tarfile
import threading

import pytest

from ode_sim.description import modeldb, sdf
from ode_sim.description.model import ModelError
from ode_sim.description.resolve import ModelPaths, model_sdf_file

HERE = os.path.dirname(os.path.abspath(__file__))
MODELS = os.path.join(HERE, 'fixtures', 'gazebo_models')


def tarball(name, top=True):
    buf = io.BytesIO()
    with tarfile.open(fileobj=buf, mode='w:gz') as tar:
        src = os.path.join(MODELS, name)
        if top:
            tar.add(src, arcname=name)
        else:
            for entry in os.listdir(src):
                tar.add(os.path.join(src, entry), arcname=entry)
    return buf.getvalue()


class Database:
    """An HTTP model database on 127.0.0.1 serving `files` (path -> bytes); counts requests."""

    def __init__(self, files):
        self.files, self.requests = files, []
        db = self

        class Handler(http.server.BaseHTTPRequestHandler):
            def do_GET(self):
                db.requests.append(self.path)
                data = db.files.get(self.path.lstrip('/'))
                if data is None:
                    self.send_error(404)
                    return
                self.send_response(200)
                self.send_header('Content-Length', str(len(data)))
                self.end_headers()
                self.wfile.write(data)

            def log_message(self, *args):
                pass

        self.server = http.server.ThreadingHTTPServer(('127.0.0.1', 0), Handler)
        self.uri = 'http://127.0.0.1:%d' % self.server.server_address[1]
        self.thread = threading.Thread(target=self.server.serve_forever, daemon=True)
        self.thread.start()

    def close(self):
        self.server.shutdown()
        self.server.server_close()


def config(*names):
    uris = ''.join('<uri>file://%s</uri>' % n for n in names)
    return ('<?xml version="1.0"?><database><name>gazebo_models</name><license>CC-BY 3.0'
            '</license><version>1.0</version><models>%s</models></database>' % uris).encode()


@pytest.fixture(autouse=True)
def fresh_index():
    modeldb._INDEX.clear()
    yield
    modeldb._INDEX.clear()


@pytest.fixture
def home(tmp_path):
    h = tmp_path / 'home'
    h.mkdir()
    return str(h)


@pytest.fixture
def database():
    db = Database({'database.config': config('step_block', 'prism', 'broken', 'flat'),
                   'step_block/model.tar.gz': tarball('step_block'),
                   'prism/model.tar.gz': tarball('prism'),
                   'flat/model.tar.gz': tarball('prism', top=False),
                   'broken/model.tar.gz': tarball('prism')[:300]})
    yield db
    db.close()


def closed_port():
    s = socket.socket()
    s.bind(('127.0.0.1', 0))
    port = s.getsockname()[1]
    s.close()
    return port


def paths(home, uri, model_path=''):
    return ModelPaths(env={'HOME': home, 'GAZEBO_MODEL_PATH': model_path,
                           'GAZEBO_MODEL_DATABASE_URI': uri}, library='')


def load(p, name='step_block'):
    return sdf.parse_world('<sdf version="1.6"><world name="w"><include><uri>model://%s</uri>'
                           '</include></world></sdf>' % name, os.path.join(HERE, 'w.world'),
                           paths=p)


def test_downloaded_once_into_dot_gazebo_models(home, database, capfd):
    w = load(paths(home, database.uri))
    dest = os.path.join(home, '.gazebo', 'models', 'step_block')
    assert os.path.isfile(os.path.join(dest, 'meshes', 'step_block.dae'))
    assert os.path.isfile(os.path.join(dest, 'materials', 'textures', 'split.png'))
    g = w.models[0].links[0].collisions[0].geometry
    assert g.filename == os.path.join(dest, 'meshes', 'step_block.dae') and len(g.faces) == 24
    err = capfd.readouterr().err
    assert 'model://step_block: downloading %s/step_block/model.tar.gz' % database.uri in err
    assert 'unpacked into %s' % dest in err
    assert database.requests == ['/database.config', '/step_block/model.tar.gz']
    # a second world, a new lookup: found in ~/.gazebo/models, the database is not asked
    modeldb._INDEX.clear()
    load(paths(home, database.uri))
    assert len(database.requests) == 2
    assert not [n for n in os.listdir(os.path.join(home, '.gazebo', 'models'))
                if n.startswith('.')], 'no temp folder left behind'


def test_archive_without_top_folder(home, database):
    d = paths(home, database.uri).model_dir('flat')
    assert d == os.path.join(home, '.gazebo', 'models', 'flat')
    assert os.path.isfile(os.path.join(d, 'meshes', 'prism.obj'))


def test_local_models_win_and_need_no_database(home, tmp_path):
    offline = 'http://127.0.0.1:%d' % closed_port()
    # a model cloned into a folder on GAZEBO_MODEL_PATH, unchanged
    clone = tmp_path / 'clone'
    shutil.copytree(os.path.join(MODELS, 'prism'), str(clone / 'prism'))
    w = load(paths(home, offline, str(clone)), 'prism')
    assert w.models[0].links[0].collisions[0].geometry.filename.startswith(str(clone))
    # a model copied into ~/.gazebo/models
    shutil.copytree(os.path.join(MODELS, 'step_block'),
                    os.path.join(home, '.gazebo', 'models', 'step_block'))
    w = load(paths(home, offline))
    assert w.models[0].name == 'step_block'


def test_offline_is_one_clear_line(home):
    uri = 'http://127.0.0.1:%d' % closed_port()
    with pytest.raises(ModelError) as e:
        load(paths(home, uri), 'gas_station')
    msg = str(e.value)
    assert '\n' not in msg
    assert 'model://gas_station: not found in GAZEBO_MODEL_PATH' in msg
    assert 'and the model database %s/ cannot be reached: ' % uri in msg
    assert os.path.join(home, '.gazebo', 'models') in msg


def test_not_in_the_database(home, database):
    with pytest.raises(ModelError) as e:
        paths(home, database.uri).model_dir('gas_station')
    assert 'nor in the model database %s/ (its database.config lists 4 models)' \
        % database.uri in str(e.value)


def test_broken_archive(home, database):
    with pytest.raises(ModelError) as e:
        paths(home, database.uri).model_dir('broken')
    msg = str(e.value)
    assert 'has it but the download failed' in msg and 'broken/model.tar.gz' in msg
    assert '\n' not in msg
    assert not os.path.exists(os.path.join(home, '.gazebo', 'models', 'broken'))


def test_no_database_when_uri_empty(home):
    with pytest.raises(ModelError, match='no model database'):
        paths(home, '').model_dir('gas_station')


def test_sdf_version_choice_as_gazebo(tmp_path):
    d = tmp_path / 'm'
    d.mkdir()
    for f in ('model-1_4.sdf', 'model-1_6.sdf', 'model.sdf'):
        (d / f).write_text('<sdf/>')
    (d / 'model.config').write_text(
        '<model><sdf version="1.4">model-1_4.sdf</sdf><sdf version="1.7">model.sdf</sdf>'
        '<sdf version="1.6">model-1_6.sdf</sdf></model>')
    assert model_sdf_file(str(d)) == str(d / 'model-1_6.sdf')
    (d / 'model.config').write_text('<model><sdf version="1.8">model.sdf</sdf>'
                                    '<sdf version="1.9">model-1_4.sdf</sdf></model>')
    assert model_sdf_file(str(d)) == str(d / 'model.sdf')      # none readable: the first


def test_archive_escaping_its_folder_is_refused(home):
    buf = io.BytesIO()
    with tarfile.open(fileobj=buf, mode='w:gz') as tar:
        data = b'owned'
        info = tarfile.TarInfo('../evil.txt')
        info.size = len(data)
        tar.addfile(info, io.BytesIO(data))
    db = Database({'database.config': config('evil'), 'evil/model.tar.gz': buf.getvalue()})
    try:
        with pytest.raises(ModelError, match="refusing the member '../evil.txt'"):
            paths(home, db.uri).model_dir('evil')
    finally:
        db.close()
    assert not os.path.exists(os.path.join(home, '.gazebo', 'evil.txt'))
