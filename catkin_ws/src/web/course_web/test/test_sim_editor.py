"""The 3D panel's scene editor in headless Chromium against a real simulator
(test/sim_editor.launch: web.launch and gazebo_ros' empty_world.launch, sim_node), driven as a
student does PW4 / lab 4 in the browser: the Insert list is the simulator's model library,
insert a library model and a box by clicking on the ground, move and turn the box by dragging
it with the mouse, pause and step 100 steps (sim time advances by exactly 100 x max_step_size),
move the table with the pose fields while paused (the view shows it there), save the world (a
download) and check the file: the models at their moved poses, and sim_node loads it back to
the same poses. Clients without the token / rosauth MAC get nothing; bad requests one line."""
import os
import sys
import time
import urllib.error
import urllib.request
import xml.etree.ElementTree as ET

import numpy as np
import pytest

from course_testing import Proc, RosCore
from course_testing import sim_testing as T

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from browser_page import Page, open_page  # noqa: E402  (the browser tests' shared set-up)

TOKEN = 'beefcafe' * 4
# the panel and its canvas wholly inside the window (1700 x 1000): pointer offsets stay exact
VIEW = ({'x': 0, 'y': 0, 'w': 1200, 'h': 760}, {'fixed': 'odom', 'distance': 9, 'follow': False, 'robot': False})
LIBRARY_MODEL = 'table'


class Editor(Page):
    def sim(self):
        return self.stats('view3d')['sim']

    def click(self, css):
        self.driver.find_element('css selector', css).click()

    def canvas_offset(self, x, y):
        """Offsets of the client point x, y from Selenium's origin for the canvas: the centre of
        its part inside the viewport (WebDriver's in-view centre point)."""
        r = self.js("const r = document.querySelector('.view3d-canvas').getBoundingClientRect();"
                    "const l = Math.max(0, r.left), t = Math.max(0, r.top),"
                    " R = Math.min(innerWidth, r.right), B = Math.min(innerHeight, r.bottom);"
                    "return [Math.floor((l + R) / 2), Math.floor((t + B) / 2), innerHeight];")
        assert 0 <= y < r[2] and self.js(
            "const r = document.querySelector('.view3d-canvas').getBoundingClientRect();"
            "return r.top >= 0 && r.bottom <= innerHeight && r.left >= 0 && r.right <= innerWidth;"), \
            'the canvas is not wholly inside the window (point %.0f, %.0f)' % (x, y)
        return int(round(x - r[0])), int(round(y - r[1]))

    def type_into(self, css, text):
        """Select the field's text and type over it, as a student does."""
        from selenium.webdriver.common.keys import Keys
        f = self.driver.find_element('css selector', css)
        f.send_keys(Keys.CONTROL, 'a')
        f.send_keys(text)
        assert f.get_attribute('value') == text, (css, f.get_attribute('value'), text)

    def click_canvas(self, dx, dy):
        from selenium.webdriver.common.action_chains import ActionChains
        canvas = self.driver.find_element('css selector', '.view3d-canvas')
        ActionChains(self.driver).move_to_element_with_offset(canvas, dx, dy).click().perform()

    def model_state(self, name):
        """/gazebo/get_model_state through the page's rosbridge connection."""
        r = self.driver.execute_async_script(
            "const done = arguments[arguments.length - 1];"
            "new ROSLIB.Service({ros: courseWeb.ros(), name: '/gazebo/get_model_state',"
            " serviceType: 'gazebo_msgs/GetModelState'}).callService({model_name: arguments[0],"
            " relative_entity_name: ''}, r => done(r), e => done(String(e)));", name)
        assert isinstance(r, dict) and r['success'], 'get_model_state(%s): %s' % (name, r)
        return r['pose']


@pytest.fixture(scope='module')
def ed(tmp_path_factory):
    tmp = str(tmp_path_factory.mktemp('sim_editor'))
    downloads = os.path.join(tmp, 'downloads')
    os.makedirs(downloads)
    with open_page(tmp, 'sim_editor.launch', TOKEN, Editor, up_timeout=120, downloads=downloads) as s:
        s.downloads = downloads
        s.js('courseWeb.addPanel("view3d", arguments[0], arguments[1])', *VIEW)
        yield s


