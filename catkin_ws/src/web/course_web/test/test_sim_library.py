"""The 3D panel's Insert list on the HTTP side (no roscore): /sim/models.json is
ode_sim.description.library's list_models() (the project's library and GAZEBO_MODEL_PATH
folders), /sim/thumbnail its PNGs, behind the page's token; bad requests get one line."""
import json
import urllib.error
import urllib.request

import pytest

from course_web.server import start_server
from course_web.sim_library import SimLibrary

TOKEN = 'abad1dea' * 4
CRATE = """<?xml version="1.0"?>
<sdf version="1.6"><model name="test_crate"><static>true</static><link name="link">
<collision name="c"><geometry><box><size>0.4 0.3 0.2</size></box></geometry></collision>
<visual name="v"><geometry><box><size>0.4 0.3 0.2</size></box></geometry></visual>
</link></model></sdf>
"""


@pytest.fixture
def models(tmp_path, monkeypatch):
    """A GAZEBO_MODEL_PATH folder with one model; the thumbnail cache under a fresh HOME."""
    folder = tmp_path / 'my_models' / 'test_crate'
    folder.mkdir(parents=True)
    (folder / 'model.config').write_text(
        '<?xml version="1.0"?><model><name>Test crate</name><version>1.0</version>'
        '<sdf version="1.6">model.sdf</sdf></model>')
    (folder / 'model.sdf').write_text(CRATE)
    monkeypatch.setenv('GAZEBO_MODEL_PATH', str(tmp_path / 'my_models'))
    monkeypatch.setenv('HOME', str(tmp_path / 'home'))
    (tmp_path / 'home').mkdir()
    return tmp_path


@pytest.fixture
def server(models, tmp_path):
    www = tmp_path / 'www'
    www.mkdir()
    (www / 'index.html').write_text('<html></html>')
    httpd = start_server('127.0.0.1', 0, str(www), lambda p: None, {}, token=TOKEN,
                         routes=SimLibrary().routes())
    yield 'http://127.0.0.1:%d' % httpd.server_address[1]
    httpd.shutdown()


def get(url, token=TOKEN):
    req = urllib.request.Request(url, headers={'Authorization': 'token ' + token} if token else {})
    try:
        with urllib.request.urlopen(req, timeout=120) as r:
            return r.status, r.headers['Content-Type'], r.read()
    except urllib.error.HTTPError as e:
        return e.code, e.headers['Content-Type'], e.read()


def test_models_are_list_models(models):
    from ode_sim.description import library
    got = SimLibrary().models()
    want = library.list_models()
    assert [(m['source'], m['name'], m['uri']) for m in got] == \
        [(e.source, e.name, e.uri) for e in want]
    crate = [m for m in got if m['name'] == 'test_crate']
    assert crate == [{'name': 'test_crate', 'title': 'Test crate', 'uri': 'model://test_crate',
                      'source': 'GAZEBO_MODEL_PATH',
                      'thumbnail': 'sim/thumbnail?source=GAZEBO_MODEL_PATH&name=test_crate'}]
    assert any(m['source'] == 'library' and m['name'] == 'table' for m in got)


def test_http_list_and_thumbnail(server):
    status, ctype, body = get(server + '/sim/models.json')
    assert status == 200 and ctype == 'application/json'
    entry = [m for m in json.loads(body) if m['name'] == 'test_crate'][0]
    status, ctype, png = get(server + '/' + entry['thumbnail'])
    assert status == 200 and ctype == 'image/png' and png.startswith(b'\x89PNG\r\n\x1a\n')
    # the box is drawn: shaded faces (at least two shades) over > 5 % of the background
    import io
    import numpy as np
    from PIL import Image
    img = np.asarray(Image.open(io.BytesIO(png)).convert('RGB')).reshape(-1, 3)
    colours, counts = np.unique(img, axis=0, return_counts=True)
    assert len(colours) >= 3 and counts.sum() - counts.max() > 0.05 * len(img), \
        list(zip(colours.tolist(), counts.tolist()))


@pytest.mark.parametrize('path,status,words', [
    ('/sim/thumbnail', 400, 'needs ?source=SOURCE&name=NAME'),
    ('/sim/thumbnail?name=no_such_model', 404, 'no model "no_such_model"'),
    ('/sim/thumbnail?source=library&name=test_crate', 404, '(source library)'),
])
def test_bad_requests_get_one_line(server, path, status, words):
    got, ctype, body = get(server + path)
    text = body.decode()
    assert got == status and ctype == 'text/plain', (got, text)
    assert text.count('\n') == 1 and words in text, text


def test_token_needed(server):
    for path in ('/sim/models.json', '/sim/thumbnail?source=GAZEBO_MODEL_PATH&name=test_crate'):
        assert get(server + path, token=None)[0] == 403
        assert get(server + path, token='wrong' * 8)[0] == 403


def test_missing_library_is_one_line():
    class Broken(object):
        def list_models(self):
            raise OSError(13, 'Permission denied')
    status, ctype, body = SimLibrary(Broken()).routes()['/sim/models.json']('')
    assert status == 500 and body.decode() == \
        'listing the model library failed: PermissionError: [Errno 13] Permission denied\n'
