"""RViz for real under Xvfb: the practical-work scene (my_robot_simulation's my_scene.world) with
the sensor robot, as robot_sim_camera.launch opens it — the screenshot must show the robot, the
simulator's scene markers and the laser scan.

The scene's ground plane covers RViz's background, so gui_check.view_region (which finds the 3D
view by its background colour) cannot be used; the 3D view's place in the 1600x1000 screen is
fixed by sensors.rviz's layout instead (docks on the left, the view centred on the robot)."""
import os

from course_testing import Proc, screenshot, wait_for
from course_testing.image import load_rgb
from course_testing.gui_check import colour_mask, keep

ORANGE = (1.0, 0.42, 0.04, 1.0)     # the robot's body (URDF material) and the traffic cone
SCAN = (1.0, 0.0, 0.0, 1.0)         # sensors.rviz: LaserScan, flat colour 255 0 0
VIEW = (slice(70, 860), slice(370, 1480))        # rows, columns of the 3D view
ROBOT = (slice(380, 560), slice(830, 1020))      # around the orbit's focal point: the robot


def counts(rgb):
    orange = colour_mask(rgb, ORANGE)
    robot = int(orange[ROBOT].sum())
    return {'scan': int(colour_mask(rgb, SCAN)[VIEW].sum()), 'robot': robot,
            # orange in the view away from the robot: the traffic cone, drawn only by the
            # simulator's scene markers
            'scene': int(orange[VIEW].sum()) - robot}


def test_rviz_shows_robot_scene_markers_and_scan(rviz_env, screen, tmp_path):
    env = rviz_env
    launch = Proc(['roslaunch', 'my_robot_simulation_sensors', 'robot_sim_camera.launch',
                   'gui:=false', 'proc:=false'], env=env, log=str(tmp_path / 'launch.log'))
    shot = str(tmp_path / 'pw6_rviz_scene.png')
    seen = {}

    def drawn():
        screenshot(screen.display, shot)
        seen.update(counts(load_rgb(shot)))
        return seen['scan'] > 30 and seen['robot'] > 300 and seen['scene'] > 300
    try:
        wait_for(drawn, 150, 2.0, 'RViz drawing the robot, the scene markers and the scan')
    except TimeoutError as e:
        raise AssertionError('%s: last counts %s; launch log tail:\n%s'
                             % (e, seen, launch.output()[-3000:]))
    finally:
        launch.stop()
        if os.path.exists(shot):
            keep(shot, 'pw6_rviz_scene.png')