def test_insert_list_is_the_model_library(ed):
    from ode_sim.description import library
    ed.wait(lambda: ed.sim()['simTime'], 'the simulator\'s figures (/gazebo/world_stats) in the panel')
    assert 'Real time factor' in ed.driver.find_element('css selector', '.sim-stats').text
    ed.click('.sim-insert-toggle')
    ed.wait(lambda: ed.sim()['library'], 'the Insert list (sim/models.json)')
    shown = ed.js("return [...document.querySelectorAll('.sim-item')].map(b => b.dataset.uri)")
    assert shown == [e.uri for e in library.list_models()]
    assert 'model://%s' % LIBRARY_MODEL in shown
    # its thumbnail: a PNG rendered by the simulator's renderer
    ok = ed.wait(lambda: ed.js(
        "const i = [...document.querySelectorAll('.sim-item')].find(b => b.dataset.name === arguments[0])"
        ".querySelector('img'); i.loading = 'eager'; return i.complete && i.naturalWidth > 0 && i.naturalWidth;",
        LIBRARY_MODEL), 'the thumbnail of %s' % LIBRARY_MODEL, timeout=120)
    assert ok >= 64


def test_insert_a_library_model_and_a_box(ed):
    s = ed
    s.js("[...document.querySelectorAll('.sim-item')].find(b => b.dataset.name === arguments[0]).click()",
         LIBRARY_MODEL)
    assert s.sim()['placing'] == LIBRARY_MODEL
    s.click_canvas(-200, 60)
    s.wait(lambda: LIBRARY_MODEL in s.sim()['models'], '%s inserted' % LIBRARY_MODEL)
    s.click('.sim-shape-box')
    s.click_canvas(160, 40)
    s.wait(lambda: 'unit_box' in s.sim()['models'], 'unit_box inserted')
    s.click('.sim-insert-toggle')      # the list closes
    s.wait(lambda: {LIBRARY_MODEL, 'unit_box'} <= set(s.sim()['drawn']),
           'both models drawn in the view (scene markers)')
    table, box = s.model_state(LIBRARY_MODEL), s.model_state('unit_box')
    s.inserted_table = table
    # placed where the clicks met the ground: left and right of the view's centre
    assert abs(box['position']['z'] - 0.5) < 0.05, box
    assert np.hypot(table['position']['x'] - box['position']['x'],
                    table['position']['y'] - box['position']['y']) > 1.0, (table, box)
    s.shot('.view3d-canvas', 'inserted')


def test_move_the_box_with_the_mouse(ed):
    from selenium.webdriver.common.action_chains import ActionChains
    s = ed
    s.js("const sel = document.querySelector('.sim-model'); sel.value = 'unit_box';"
         " sel.dispatchEvent(new Event('change'))")
    s.wait(lambda: s.sim()['selectedAt'] and s.sim()['selPose'], 'unit_box selected and highlighted')
    before = s.model_state('unit_box')
    s.click('.sim-mode-translate')
    x, y = s.sim()['selectedAt']
    dx, dy = s.canvas_offset(x, y)
    canvas = s.driver.find_element('css selector', '.view3d-canvas')
    chain = ActionChains(s.driver).move_to_element_with_offset(canvas, dx, dy).click_and_hold()
    for _ in range(6):
        chain = chain.move_by_offset(-20, 0).pause(0.05)
    chain.release().perform()
    s.wait(lambda: s.sim()['info'].startswith('set unit_box to x'),
           'the move set by set_model_state (the press at %s was on %s; the box at %s)'
           % (s.sim()['lastDown'], s.sim()['lastPick'], (x, y)))
    after = s.model_state('unit_box')
    moved = np.hypot(after['position']['x'] - before['position']['x'],
                     after['position']['y'] - before['position']['y'])
    assert moved > 0.3, 'the box moved %.3f m after a 120 px drag' % moved
    assert abs(after['position']['z'] - before['position']['z']) < 0.05
    # rotate: a drag to the right turns it about z (0.01 rad a pixel), in place
    s.click('.sim-mode-rotate')
    s.wait(lambda: s.sim()['selectedAt'] and not s.sim()['held'], 'the view with the moved box (pose_info)')
    # scene markers made after the move (those of the 0.1 s around a move may be placed by the
    # pose before or after it for up to 2 s: the view is right again with the next ones)
    t_set = s.sim()['simTime']
    s.wait(lambda: (s.sim()['markersAt'] or 0) > t_set + 0.2, 'scene markers made after the move')
    time.sleep(0.3)   # a frame or two
    x, y = s.sim()['selectedAt']
    dx, dy = s.canvas_offset(x, y)
    chain = ActionChains(s.driver).move_to_element_with_offset(canvas, dx, dy).click_and_hold()
    for _ in range(4):
        chain = chain.move_by_offset(15, 0).pause(0.05)
    info = s.sim()['info']
    chain.release().perform()
    try:
        s.wait(lambda: s.sim()['info'] != info and s.sim()['info'].startswith('set unit_box to x'),
               'the rotation set', timeout=30)
    except AssertionError:
        s.shot('.view3d-canvas', 'rotate_press_missed')
        raise AssertionError('the rotation press at %s was on %s; the box at %s (%s)' % (
            s.sim()['lastDown'], s.sim()['lastPick'], (x, y), s.sim()['selCentre']))
    turned = s.model_state('unit_box')
    yaw = 2 * np.arctan2(turned['orientation']['z'], turned['orientation']['w'])
    assert 0.4 < yaw < 0.8, 'yaw %.3f rad after a 60 px drag (0.6 expected)' % yaw
    assert np.hypot(turned['position']['x'] - after['position']['x'],
                    turned['position']['y'] - after['position']['y']) < 0.01, (after, turned)
    s.click('.sim-mode-select')


