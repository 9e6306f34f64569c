"""ode_sim.description.library (the Insert tab's model list and thumbnails rendered by the
simulator's renderer) and ode_sim.description.walls (the wall tool's model); no ROS."""
import math
import os
import shutil

import numpy as np
import pytest
from PIL import Image

from ode_sim.description import library, sdf, walls
from ode_sim.description.model import ModelError
from ode_sim.description.resolve import package_dir
from ode_sim.engine.physics import PhysicsWorld

HERE = os.path.dirname(os.path.abspath(__file__))
GAZEBO_MODELS = os.path.join(HERE, 'fixtures', 'gazebo_models')
LOADER_MODELS = os.path.join(HERE, 'fixtures', 'loaders', 'models')
LIBRARY = os.path.join(package_dir(), 'models')


@pytest.fixture
def env(tmp_path):
    """GAZEBO_MODEL_PATH: the Gazebo-style fixtures and the loader fixtures; HOME with one
    downloaded model and a folder without model.config; a cache of this test's own."""
    home = tmp_path / 'home'
    cached = home / '.gazebo' / 'models'
    cached.mkdir(parents=True)
    shutil.copytree(os.path.join(LIBRARY, 'traffic_cone'), str(cached / 'cone_copy'))
    (cached / 'not_a_model').mkdir()
    return {'HOME': str(home), 'XDG_CACHE_HOME': str(tmp_path / 'cache'),
            'GAZEBO_MODEL_PATH': os.pathsep.join([GAZEBO_MODELS, LOADER_MODELS, LIBRARY]),
            'GAZEBO_MODEL_DATABASE_URI': ''}


def test_list_models_sources_order_titles(env):
    entries = library.list_models(env=env)
    by = {(e.source, e.name): e for e in entries}
    lib = sorted(n for n in os.listdir(LIBRARY)
                 if os.path.isfile(os.path.join(LIBRARY, n, 'model.config')))
    assert [e.name for e in entries if e.source == 'library'] == lib
    assert 'traffic_cone' in lib and 'sun' in lib
    gmp = [e.name for e in entries if e.source == 'GAZEBO_MODEL_PATH']
    # the fixtures, sorted; the library's folder on the path is not listed twice
    assert gmp == sorted(['painted_panel', 'prism', 'step_block', 'crate', 'ground_plane', 'sun'])
    assert [e.name for e in entries if e.source == '~/.gazebo/models'] == ['cone_copy']
    assert [e.source for e in entries] == sorted(
        (e.source for e in entries), key=library.SOURCES.index)
    cone = by[('library', 'traffic_cone')]
    assert cone.uri == 'model://traffic_cone' and cone.title == 'traffic_cone'
    assert cone.path == os.path.join(LIBRARY, 'traffic_cone')
    assert by[('GAZEBO_MODEL_PATH', 'crate')].path == os.path.join(LOADER_MODELS, 'crate')
    assert not any(e.source == 'database' for e in entries)


def test_database_models_listed_and_downloaded_for_their_thumbnail(env):
    import importlib.util
    spec = importlib.util.spec_from_file_location(
        'model_database_server', os.path.join(HERE, 'test_model_database.py'))
    mdb = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mdb)         # its local HTTP model database (Database)
    Database, config, tarball = mdb.Database, mdb.config, mdb.tarball
    from ode_sim.description import modeldb
    modeldb._INDEX.clear()
    db = Database({'database.config': config('step_block', 'prism', 'cone_copy'),
                   'step_block/model.tar.gz': tarball('step_block'),
                   'prism/model.tar.gz': tarball('prism')})
    try:
        env = dict(env, GAZEBO_MODEL_PATH=LOADER_MODELS, GAZEBO_MODEL_DATABASE_URI=db.uri)
        assert not any(e.source == 'database' for e in library.list_models(env=env))
        entries = library.list_models(env=env, database=True)
        remote = [e for e in entries if e.source == 'database']
        # cone_copy is in ~/.gazebo/models already: listed there, not again
        assert [(e.name, e.path, e.uri) for e in remote] == [
            ('prism', '', 'model://prism'), ('step_block', '', 'model://step_block')]
        assert entries[-2:] == remote
        path = library.thumbnail(remote[0], 32, env=env)
        assert os.path.isfile(path)
        assert os.path.isfile(os.path.join(env['HOME'], '.gazebo', 'models', 'prism',
                                           'model.config'))
        assert 'prism/model.tar.gz' in [r.lstrip('/') for r in db.requests]
    finally:
        db.close()
        modeldb._INDEX.clear()


def test_database_listing_needs_a_reachable_database(env):
    env = dict(env, GAZEBO_MODEL_DATABASE_URI='http://127.0.0.1:9/')   # discard port: refused
    with pytest.raises(ModelError, match='cannot be reached'):
        library.list_models(env=env, database=True)


def _png(path):
    return np.asarray(Image.open(path).convert('RGB'))


def test_thumbnail_renders_the_model_and_is_cached(env):
    entries = {(e.source, e.name): e for e in library.list_models(env=env)}
    cone = entries[('library', 'traffic_cone')]
    path = library.thumbnail(cone, 96, env=env)
    assert path.startswith(os.path.join(env['XDG_CACHE_HOME'], 'ode_sim', 'thumbnails'))
    img = _png(path)
    assert img.shape == (96, 96, 3)
    bg = np.array(library.BACKGROUND[:3]) * 255
    model = np.abs(img.astype(float) - bg).sum(axis=2) > 30
    # the cone fills the middle of the picture and not the corners; it is orange
    assert model[40:56, 40:56].mean() > 0.5 and not model[:5, :5].any()
    r, g, b = img[model].mean(axis=0)
    assert r > g > b, (r, g, b)
    # a second call reads the cache: same file, not rewritten
    mtime = os.stat(path).st_mtime_ns
    assert library.thumbnail(cone, 96, env=env) == path
    assert os.stat(path).st_mtime_ns == mtime
    # another size is another file
    assert _png(library.thumbnail(cone, 48, env=env)).shape == (48, 48, 3)


