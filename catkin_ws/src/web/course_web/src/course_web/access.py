"""What course_web_server's ~token, ~address and argv mean (no ROS imports)."""
from course_web.server import new_token

RANDOM = 'random'     # web.launch's default for ~token: a new one at each start


def choose_token(param, argv):
    """(token or None, warning or None) from ~token and the node's argv (--no-token)."""
    if '--no-token' in argv or param == '':
        return None, ('course_web: no token (--no-token / token:=""): anybody who can reach '
                      'this port can open the page and drive the robot through it')
    if param is None or param == RANDOM:
        return new_token(), None
    param = str(param)
    if len(param) < 8:
        raise ValueError('~token: %d characters is too easy to guess; give at least 8, '
                         '"random" or "" (no token)' % len(param))
    return param, None


def page_url(address, port, token):
    """The URL to print: localhost for a local bind, else the address (0.0.0.0: this host's
    own name in the browser, localhost works on the machine itself)."""
    host = 'localhost' if address in ('', '0.0.0.0', '127.0.0.1', '::', '::1') else address
    url = 'http://%s:%d/' % (host, port)
    return url + ('?token=%s' % token if token else '')