def test_pause_and_step_100(ed):
    s = ed
    s.click('.sim-pause')
    s.wait(lambda: s.sim()['paused'] is True, 'the simulation paused (world_stats)')
    # the figures while paused stand still
    s.wait(lambda: (lambda a: time.sleep(0.5) or (a if a == s.sim()['simTime'] else None))(s.sim()['simTime']),
           'sim time to stand still while paused')
    step = s.sim()['stepSize']

    def steps(n):
        before = s.sim()['lastStep']
        s.type_into('.sim-steps', str(n))
        s.click('.sim-step')
        return s.wait(lambda: s.sim()['lastStep'] != before and s.sim()['lastStep'], 'the answer of step_world')
    one = steps(1)
    assert one['steps'] == 1
    last = steps(100)
    assert last['steps'] == 100
    assert abs(last['sim_time'] - (one['sim_time'] + 100 * step)) < 1e-9, (one, step, last)
    assert last['iterations'] == one['iterations'] + 100, (one, last)
    # the bottom bar shows it (a ROS time: whole nanoseconds)
    s.wait(lambda: abs(s.sim()['simTime'] - last['sim_time']) < 2e-9 and s.sim()['iterations'] == last['iterations'],
           'world_stats at the stepped time')
    assert s.sim()['paused'] is True


def test_set_the_table_pose_in_the_fields(ed):
    s = ed
    s.js("const sel = document.querySelector('.sim-model'); sel.value = arguments[0];"
         " sel.dispatchEvent(new Event('change'))", LIBRARY_MODEL)
    s.wait(lambda: s.sim()['selected'] == LIBRARY_MODEL and s.sim()['selPose'], 'the table selected')
    for k, v in (('x', '-1.5'), ('y', '2.25'), ('yaw', '0.7')):
        s.type_into('.sim-pose-' + k, v)
    s.click('.sim-apply')
    s.wait(lambda: abs(s.model_state(LIBRARY_MODEL)['position']['x'] + 1.5) < 1e-6, 'the table at x -1.5')
    p = s.model_state(LIBRARY_MODEL)
    assert abs(p['position']['y'] - 2.25) < 1e-6
    yaw = 2 * np.arctan2(p['orientation']['z'], p['orientation']['w'])
    assert abs(yaw - 0.7) < 1e-6, p
    # paused, the view shows it there (the scene markers moved by /gazebo/pose_info)
    assert s.sim()['paused'] is True
    s.wait(lambda: s.sim()['selCentre'] and
           np.hypot(s.sim()['selCentre'][0] + 1.5, s.sim()['selCentre'][1] - 2.25) < 0.2,
           'the table drawn at -1.5, 2.25 while paused')
    s.shot('.view3d-canvas', 'table_moved_paused')


