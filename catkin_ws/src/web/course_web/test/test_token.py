"""The page's token without ROS: 403 without it, the ?token= visit sets a cookie and redirects,
the cookie or an Authorization header works, /rosauth gives a rosauth auth message only with
it; ~token / --no-token and the printed URL."""
import http.client
import json

import pytest

from course_web import access
from course_web.server import cookie_name, start_server, token_matches, without_token
from rosauth.mac import Authenticator

TOKEN = 'a1b2c3d4e5f6a7b8c9d0'
SECRET = 'abcdefghij012345'


@pytest.fixture
def server(tmp_path):
    (tmp_path / 'index.html').write_text('<html>page</html>')
    (tmp_path / 'app.js').write_text('export {}')
    lines = []

    def issuer(client, dest):
        from rosauth.mac import auth_message
        return auth_message(SECRET, client, dest)
    httpd = start_server('127.0.0.1', 0, str(tmp_path), {}.__getitem__, {'rosbridge_port': 1},
                         log=lines.append, token=TOKEN, auth_issuer=issuer)
    httpd.lines = lines
    try:
        yield httpd
    finally:
        httpd.shutdown()
        httpd.server_close()


def _get(httpd, path, headers=None):
    c = http.client.HTTPConnection('127.0.0.1', httpd.server_address[1], timeout=10)
    c.request('GET', path, headers=headers or {})
    r = c.getresponse()
    body = r.read()
    c.close()
    return r.status, dict(r.getheaders()), body


def test_everything_needs_the_token(server):
    for path in ('/', '/app.js', '/config.json', '/rosauth', '/?token=wrong',
                 '/app.js?token=' + TOKEN[:-1]):
        status, headers, body = _get(server, path)
        assert status == 403, path
        assert b'needs its token' in body and TOKEN.encode() not in body
        assert 'Access-Control-Allow-Origin' not in headers
    status, _, _ = _get(server, '/', {'Cookie': '%s=%s' % (cookie_name(1), TOKEN)})
    assert status == 403          # another port's cookie name


def test_token_visit_sets_cookie_and_redirects(server):
    status, headers, _ = _get(server, '/?layout=empty&token=%s' % TOKEN)
    assert status == 302 and headers['Location'] == '/?layout=empty'
    name = cookie_name(server.server_address[1])
    cookie = headers['Set-Cookie']
    assert cookie.startswith('%s=%s;' % (name, TOKEN)) and 'HttpOnly' in cookie
    status, _, body = _get(server, '/', {'Cookie': 'other=1; %s=%s' % (name, TOKEN)})
    assert status == 200 and body == b'<html>page</html>'
    assert _get(server, '/app.js', {'Authorization': 'token ' + TOKEN})[0] == 200
    assert _get(server, '/app.js', {'Authorization': 'token x' + TOKEN})[0] == 403
    assert not any(TOKEN in line for line in server.lines), server.lines


def test_rosauth_gives_a_fresh_auth_message(server):
    h = {'Authorization': 'token ' + TOKEN}
    status, headers, body = _get(server, '/rosauth', h)
    assert status == 200 and headers['Cache-Control'] == 'no-store'
    a = json.loads(body)
    assert a['op'] == 'auth' and a['client'] == '127.0.0.1' and a['dest'] == '127.0.0.1'
    check = Authenticator(SECRET)
    fields = [a[k] for k in ('mac', 'client', 'dest', 'rand', 't', 'level', 'end')]
    assert check.authenticate(*fields) == (True, 'authenticated')
    b = json.loads(_get(server, '/rosauth', h)[2])
    assert b['mac'] != a['mac']     # a new one each time (each is accepted once)


def test_helpers():
    assert token_matches(TOKEN, TOKEN) and not token_matches(TOKEN + 'x', TOKEN)
    assert not token_matches(None, TOKEN)
    assert without_token('/x?token=1&a=2') == '/x?a=2' and without_token('/?token=1') == '/'
    t, warning = access.choose_token(None, [])
    assert len(t) == 48 and warning is None
    assert access.choose_token('random', [])[0] != access.choose_token('random', [])[0]
    t, warning = access.choose_token('', [])
    assert t is None and 'no token' in warning
    assert access.choose_token('random', ['--no-token'])[0] is None
    assert access.choose_token(12345678, [])[0] == '12345678'
    with pytest.raises(ValueError, match='~token: 3 characters'):
        access.choose_token('abc', [])
    assert access.page_url('127.0.0.1', 8080, 'tok') == 'http://localhost:8080/?token=tok'
    assert access.page_url('0.0.0.0', 8080, None) == 'http://localhost:8080/'
    assert access.page_url('192.0.2.7', 81, 't') == 'http://192.0.2.7:81/?token=t'
