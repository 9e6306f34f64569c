"""The Insert tab's model database (as Gazebo's Insert tab lists models.gazebosim.org): a local
HTTP model database (ode_sim's test server) listed on request, and one line when the database
cannot be reached. In-process Qt (pytest-qt), offscreen when there is no display; no ROS."""
import importlib.util
import os

if not os.environ.get('DISPLAY'):
    os.environ.setdefault('QT_QPA_PLATFORM', 'offscreen')

import pytest                           # noqa: E402
from PyQt5 import QtWidgets             # noqa: E402

from ode_sim.description import modeldb                     # noqa: E402
from ode_sim.description.resolve import find_package        # noqa: E402
from ode_sim_gui.panels import MODEL_ROLE, InsertPanel     # noqa: E402

ODE_SIM_TEST = os.path.join(find_package('ode_sim'), 'test')


def model_database_server():
    spec = importlib.util.spec_from_file_location(
        'model_database_server', os.path.join(ODE_SIM_TEST, 'test_model_database.py'))
    mdb = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mdb)
    return mdb


@pytest.fixture
def env(tmp_path, monkeypatch):
    home = tmp_path / 'home'
    (home / '.gazebo' / 'models').mkdir(parents=True)
    monkeypatch.setenv('HOME', str(home))
    monkeypatch.setenv('XDG_CACHE_HOME', str(tmp_path / 'cache'))
    monkeypatch.setenv('GAZEBO_MODEL_PATH', '')
    modeldb._INDEX.clear()
    yield home
    modeldb._INDEX.clear()


def panel(qtbot):
    parent = QtWidgets.QWidget()
    qtbot.addWidget(parent)
    p = InsertPanel(parent)
    qtbot.waitUntil(lambda: bool(p.entries or p.error), timeout=60000)
    assert p.error is None and all(e.source == 'library' for e in p.entries)
    return p


def listed(p):
    return [p.list.item(i).data(MODEL_ROLE) for i in range(p.list.count())
            if p.list.item(i).data(MODEL_ROLE) is not None]


def test_the_model_database_is_listed_on_request(qtbot, env, monkeypatch):
    mdb = model_database_server()
    db = mdb.Database({'database.config': mdb.config('step_block', 'prism'),
                       'step_block/model.tar.gz': mdb.tarball('step_block'),
                       'prism/model.tar.gz': mdb.tarball('prism')})
    try:
        monkeypatch.setenv('GAZEBO_MODEL_DATABASE_URI', db.uri)
        p = panel(qtbot)
        local = len(p.entries)
        p.btn_database.click()
        qtbot.waitUntil(lambda: p.status.text().startswith('model database: 2 '), timeout=60000)
        remote = [e for e in listed(p) if e.source == 'database']
        assert [(e.name, e.uri) for e in remote] == [
            ('prism', 'model://prism'), ('step_block', 'model://step_block')]
        assert len(listed(p)) == local + 2 and p.btn_database.isEnabled()
        # listed only: nothing downloaded until a model is inserted
        assert not os.path.exists(os.path.join(str(env), '.gazebo', 'models', 'prism'))
        assert db.requests and all('tar.gz' not in r for r in db.requests)
    finally:
        db.close()


def test_an_unreachable_database_is_one_line(qtbot, env, monkeypatch):
    monkeypatch.setenv('GAZEBO_MODEL_DATABASE_URI', 'http://127.0.0.1:9/')   # refused
    p = panel(qtbot)
    local = len(p.entries)
    p.btn_database.click()
    qtbot.waitUntil(lambda: p.btn_database.isEnabled() and 'cannot be reached' in p.status.text(),
                    timeout=60000)
    assert '\n' not in p.status.text() and p.status.text().startswith('model database: ')
    assert len(listed(p)) == local            # the local models stay


def test_no_thumbnail_download_for_database_entries(qtbot, env, monkeypatch):
    """Drawing a database entry's thumbnail would download it: the entry has none until then."""
    mdb = model_database_server()
    db = mdb.Database({'database.config': mdb.config('prism'),
                       'prism/model.tar.gz': mdb.tarball('prism')})
    try:
        monkeypatch.setenv('GAZEBO_MODEL_DATABASE_URI', db.uri)
        p = panel(qtbot)
        p.btn_database.click()
        qtbot.waitUntil(lambda: p.status.text().startswith('model database: 1 '), timeout=60000)
        item = [p.list.item(i) for i in range(p.list.count())
                if p.list.item(i).data(MODEL_ROLE) is not None
                and p.list.item(i).data(MODEL_ROLE).source == 'database'][0]
        assert item.icon().isNull() and 'downloaded when inserted' in item.toolTip()
    finally:
        db.close()
