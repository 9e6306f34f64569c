"""The page in headless Chromium (Debian's chromium + chromedriver, driven by Debian's
python3-selenium) against one launch (test/browser.launch: web.launch with rosbridge,
turtlesim, the space scanner in the office): the turtlesim panel draws the turtle and its
trail after a Twist, the arrow keys and the teleop pad move the turtle, the plot panel draws a
line, the 3D panel shows the simulated robot and its laser scan (pixels of screenshots)."""
import os
import sys
import urllib.request

import numpy as np
import pytest

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from browser_page import Page, open_page  # noqa: E402  (the browser tests' shared set-up)

PEN = np.array([179, 184, 255])          # turtlesim's default pen colour
BACKGROUND = np.array([69, 86, 255])     # turtlesim's default background
PLOT_BLUE = np.array([31, 119, 255])     # the plot's first series (#1f77ff)
LAYOUT = {'version': 1, 'panels': [
    {'type': 'turtlesim', 'x': 0, 'y': 0, 'w': 516, 'h': 570},
    {'type': 'teleop', 'x': 520, 'y': 0, 'w': 300, 'h': 300, 'opts': {'topic': '/turtle1/cmd_vel'}},
    {'type': 'plot', 'x': 520, 'y': 305, 'w': 520, 'h': 265, 'opts': {'fields': ['/turtle1/pose/x']}},
]}
TOKEN = 'c0ffee42' * 4                 # the page's token (web.launch token:=...)
# added by the 3D test only (software WebGL is the page's costliest part)
VIEW3D = ({'x': 1045, 'y': 0, 'w': 600, 'h': 570}, {'fixed': 'odom', 'distance': 1.2})


class Stack(Page):
    """The page with the turtlesim panel: the turtle's pose, teleports, Twists."""

    def pose(self, turtle='turtle1'):
        """The turtle's last /turtle1/pose as the page received it (x, y)."""
        p = self.stats('turtlesim')['poses'].get(turtle) or {}
        return p.get('x', float('nan')), p.get('y', float('nan'))

    def still_pose(self, turtle='turtle1'):
        """The turtle's pose once it has stopped (turtlesim stops 1 s after the last command)."""
        def still():
            p = self.stats('turtlesim')['poses'].get(turtle) or {}
            return p and p['linear_velocity'] == 0 and p['angular_velocity'] == 0 and (p['x'], p['y'])
        return self.wait(still, '%s to stand still' % turtle, timeout=30)

    def teleport(self, x, y, theta, turtle='turtle1'):
        """/turtle1/teleport_absolute called from the browser (rosbridge call_service): room
        to move, away from the walls."""
        self.still_pose(turtle)   # a command still running would carry it off the spot
        ok = self.driver.execute_async_script(
            "const done = arguments[arguments.length - 1];"
            "new ROSLIB.Service({ros: courseWeb.ros(), name: '/' + arguments[0] + '/teleport_absolute',"
            " serviceType: 'turtlesim/TeleportAbsolute'})"
            ".callService({x: arguments[1], y: arguments[2], theta: arguments[3]},"
            " () => done(true), e => done(String(e)));", turtle, x, y, theta)
        assert ok is True, 'teleport_absolute through rosbridge failed: %s' % ok
        return self.wait(lambda: np.hypot(*np.subtract(self.pose(turtle), (x, y))) < 0.05,
                         '%s at (%.1f, %.1f) after the teleport' % (turtle, x, y), timeout=30)

    def publish_twist(self, topic, vx, wz, times=10):
        """Twists from the browser through rosbridge (roslibjs), as any web client sends them:
        10 at 10 Hz (a new ROS publisher's first messages may go out before the subscriber is
        connected, so rostopic pub -1 waits; a stream does not need to)."""
        self.js("const t = new ROSLIB.Topic({ros: courseWeb.ros(), name: arguments[0],"
                " messageType: 'geometry_msgs/Twist'});"
                "let n = 0; const id = setInterval(() => {"
                " t.publish({linear: {x: arguments[1], y: 0, z: 0}, angular: {x: 0, y: 0, z: arguments[2]}});"
                " if (++n >= arguments[3]) clearInterval(id); }, 100);", topic, vx, wz, times)


def _near(img, rgb, tol=12):
    return int((np.abs(img.astype(int) - rgb).max(axis=2) <= tol).sum())


@pytest.fixture(scope='module')
def stack(tmp_path_factory):
    tmp = str(tmp_path_factory.mktemp('course_web'))

    def vendor_served(web):
        req = urllib.request.Request('http://127.0.0.1:%d/vendor/roslib.min.js' % web,
                                     headers={'Authorization': 'token ' + TOKEN})
        with urllib.request.urlopen(req, timeout=10) as r:
            assert r.status == 200, 'www/vendor is missing: run scripts/install_js.sh'
    with open_page(tmp, 'browser.launch', TOKEN, Stack, up_timeout=90, served=vendor_served) as s:
        s.js('courseWeb.setLayout(arguments[0])', LAYOUT)
        yield s


