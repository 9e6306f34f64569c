"""Run inside the test's second network namespace (ip netns exec): what a machine on the
network sees of the page and rosbridge. Prints one JSON object.
    netns_client.py HOST WEB_PORT BRIDGE_PORT TOKEN|- WSCLIENT_DIR"""
import http.client
import json
import socket
import sys


def get(host, port, path, headers=None):
    c = http.client.HTTPConnection(host, port, timeout=20)
    c.request('GET', path, headers=headers or {})
    r = c.getresponse()
    out = (r.status, dict(r.getheaders()), r.read())
    c.close()
    return out


def ws_outcome(host, port, first, then=None):
    """'closed: ...' if the server closes the connection, else the first answer's op."""
    from wsclient import WsClient
    c = WsClient(port, host=host, timeout=20)
    try:
        c.send(**first)
        if then:
            c.send(**then)
        while True:
            m = c.recv()
            if isinstance(m, dict) and m.get('op') in ('publish', 'service_response'):
                return m
    except (ConnectionError, OSError) as e:
        return 'closed: %s' % e
    finally:
        c.close()


def main():
    host, web, bridge, token, wsdir = sys.argv[1:6]
    web, bridge = int(web), int(bridge)
    sys.path.insert(0, wsdir)
    out = {}
    for name, port in (('web', web), ('bridge', bridge)):
        s = socket.socket()
        s.settimeout(10)
        try:
            s.connect((host, port))
            out[name + '_reachable'] = True
        except OSError as e:
            out[name + '_reachable'] = str(e)
        finally:
            s.close()
    if out['web_reachable'] is not True:
        print(json.dumps(out))
        return
    out['page_without_token'] = get(host, web, '/')[0]
    out['static_without_token'] = get(host, web, '/app.js')[0]
    out['rosauth_without_token'] = get(host, web, '/rosauth')[0]
    out['ws_without_auth'] = ws_outcome(host, bridge, {'op': 'subscribe', 'topic': '/turtle1/pose',
                                                       'type': 'turtlesim/Pose'})
    if token != '-':
        status, headers, _ = get(host, web, '/?token=' + token)
        out['token_visit'] = status
        cookie = headers.get('Set-Cookie', '').split(';')[0]
        out['page_with_cookie'] = get(host, web, '/', {'Cookie': cookie})[0]
        out['static_with_cookie'] = get(host, web, '/app.js', {'Cookie': cookie})[0]
        status, _, body = get(host, web, '/rosauth', {'Cookie': cookie})
        auth = json.loads(body) if status == 200 else None
        out['rosauth_with_cookie'] = status
        if auth:
            m = ws_outcome(host, bridge, auth, {'op': 'subscribe', 'topic': '/turtle1/pose',
                                                'type': 'turtlesim/Pose'})
            out['ws_with_auth'] = m.get('topic') if isinstance(m, dict) else m
            out['ws_replayed_auth'] = ws_outcome(host, bridge, auth,
                                                 {'op': 'subscribe', 'topic': '/turtle1/pose'})
            if isinstance(out['ws_replayed_auth'], dict):
                out['ws_replayed_auth'] = 'answered'
    print(json.dumps(out))


if __name__ == '__main__':
    main()
