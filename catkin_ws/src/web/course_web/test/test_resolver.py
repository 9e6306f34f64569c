"""Unit tests of the HTTP side (no roscore): package:// resolution and path safety."""
import json
import os
import urllib.error
import urllib.request

import pytest

from course_web.resolver import ResolveError, package_url_to_http, resolve, safe_join
from course_web.server import ServerError, content_type, start_server


@pytest.fixture
def tree(tmp_path):
    """www/ with an index, two packages, a secret next to them and symlinks leading out."""
    www = tmp_path / 'www'
    (www / 'panels').mkdir(parents=True)
    (www / 'index.html').write_text('<html>page</html>')
    (www / 'panels' / 'plot.js').write_text('export {}')
    robot = tmp_path / 'src' / 'my_robot'
    (robot / 'meshes').mkdir(parents=True)
    (robot / 'meshes' / 'base frame.stl').write_bytes(b'solid x\nendsolid x\n')
    other = tmp_path / 'src' / 'my_robot_extra'
    other.mkdir()
    (other / 'x.dae').write_text('<COLLADA/>')
    (tmp_path / 'secret.txt').write_text('password')
    os.symlink(tmp_path / 'secret.txt', robot / 'meshes' / 'leak.stl')
    os.symlink(tmp_path, www / 'up')
    pkgs = {'my_robot': str(robot), 'my_robot_extra': str(other)}
    return www, pkgs.__getitem__


def test_index_and_static_files(tree):
    www, find = tree
    assert resolve('/', str(www), find) == str(www / 'index.html')
    assert resolve('/?rosbridge=ws://x:1', str(www), find) == str(www / 'index.html')
    assert resolve('/panels/plot.js', str(www), find) == str(www / 'panels' / 'plot.js')
    assert resolve('/panels/./plot.js', str(www), find) == str(www / 'panels' / 'plot.js')


def test_package_url_resolution(tree):
    www, find = tree
    url = package_url_to_http('package://my_robot/meshes/base frame.stl')
    assert url == '/package/my_robot/meshes/base frame.stl'
    assert resolve('/package/my_robot/meshes/base%20frame.stl', str(www), find).endswith('base frame.stl')
    assert resolve('/package/my_robot_extra/x.dae', str(www), find).endswith('x.dae')
    with pytest.raises(ResolveError) as e:
        package_url_to_http('file:///etc/passwd')
    assert e.value.status == 400


@pytest.mark.parametrize('path,status', [
    ('/package/nope/a.stl', 404),                    # unknown package
    ('/package/my_robot/meshes/none.stl', 404),      # missing file
    ('/package/my_robot', 403),                      # a package directory
    ('/package/my_robot/meshes', 403),               # a directory inside it
    ('/package/my_robot/../secret.txt', 403),        # '..'
    ('/package/my_robot/%2e%2e/%2e%2e/secret.txt', 403),  # encoded '..'
    ('/package/my_robot/..%2f..%2fsecret.txt', 403),
    ('/package/my_robot/meshes/leak.stl', 403),      # symlink out of the package
    ('/package/..%2fsecret.txt', 400),               # bad package name
    ('/package/my_robot/a%00.stl', 400),             # NUL
    ('/../secret.txt', 403),
    ('/up/secret.txt', 403),                         # symlink out of www
    ('/%2e%2e/secret.txt', 403),
    ('/nothing.js', 404),
])
def test_nothing_outside_is_served(tree, path, status):
    www, find = tree
    with pytest.raises(ResolveError) as e:
        resolve(path, str(www), find)
    assert e.value.status == status, e.value.reason


def test_safe_join_absolute_part_stays_inside(tmp_path):
    (tmp_path / 'etc').mkdir()
    (tmp_path / 'etc' / 'passwd').write_text('inside')
    # a leading '/' or '//' is a path inside the root, never the filesystem's root
    assert safe_join(str(tmp_path), '//etc/passwd') == str(tmp_path / 'etc' / 'passwd')


def test_content_types():
    assert content_type('a/app.js') == 'text/javascript'   # ES modules need it
    assert content_type('m.STL') == 'model/stl'
    assert content_type('x.bin') == 'application/octet-stream'


def _get(url):
    try:
        with urllib.request.urlopen(url, timeout=10) as r:
            return r.status, r.headers['Content-Type'], r.read()
    except urllib.error.HTTPError as e:
        return e.code, e.headers['Content-Type'], e.read()


def test_server_over_http(tree):
    www, find = tree
    httpd = start_server('127.0.0.1', 0, str(www), find, {'rosbridge_port': 9191})
    try:
        base = 'http://127.0.0.1:%d' % httpd.server_address[1]
        assert _get(base + '/')[::2] == (200, b'<html>page</html>')
        status, ctype, body = _get(base + '/config.json')
        assert status == 200 and json.loads(body) == {'rosbridge_port': 9191}
        assert _get(base + '/package/my_robot/meshes/base%20frame.stl')[:2] == (200, 'model/stl')
        status, _, body = _get(base + '/package/my_robot/%2e%2e/%2e%2e/secret.txt')
        assert status == 403 and b'password' not in body
        assert _get(base + '/package/my_robot/meshes/leak.stl')[0] == 403
    finally:
        httpd.shutdown()
        httpd.server_close()


def test_busy_port_is_a_clear_error(tree):
    www, find = tree
    httpd = start_server('127.0.0.1', 0, str(www), find, {})
    try:
        with pytest.raises(ServerError, match=r'cannot listen on 127.0.0.1:\d+: .*port:='):
            start_server('127.0.0.1', httpd.server_address[1], str(www), find, {})
    finally:
        httpd.shutdown()
        httpd.server_close()


def test_missing_page_is_a_clear_error(tmp_path):
    with pytest.raises(ServerError, match='no index.html'):
        start_server('127.0.0.1', 0, str(tmp_path), {}.__getitem__, {})