def test_turtlesim_panel_draws_turtle_and_trail(stack):
    s = stack
    s.wait(lambda: (s.stats('turtlesim')['poses'].get('turtle1') or {}).get('x'), 'turtle1 in the turtlesim panel')
    img = s.shot('.turtlesim-canvas', 'turtlesim_before')
    assert _near(img, BACKGROUND) > 0.9 * 500 * 500, 'the background is not turtlesim\'s default colour'
    turtle_px = img.size // 3 - _near(img, BACKGROUND)
    assert turtle_px > 150, 'no turtle drawn (%d pixels differ from the background)' % turtle_px
    assert _near(img, PEN) < 20, 'a trail before the turtle moved'
    s.publish_twist('/turtle1/cmd_vel', 1.0, 0.6)
    s.wait(lambda: _near(s.shot('.turtlesim-canvas', 'turtlesim_trail'), PEN, 20) > 80,
           'the pen trail (>80 pixels of rgb%s) after a Twist' % (tuple(PEN),), timeout=30)


def test_arrow_keys_move_the_turtle(stack):
    from selenium.webdriver.common.keys import Keys
    s = stack
    s.teleport(3.0, 5.5, 0.0)
    x0, y0 = s.still_pose()
    canvas = s.driver.find_element('css selector', '.turtlesim-canvas')
    canvas.click()
    for _ in range(3):
        canvas.send_keys(Keys.ARROW_UP)
    s.wait(lambda: abs(np.hypot(*np.subtract(s.pose(), (x0, y0)))) > 0.5,
           'turtle1 to move after the up arrow (turtle_teleop_key)', timeout=30)


def test_teleop_pad_moves_the_turtle(stack):
    from selenium.webdriver.common.action_chains import ActionChains
    s = stack
    s.teleport(3.0, 5.5, 0.0)
    x0, y0 = s.still_pose()
    fwd = s.driver.find_element('css selector', '.teleop-forward')
    ActionChains(s.driver).click_and_hold(fwd).pause(1.5).release().perform()
    s.wait(lambda: abs(np.hypot(*np.subtract(s.pose(), (x0, y0)))) > 0.5,
           'turtle1 to move after holding the teleop pad\'s forward button', timeout=30)
    s.wait(lambda: not s.stats('teleop')['moving'], 'the pad to stop publishing after release')


def test_plot_panel_draws_a_line(stack):
    s = stack
    s.wait(lambda: s.stats('plot')['series'] and s.stats('plot')['series'][0]['points'] > 5,
           'points of /turtle1/pose/x in the plot')
    px = s.wait(lambda: _near(s.shot('.plot-canvas', 'plot'), PLOT_BLUE, 30), 'the plot line', timeout=20)
    assert px > 100, 'the plot line has only %d pixels' % px


def test_3d_panel_shows_robot_and_scan(stack):
    s = stack
    s.js('courseWeb.addPanel("view3d", arguments[0], arguments[1])', *VIEW3D)
    s.wait(lambda: s.stats('view3d')['visibleLinks'] >= 5, 'the robot model placed by TF in the 3D panel', timeout=90)
    s.wait(lambda: ((s.stats('view3d')['displays'].get('/scan') or {}).get('count') or 0) > 100,
           'the laser scan (/scan) in the 3D panel', timeout=60)

    def red(img):
        return int(((img[:, :, 0] > 235) & (img[:, :, 1] < 40) & (img[:, :, 2] < 40)).sum())

    def shot_when(name, ok, what):
        """Screenshots until OK(picture): the view draws on its own frames, later on a busy
        machine (the wait is a hang guard); the picture."""
        def take():
            img = s.shot('.view3d-canvas', name)
            return (img,) if ok(img) else None
        return s.wait(take, what, timeout=30)[0]
    with_all = shot_when('view3d', lambda img: red(img) > 100, 'red laser points in the 3D view')
    # the scan: red points that go away when its display is switched off
    s.js("document.querySelectorAll('.view3d-displays label').forEach(l => {"
         " if (l.textContent.startsWith('/scan ')) l.querySelector('input').click(); })")
    no_scan = shot_when('view3d_no_scan', lambda img: red(with_all) - red(img) > 100,
                        'the laser points to go with the /scan display off (%d red pixels with it)'
                        % red(with_all))
    # the robot: the middle of the view (the camera follows base_footprint) changes without it
    s.js("document.querySelector('.panel[data-type=view3d] input[type=checkbox]:nth-of-type(1)');"
         "[...document.querySelectorAll('.panel[data-type=view3d] label')]"
         ".find(l => l.textContent.includes('robot model'))"
         ".querySelector('input').click()")
    h, w = no_scan.shape[:2]
    mid = (slice(h // 4, 3 * h // 4), slice(w // 4, 3 * w // 4))

    def changed(img):
        return int((np.abs(no_scan[mid].astype(int) - img[mid]).max(axis=2) > 40).sum())
    shot_when('view3d_no_robot', lambda img: changed(img) > 500,
              'the robot model to go from the view\'s middle (more than 500 pixels change)')


def test_page_connected_through_rosauth(stack):
    """The page reached rosbridge (authenticate:=true in web.launch) with the rosauth MAC that
    course_web_server gave it for its token: rosbridge accepted it, never refused it."""
    log = stack.launch.output()
    assert 'has authenticated.' in log, log[-3000:]
    assert 'did not authenticate' not in log, log[-3000:]
    # a new connection (as after a rosbridge restart) authenticates with a new MAC: the
    # first one would be refused as a replay
    before = log.count('has authenticated.')
    stack.js('courseWeb.ros().close()')
    stack.wait(lambda: stack.launch.output().count('has authenticated.') > before and
               stack.js('return courseWeb.connected()'), 'the page to reconnect and authenticate')
    log = stack.launch.output()
    assert 'did not authenticate' not in log, log[-3000:]
    assert TOKEN not in log.replace('?token=%s' % TOKEN, ''), 'the token leaked into a log line'
