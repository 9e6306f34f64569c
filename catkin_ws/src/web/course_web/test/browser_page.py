"""The browser tests' shared set-up (test_browser.py, test_sim_editor.py): a private roscore,
one launch file of the test folder (web.launch's server and rosbridge on free ports), headless
Chromium (Debian's chromium + chromedriver, driven by Debian's python3-selenium) on the page
with its token, and `Page`, the page as the tests drive it."""
import contextlib
import io
import os
import socket

import numpy as np
from PIL import Image

from course_testing import Proc, RosCore, free_port, wait_for
from course_testing import sim_testing as T

HERE = os.path.dirname(os.path.abspath(__file__))


def port_open(port):
    with socket.socket() as s:
        s.settimeout(0.5)
        return s.connect_ex(('127.0.0.1', port)) == 0


def chrome(log_path):
    from selenium import webdriver
    from selenium.webdriver.chrome.service import Service
    opts = webdriver.ChromeOptions()
    opts.binary_location = '/usr/bin/chromium'
    for a in ('--headless=new', '--no-sandbox', '--disable-dev-shm-usage', '--window-size=1700,1000',
              '--enable-unsafe-swiftshader', '--use-angle=swiftshader', '--disable-extensions',
              '--no-first-run', '--disable-background-networking'):
        opts.add_argument(a)
    opts.set_capability('goog:loggingPrefs', {'browser': 'ALL'})
    return webdriver.Chrome(service=Service('/usr/bin/chromedriver', log_path=log_path), options=opts)


class Page:
    """The page in the browser: scripts, the panels' stats, waits that show the browser's
    console and the launch's log when they time out, screenshots of elements."""

    def __init__(self, env, driver, launch, tmp):
        self.env, self.driver, self.launch, self.tmp = env, driver, launch, tmp

    def js(self, script, *args):
        return self.driver.execute_script(script, *args)

    def stats(self, kind):
        for p in self.js('return courseWeb.panels()'):
            if p['type'] == kind:
                return p['stats']
        raise AssertionError('no %s panel on the page' % kind)

    def wait(self, predicate, what, timeout=60.0):
        try:
            return wait_for(predicate, timeout, 0.2, what)
        except TimeoutError as e:
            logs = [entry['message'][:300] for entry in self.driver.get_log('browser')][-15:]
            raise AssertionError('%s\nbrowser console: %s\nlaunch log:\n%s'
                                 % (e, '\n'.join(logs), self.launch.output()[-3000:]))

    def shot(self, css, name):
        """RGB array of the element's screenshot (also kept as NAME.png in the test's tmp dir)."""
        png = self.driver.find_element('css selector', css).screenshot_as_png
        with open(os.path.join(self.tmp, name + '.png'), 'wb') as f:
            f.write(png)
        return np.asarray(Image.open(io.BytesIO(png)).convert('RGB'))


@contextlib.contextmanager
def open_page(tmp, launch_file, token, page_class=Page, up_timeout=90, served=None, downloads=None):
    """A roscore, `roslaunch test/LAUNCH_FILE port:= rosbridge_port:= token:= secret_file:=`, and
    Chromium on the page (?layout=empty&token=TOKEN) once it is connected to rosbridge; yields a
    PAGE_CLASS with .web, .bridge (the ports) and .core; stops all three afterwards.
    SERVED(web_port) runs once the server is up, before the browser starts; DOWNLOADS is the
    folder the browser saves downloads in."""
    core = RosCore(log_dir=os.path.join(tmp, 'ros_log')).start()
    driver = launch = None
    try:
        env = T.ros_env(core)
        web, bridge = free_port(), free_port()
        launch = Proc(['roslaunch', os.path.join(HERE, launch_file), 'port:=%d' % web,
                       'rosbridge_port:=%d' % bridge, 'token:=' + token,
                       'secret_file:=' + os.path.join(tmp, 'secret')],
                      env=env, log=os.path.join(tmp, 'launch.log'))

        def up():
            assert launch.alive(), '%s exited:\n%s' % (launch_file, launch.output()[-3000:])
            # the page's own server (its URL printed), not another process on a port that
            # free_port() gave out (a node's XML-RPC server answers GET with 501)
            return ('course_web: open http://localhost:%d/' % web) in launch.output() and \
                port_open(web) and port_open(bridge)
        wait_for(up, up_timeout, 0.2, 'the page (port %d) and rosbridge (port %d)' % (web, bridge))
        if served:
            served(web)
        driver = chrome(os.path.join(tmp, 'chromedriver.log'))
        driver.set_script_timeout(30)
        if downloads:
            driver.execute_cdp_cmd('Page.setDownloadBehavior', {'behavior': 'allow', 'downloadPath': downloads})
        # the printed URL's way in: ?token= once, then the cookie (rosbridge: the page's
        # rosauth MAC from /rosauth)
        driver.get('http://127.0.0.1:%d/?layout=empty&token=%s' % (web, token))
        s = page_class(env, driver, launch, tmp)
        s.web, s.bridge, s.core = web, bridge, core
        s.wait(lambda: s.js('return window.courseWeb && courseWeb.connected()'), 'the page to connect to rosbridge')
        yield s
    finally:
        if driver:
            driver.quit()
        if launch:
            launch.stop()
        core.stop()
