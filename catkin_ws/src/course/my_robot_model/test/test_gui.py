"""robot.launch and first_model.launch under Xvfb: RViz really draws the model's colours."""
import pytest

from my_robot_model import model_check as mc
from course_testing.gui_check import rviz_launch_shows

ORANGE = (1.0, 108 / 255, 10 / 255, 1.0)
BLUE = (0.0, 0.0, 0.8, 1.0)
BLACK = (0.0, 0.0, 0.0, 1.0)


def test_robot_launch_shows_orange_body_and_black_wheels(rviz_env, screen, tmp_path):
    box, counts = rviz_launch_shows(rviz_env, screen.display, tmp_path,
                                    ['my_robot_model', 'robot.launch'],
                                    {'orange body': ORANGE, 'black wheels': BLACK}, 'my_robot_model_robot.png')
    assert counts['orange body'] > counts['black wheels']
    assert box[2] - box[0] > 800   # the 3D view is the main part of the window


def test_robot_launch_with_gui_sliders(rviz_env, screen, tmp_path):
    """gui:=true starts joint_state_publisher_gui instead; the model is still drawn."""
    rviz_launch_shows(rviz_env, screen.display, tmp_path,
                      ['my_robot_model', 'robot.launch'], {'orange body': ORANGE, 'black wheels': BLACK},
                      'my_robot_model_robot_gui.png', launch_args=['gui:=true'])


def test_first_model_launch_shows_blue_body_and_black_wheels(rviz_env, screen, tmp_path):
    _, counts = rviz_launch_shows(rviz_env, screen.display, tmp_path,
                                  ['my_robot_model', 'first_model.launch'],
                                  {'blue body': BLUE, 'black wheels': BLACK}, 'my_robot_model_first_model.png')
    assert counts['blue body'] > counts['black wheels']


def test_colours_in_the_test_are_the_models_colours():
    colours = mc.material_colours(mc.expand_xacro(mc.__file__.replace(
        'src/my_robot_model/model_check.py', 'urdf/diff_robot_model.urdf.xacro')))
    assert colours['orange'] == pytest.approx(ORANGE) and colours['black'] == pytest.approx(BLACK)
    with open(mc.__file__.replace('src/my_robot_model/model_check.py', 'urdf/my_first_model.urdf')) as f:
        colours = mc.material_colours(f.read())
    assert colours['blue'] == pytest.approx(BLUE)