def test_save_world_and_load_it_back(ed, tmp_path):
    s = ed
    poses = {n: s.model_state(n) for n in (LIBRARY_MODEL, 'unit_box')}
    s.type_into('.sim-file', 'browser_scene.world')
    s.click('.sim-save')
    path = os.path.join(s.downloads, 'browser_scene.world')
    s.wait(lambda: os.path.isfile(path) and not os.path.exists(path + '.crdownload') and
           os.path.getsize(path) == s.sim()['saved']['bytes'], 'the downloaded world file')
    world = ET.parse(path).getroot().find('world')
    assert world is not None, open(path).read()[:500]
    found = {}
    for inc in world.findall('include'):
        found[inc.findtext('name')] = ('include', inc.findtext('uri'), inc.findtext('pose'))
    for mod in world.findall('model'):
        found[mod.get('name')] = ('model', None, mod.findtext('pose'))
    assert found[LIBRARY_MODEL][:2] == ('include', 'model://' + LIBRARY_MODEL), found
    assert found['unit_box'][0] == 'model', found
    for name, p in poses.items():
        vals = [float(v) for v in found[name][2].split()]
        assert np.allclose(vals[:3], [p['position'][k] for k in 'xyz'], atol=1e-4), (name, vals, p)
        yaw = 2 * np.arctan2(p['orientation']['z'], p['orientation']['w'])
        assert abs(np.arctan2(np.sin(vals[5] - yaw), np.cos(vals[5] - yaw))) < 1e-4, (name, vals, p)
    # sim_node loads the saved file back (paused): the same models at the same poses
    core = RosCore(log_dir=str(tmp_path / 'ros_log')).start()
    sim = None
    try:
        env = T.ros_env(core)
        sim = Proc(['rosrun', 'ode_sim', 'sim_node', path, '-u', '__name:=gazebo'], env=env,
                   log=str(tmp_path / 'sim.log'))
        for name, p in poses.items():
            got = T.probe(['model', name], env, proc=sim)['pose']    # x y z yaw
            yaw = 2 * np.arctan2(p['orientation']['z'], p['orientation']['w'])
            assert np.allclose([got[k] for k in 'xyz'], [p['position'][k] for k in 'xyz'],
                               atol=1e-4), (name, got, p)
            assert abs(np.arctan2(np.sin(got['yaw'] - yaw), np.cos(got['yaw'] - yaw))) < 1e-4, \
                (name, got, p)
    finally:
        if sim:
            sim.stop()
        core.stop()


def test_delete_and_bad_input_give_one_line(ed):
    s = ed
    # step while running: the simulator's one line in the panel
    s.click('.sim-pause')
    s.wait(lambda: s.sim()['paused'] is False, 'the simulation running again')
    s.click('.sim-step')
    s.wait(lambda: s.sim()['info'].startswith('step_world: '), 'step_world\'s refusal in the panel')
    assert '\n' not in s.sim()['info']
    s.js("const sel = document.querySelector('.sim-model'); sel.value = 'unit_box';"
         " sel.dispatchEvent(new Event('change'))")
    s.wait(lambda: s.sim()['selected'] == 'unit_box', 'unit_box selected')
    # Gazebo's keys in the view: T, R, Esc; Delete deletes the selection
    from selenium.webdriver.common.action_chains import ActionChains
    from selenium.webdriver.common.keys import Keys
    s.js("document.querySelector('.view3d-canvas').parentElement.focus()")   # the view, not a field
    for key, mode in (('t', 'translate'), ('r', 'rotate'), (Keys.ESCAPE, 'select')):
        ActionChains(s.driver).send_keys(key).perform()
        s.wait(lambda: s.sim()['mode'] == mode, '%s mode from the keyboard' % mode, timeout=10)
    assert s.sim()['selected'] == 'unit_box'
    ActionChains(s.driver).send_keys(Keys.DELETE).perform()
    s.wait(lambda: 'unit_box' not in s.sim()['models'] and 'unit_box' not in s.sim()['drawn'],
           'unit_box deleted (list and view)')
    # Edit -> Reset Model Poses: the table back where it was inserted; Reset World: time too
    s.click('.sim-reset-poses')
    s.wait(lambda: s.sim()['info'] == 'model poses reset', 'reset_world answered')
    back, was = s.model_state(LIBRARY_MODEL), s.inserted_table
    assert np.allclose([back['position'][k] for k in 'xy'], [was['position'][k] for k in 'xy'], atol=1e-3), (back, was)
    t = s.sim()['simTime']
    s.click('.sim-reset-world')
    s.wait(lambda: s.sim()['info'] == 'world reset' and s.sim()['simTime'] < t - 0.5, 'sim time to start over')


