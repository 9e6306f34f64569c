"""The table "the diploma prints → type here" of catkin_ws/src/space_scanner/README.md, row by
row: every "here" launch command resolves with its arguments (roslaunch's own check: includes,
args, packages and node executables) and loads, every $(find ...) path and package:// mesh
exists, every pkg/type node is found. The printed $(find diff_drive_controller)/... paths and
`roslaunch diff_drive_controller robot_config.launch` indeed do not exist here, or are
ros_controllers' files for its own test robot (that package has the name), and every path and
command of the diploma's listings has its row."""
import os
import re
import shlex
import subprocess

import pytest

from course_testing.launch_check import check_launch

README = os.path.join(os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))), 'README.md')

# every package path, launch command and node of the diploma's listings (figures 1.7, 1.8, 1.9,
# 1.12, 2.25, 2.26, 2.27), as printed (OCR damage repaired)
DIPLOMA = [
    'roslaunch diff_drive_controller robot_config.launch',
    '$(find diff_drive_controller)/launch/robot_config.launch',
    '$(find diff_drive_controller)/urdf/chassi_bot.urdf.xacro',
    'pkg="diff_drive_controller" type="diffbot"',
    '$(find diff_drive_controller)/test/diffbot_controllers.yaml',
    '$(find diff_drive_controller)/test/diffbot_limits.yaml',
    '$(find diff_drive_controller)/config/ekf.yaml',
    '$(find rplidar_ros)/launch/rplidar.launch',
    '$(find imu_filter_madgwick)/launch/imu_filter_madgwick.launch',
    'pkg="robot_localization" type="ekf_localization_node"',
    'pkg="rosserial_python" type="serial_node.py"',
    'pkg="gmapping" type="slam_gmapping"',
    'pkg="teleop_twist_keyboard" type="teleop_twist_keyboard.py"',
    '$(find diff_drive_controller)/maps/mymap.yaml',
    '$(find amcl)/examples/amcl_diff.launch',
    '$(find diff_drive_controller)/launch/amcl.launch',
    'pkg="map_server" type="map_server"',
    'pkg="move_base" type="move_base"',
    '$(find diff_drive_controller)/config/costmap_common_params.yaml',
    '$(find diff_drive_controller)/config/local_costmap_params.yaml',
    '$(find diff_drive_controller)/config/global_costmap_params.yaml',
    '$(find diff_drive_controller)/config/base_local_planner_params.yaml',
    "roslaunch urdf_tutorial display.launch model:='$(find space_scanner_simulation)/urdf/chassi_bot.urdf.xacro'",
    '$(find space_scanner_simulation)/urdf/chassi_bot.urdf.xacro',
    '$(find space_scanner_simulation)/urdf/include/materials.xacro',
    '$(find space_scanner_simulation)/urdf/include/materials.gazebo',
    'package://space_scanner_simulation/meshes/base.dae',
    'roslaunch space_scanner_simulation simulation.launch',
    '$(find gazebo_ros)/launch/empty_world.launch',
    'pkg="gazebo_ros" type="spawn_model"',
    '$(find space_scanner_simulation)/rviz/config.rviz',
]


def table():
    with open(README) as f:
        text = f.read()
    m = re.search(r'<!-- diploma-table -->\n(.*?)<!-- /diploma-table -->', text, re.S)
    assert m, '%s: no <!-- diploma-table --> ... <!-- /diploma-table --> block' % README
    rows = []
    for line in m.group(1).splitlines()[2:]:            # skip the header and the |---|---| line
        cells = [c.strip() for c in line.strip().strip('|').split('|')]
        assert len(cells) == 2, 'not a two-column row: %r' % line
        here = re.findall(r'`([^`]+)`', cells[1])
        assert len(here) == 1, 'the "type here" cell must be one code span: %r' % line
        rows.append((re.findall(r'`([^`]+)`', cells[0]), here[0]))
    return rows


ROWS = table()


def resolve_find(text):
    from roslaunch.substitution_args import resolve_args
    return resolve_args(text)


def find_node(pkg, exe):
    import roslib.packages
    return roslib.packages.find_node(pkg, exe)


def resolves(item):
    """None if `item` (a command, path or node) resolves here, else what is wrong."""
    if item.startswith('roslaunch '):
        words = shlex.split(item)
        import rospkg
        try:
            path = os.path.join(rospkg.RosPack().get_path(words[1]), 'launch', words[2])
        except rospkg.ResourceNotFound:
            return 'no package %s' % words[1]
        if not os.path.isfile(path):
            found = subprocess.run(['find', rospkg.RosPack().get_path(words[1]), '-name', words[2]],
                                   capture_output=True, text=True).stdout.split()
            if not found:
                return 'no launch file %s in %s' % (words[2], words[1])
            path = found[0]
        err, _ = check_launch(path, words[3:])
        return None if err is None else '%s: %s' % (item, err)
    m = re.fullmatch(r'pkg="([^"]+)" type="([^"]+)"', item)
    if m:
        return None if find_node(*m.groups()) else 'no node %s in package %s' % (m.group(2), m.group(1))
    if item.startswith('$(find '):
        try:
            path = resolve_find(item)
        except Exception as e:
            return '%s: %s' % (item, e)
        return None if os.path.isfile(path) else 'no file %s' % path
    if item.startswith('package://'):
        from my_robot_model import model_check as mc
        path = mc.rospack_resolver()(item)
        return None if path and os.path.isfile(path) else 'no file for %s' % item
    return 'not a command, path or node: %r' % item


@pytest.mark.parametrize('printed, here', ROWS, ids=[r[1][:60] for r in ROWS])
def test_row_resolves_here(printed, here):
    problem = resolves(here)
    assert problem is None, problem


DDC_ROWS = [(p, here) for printed, here in ROWS for p in printed
            if p.startswith(('$(find diff_drive_controller)', 'roslaunch diff_drive_controller'))]


@pytest.mark.parametrize('item, here', DDC_ROWS, ids=[r[0][:60] for r in DDC_ROWS])
def test_the_printed_diff_drive_controller_paths_are_not_ours(item, here):
    """Why the table exists: ros_controllers' diff_drive_controller has none of them, or (its
    test/diffbot_*.yaml) has files of that name for its own two-wheeled test robot."""
    if resolves(item) is None:
        with open(resolve_find(item)) as a, open(resolve_find(here)) as b:
            theirs, ours = a.read(), b.read()
        assert theirs != ours and 'wheel_3_joint' not in theirs, '%s is the space scanner\'s file' % item


def test_every_listing_item_has_its_row():
    printed = {p for ps, _ in ROWS for p in ps}
    missing = [d for d in DIPLOMA if d not in printed]
    assert not missing, 'rows missing for: %s' % missing