def test_thumbnail_follows_model_changes(env, tmp_path):
    root = tmp_path / 'models'
    shutil.copytree(os.path.join(LIBRARY, 'traffic_cone'), str(root / 'cone'))
    env = dict(env, GAZEBO_MODEL_PATH=str(root))
    [entry] = [e for e in library.list_models(env=env) if e.name == 'cone']
    first = library.thumbnail(entry, 64, env=env)
    sdf_file = root / 'cone' / 'model.sdf'
    sdf_file.write_text(sdf_file.read_text())
    st = os.stat(str(sdf_file))
    os.utime(str(sdf_file), ns=(st.st_atime_ns, st.st_mtime_ns + 10**9))
    second = library.thumbnail(entry, 64, env=env)
    assert second != first and os.path.isfile(second)


def test_thumbnails_of_meshes_textures_and_lights(env):
    entries = {(e.source, e.name): e for e in library.list_models(env=env)}
    bg = np.array(library.BACKGROUND[:3]) * 255
    for key in (('GAZEBO_MODEL_PATH', 'painted_panel'), ('GAZEBO_MODEL_PATH', 'prism'),
                ('library', 'sun'), ('library', 'office')):
        img = _png(library.thumbnail(entries[key], 64, env=env))
        drawn = np.abs(img.astype(float) - bg).sum(axis=2) > 30
        assert drawn.mean() > 0.02, key


def test_thumbnail_of_a_broken_model_says_why(env, tmp_path):
    bad = tmp_path / 'bad' / 'broken'
    bad.mkdir(parents=True)
    (bad / 'model.config').write_text('<model><name>broken</name><sdf version="1.6">model.sdf'
                                      '</sdf></model>')
    (bad / 'model.sdf').write_text('<sdf version="1.6"><model name="x"><link name="l">')
    env = dict(env, GAZEBO_MODEL_PATH=str(tmp_path / 'bad'))
    [entry] = [e for e in library.list_models(env=env) if e.name == 'broken']
    with pytest.raises(ModelError, match='model.sdf'):
        library.thumbnail(entry, 32, env=env)


# ------------------------------------------------------------------------------ walls

def test_walls_one_static_model_a_box_per_wall():
    text = walls.walls_model('room', [(0, 0, 4, 0), (4, 0, 4, 3)], height=2.0, thickness=0.2)
    m = sdf.parse_sdf_model(text, 'walls')
    assert m.name == 'room' and m.static and len(m.links) == 1
    link = m.links[0]
    assert [c.name for c in link.collisions] == ['wall_0_collision', 'wall_1_collision']
    assert [v.name for v in link.visuals] == ['wall_0_visual', 'wall_1_visual']
    c0, c1 = link.collisions
    assert c0.geometry.kind == 'box' and c0.geometry.size == pytest.approx((4.2, 0.2, 2.0))
    assert list(c0.pose.p) == pytest.approx([2, 0, 1])
    assert c1.geometry.size == pytest.approx((3.2, 0.2, 2.0))
    assert list(c1.pose.p) == pytest.approx([4, 1.5, 1])
    assert c1.pose.rpy()[2] == pytest.approx(math.pi / 2)
    assert link.visuals[0].material_name == 'Gazebo/Grey'


def test_walls_stop_a_box_in_the_engine():
    """A box pushed along +x stops at the wall: the walls collide."""
    world = sdf.parse_world('<sdf version="1.6"><world name="w"><gravity>0 0 0</gravity>'
                            '</world></sdf>', 'w.world')
    pw = PhysicsWorld(world.physics, world.gravity)
    pw.add_model(sdf.parse_sdf_model(walls.walls_model('wall', [(1, -1, 1, 1)]), 'walls'))
    box = sdf.parse_sdf_model(
        '<sdf version="1.6"><model name="b"><pose>0 0 0.5 0 0 0</pose><link name="l">'
        '<inertial><mass>1</mass><inertia><ixx>0.01</ixx><iyy>0.01</iyy><izz>0.01</izz>'
        '</inertia></inertial><collision name="c"><geometry><box><size>0.2 0.2 0.2</size>'
        '</box></geometry></collision></link></model></sdf>', 'box')
    m = pw.add_model(box)
    m.set_twist((1.0, 0, 0), (0, 0, 0))
    pw.step(3000)
    assert m.pose().p[0] < 1 - 0.075 - 0.1 + 0.02       # wall face minus half the box


@pytest.mark.parametrize('args, match', [
    (('', [(0, 0, 1, 0)]), 'needs a name'),
    (('w', []), 'no wall segments'),
    (('w', [(0, 0, 0, 0)]), 'segment 0 has zero length'),
    (('w', [(0, 0, 1)]), r'segment 0 must be \(x0, y0, x1, y1\)'),
    (('w', [(0, 0, 1, 'x')]), 'segment 0 must be a number'),
    (('w', [(0, 0, 1, 0)], -1.0), 'height and thickness must be positive'),
    (('w', [(0, 0, 1, 0)], 2.0, float('nan')), 'thickness must be finite'),
])
def test_walls_bad_input_one_line(args, match):
    with pytest.raises(ModelError, match=match):
        walls.walls_model(*args)