def test_clients_without_token_or_mac_get_nothing(ed):
    s = ed
    for path in ('/sim/models.json', '/sim/thumbnail?source=library&name=table'):
        with pytest.raises(urllib.error.HTTPError) as e:
            urllib.request.urlopen('http://127.0.0.1:%d%s' % (s.web, path), timeout=10)
        assert e.value.code == 403
    req = urllib.request.Request('http://127.0.0.1:%d/sim/thumbnail?name=no_such_model' % s.web,
                                 headers={'Authorization': 'token ' + TOKEN})
    with pytest.raises(urllib.error.HTTPError) as e:
        urllib.request.urlopen(req, timeout=10)
    body = e.value.read().decode()
    assert e.value.code == 404 and body.count('\n') == 1 and 'no_such_model' in body, body
    # a WebSocket client without rosauth's MAC gets one status line and is closed before any
    # simulator service runs
    import json
    import subprocess
    sys.path.insert(0, os.path.join(subprocess.check_output(
        ['rospack', 'find', 'rosbridge_server'], env=s.env, text=True).strip(), 'test'))
    from wsclient import WsClient
    c = WsClient(s.bridge)
    said, closed = [], None
    try:
        c.send(op='call_service', service='/gazebo/delete_model', id='x',
               args={'model_name': LIBRARY_MODEL})
        while True:
            m = c.recv()
            assert not (isinstance(m, dict) and m.get('op') == 'service_response'), m
            if isinstance(m, dict) and m.get('op') == 'status':
                said.append(m['msg'])
    except (ConnectionError, OSError) as e:
        closed = str(e)
    finally:
        c.close()
    assert closed, 'rosbridge answered a client without authentication'
    assert said == ["authentication required: its first op was 'call_service', not auth"], said
    assert LIBRARY_MODEL in s.sim()['models'] and s.model_state(LIBRARY_MODEL)
    # an authenticated client with bad requests: one line each, from rosbridge or the simulator
    req = urllib.request.Request('http://127.0.0.1:%d/rosauth' % s.web,
                                 headers={'Authorization': 'token ' + TOKEN})
    auth = json.loads(urllib.request.urlopen(req, timeout=10).read())
    c = WsClient(s.bridge)
    answers = {}
    try:
        c.send(**auth)
        c.send(op='call_service', service='/gazebo/step_world', id='type', args={'steps': 'many'})
        c.send(op='call_service', service='/gazebo/spawn_sdf_model', id='xml',
               args={'model_name': 'bad', 'model_xml': '<sdf version="1.6"><model name="bad">'})
        while len(answers) < 2:
            m = c.recv()
            if isinstance(m, dict) and m.get('op') == 'service_response':
                answers[m['id']] = m
    finally:
        c.close()
    assert answers['type']['result'] is False and isinstance(answers['type']['values'], str) and \
        '\n' not in answers['type']['values'].strip() and 'steps' in answers['type']['values'], answers
    xml = answers['xml']
    assert xml['result'] is True and xml['values']['success'] is False, xml
    said = xml['values']['status_message']
    assert '\n' not in said and 'spawn_sdf_model(bad)' in said, xml


def test_editor_helpers(ed):
    """simedit.js' pure helpers, imported by the page: Gazebo's names of inserted models, the
    bottom bar's time format, roll-pitch-yaw, a bad shape's one-line error."""
    r = ed.driver.execute_async_script(
        "const done = arguments[arguments.length - 1];"
        "import('./panels/simedit.js').then(m => {"
        " let bad = null; try { m.shapeSdf('cone', 'c'); } catch (e) { bad = e.message; }"
        " const q = m.rpyToQuat(0.1, -0.2, 0.3);"
        " done({u0: m.uniqueName('unit_box', new Set(['ground_plane'])),"
        "  u2: m.uniqueName('unit_box', new Set(['unit_box', 'unit_box_0', 'unit_box_1'])),"
        "  t: m.formatTime(90061.5), t0: m.formatTime(0.0015), rpy: m.quatToRpy(q), bad,"
        "  inc: m.includeSdf('model://table')}); }, e => done(String(e)));")
    assert isinstance(r, dict), r
    assert r['u0'] == 'unit_box' and r['u2'] == 'unit_box_2'
    assert r['t'] == '01 01:01:01.500' and r['t0'] == '00 00:00:00.002'
    assert np.allclose(r['rpy'], [0.1, -0.2, 0.3], atol=1e-9)
    assert r['bad'] == 'unknown shape "cone" (box, sphere, cylinder)'
    assert r['inc'] == '<sdf version="1.6"><include><uri>model://table</uri></include></sdf>'
