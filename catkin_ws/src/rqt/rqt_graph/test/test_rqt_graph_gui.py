"""rqt_graph for real (practical 1 §2.4): talker and listener on a private master, the graph
under Xvfb; the model's node/edge lists and a screenshot of the drawn items are checked."""
import os
import shutil
import sys
import time

from course_testing import Proc, screenshot, wait_for
from course_testing.image import load_rgb
from course_testing.rqt_driver import dark_fraction, gui_env, states

HERE = os.path.dirname(os.path.abspath(__file__))


def test_graph_shows_talker_listener_and_chatter(roscore, xvfb, tmp_path):
    env = gui_env(roscore.env, xvfb.display, tmp_path / 'config')
    flag = tmp_path / 'shot.done'
    procs = []
    try:
        procs.append(Proc(['rosrun', 'rospy_tutorials', 'talker'], env=env, log=str(tmp_path / 'talker.log')))
        procs.append(Proc(['rosrun', 'rospy_tutorials', 'listener'], env=env, log=str(tmp_path / 'listener.log')))
        gui = Proc([sys.executable, os.path.join(HERE, 'check_graph_driver.py'), str(flag)], env=env,
                   log=str(tmp_path / 'rqt_graph.log'))
        procs.append(gui)
        wait_for(lambda: len(states(gui.output())) >= 2 or not gui.alive(), 90, 0.3,
                 'rqt_graph to show /talker and /listener')
        got = states(gui.output())
        assert len(got) >= 2 and 'error' not in got[0], gui.output()[-3000:]
        nodes_only, topics = got[0], got[1]
        assert nodes_only['title'] == 'Node Graph'
        # rospy_tutorials' talker and listener are anonymous: /talker_<pid>_<stamp>
        talker = [n for n in nodes_only['nodes'] if n.startswith('/talker_')]
        listener = [n for n in nodes_only['nodes'] if n.startswith('/listener_')]
        assert len(talker) == 1 and len(listener) == 1, nodes_only['nodes']
        talker, listener = talker[0], listener[0]
        assert nodes_only['edges'] == [[talker, listener, '/chatter']]   # /rosout edges are hidden
        assert topics['mode'] == 'node_topic'
        assert topics['topics'] == ['/chatter']
        assert sorted(topics['edges']) == sorted([[talker, '/chatter'], ['/chatter', listener]])
        assert topics['tooltips']['t_/chatter'] == 'topic:/chatter'
        png = str(tmp_path / 'rqt_graph.png')

        def painted():      # screenshots until the items are painted (later on a busy machine)
            rgb = load_rgb(screenshot(xvfb.display, png))
            return all(0.03 < dark_fraction(rgb, topics['rects'][key]) < 0.6
                       for key in ('n_' + talker, 'n_' + listener, 't_/chatter'))
        deadline = time.monotonic() + 30                # a hang guard
        while not painted() and time.monotonic() < deadline:
            time.sleep(0.5)
        flag.write_text('done')
        keep = os.environ.get('COURSE_SCREENSHOT_DIR')
        if keep:
            os.makedirs(keep, exist_ok=True)
            shutil.copy(png, os.path.join(keep, 'rqt_graph.png'))
        wait_for(lambda: not gui.alive(), 30, 0.2, 'rqt_graph to close')
        assert gui.popen.returncode == 0, gui.output()[-3000:]
    finally:
        for p in reversed(procs):
            p.stop()
    rgb = load_rgb(png)
    # each drawn item (outline + label) has dark pixels; the view around them is white
    for key in ('n_' + talker, 'n_' + listener, 't_/chatter'):
        rect = topics['rects'][key]
        assert rect[2] > 20 and rect[3] > 10, '%s is drawn too small: %s' % (key, rect)
        frac = dark_fraction(rgb, rect)
        assert 0.03 < frac < 0.6, '%s: %.3f of its rectangle %s is dark' % (key, frac, rect)
    vx, vy, vw, vh = topics['view']
    view = rgb[vy:vy + vh, vx:vx + vw]
    assert (view.min(axis=2) > 240).mean() > 0.6, 'the graph view is not mostly white background'
