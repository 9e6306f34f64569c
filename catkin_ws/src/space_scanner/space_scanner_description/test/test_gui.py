"""display.launch under Xvfb: RViz really draws the model in its material colours."""
import os

from my_robot_model import model_check as mc
from course_testing.gui_check import rviz_launch_shows

COLOURS = {'green decks': (0.1, 0.75, 0.2, 1.0), 'red front wheels': (0.85, 0.05, 0.05, 1.0),
           'blue rear wheels': (0.05, 0.2, 0.85, 1.0)}


def test_display_launch_shows_the_model(rviz_env, screen, tmp_path):
    rviz_launch_shows(rviz_env, screen.display, tmp_path, ['space_scanner_description', 'display.launch'], COLOURS,
                      'space_scanner_description_display.png')


def test_colours_are_the_models_materials():
    urdf = mc.expand_xacro(os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))),
                                        'urdf', 'chassi_bot.urdf.xacro'))
    used = set(mc.material_colours(urdf).values())
    for name, rgba in COLOURS.items():
        assert tuple(rgba) in used, name
