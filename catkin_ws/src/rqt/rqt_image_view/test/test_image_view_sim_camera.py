"""Image View shows the simulated camera (practical 6's robot_sim_camera.launch, headless) under
Xvfb: frames arrive, and the screenshot of the image area is the picture (not a blank frame): its
mean colour matches the received image and it has structure."""
import os
import shutil
import sys

import numpy as np
from course_testing import Proc, screenshot, wait_for
from course_testing.image import load_rgb
from course_testing.rqt_driver import gui_env, states

HERE = os.path.dirname(os.path.abspath(__file__))


def test_image_view_shows_sim_camera(roscore, xvfb, tmp_path):
    env = gui_env(roscore.env, xvfb.display, tmp_path / 'config')
    flag = tmp_path / 'shot.done'
    procs = []
    try:
        procs.append(Proc(['roslaunch', 'my_robot_simulation_sensors', 'robot_sim_camera.launch', 'gui:=false',
                           'rviz:=false', 'proc:=false'], env=env, log=str(tmp_path / 'sim.log')))
        gui = Proc([sys.executable, os.path.join(HERE, 'check_image_view_driver.py'), str(flag),
                    '/diff_drive_robot/camera1/image_raw'], env=env, log=str(tmp_path / 'image_view.log'))
        procs.append(gui)
        wait_for(lambda: any(s.get('kind') == 'shown' for s in states(gui.output())) or not gui.alive(),
                 180, 0.3, 'rqt_image_view to show 5 camera frames')
        shown = [s for s in states(gui.output()) if s.get('kind') == 'shown']
        assert shown, gui.output()[-3000:]
        shown = shown[0]
        png = screenshot(xvfb.display, str(tmp_path / 'image_view.png'))
        flag.write_text('done')
        keep = os.environ.get('COURSE_SCREENSHOT_DIR')
        if keep:
            os.makedirs(keep, exist_ok=True)
            shutil.copy(png, os.path.join(keep, 'rqt_image_view_camera.png'))
        wait_for(lambda: not gui.alive(), 30, 0.2, 'rqt_image_view to close')
        assert gui.popen.returncode == 0, gui.output()[-3000:]
    finally:
        for p in reversed(procs):
            p.stop()
    assert shown['topic'] == '/diff_drive_robot/camera1/image_raw'
    assert shown['std'] > 5, 'the camera image is uniform'
    x, y, w, h = shown['image_rect']
    assert w > 100 and h > 60
    region = load_rgb(png)[y + 2:y + h - 2, x + 2:x + w - 2].astype(float)
    mean = region.reshape(-1, 3).mean(axis=0)
    assert np.abs(mean - np.array(shown['mean'])).max() < 25, \
        'screen mean colour %s differs from the image mean %s' % (mean, shown['mean'])
    assert region.std() > 5, 'the image area on screen is uniform'
