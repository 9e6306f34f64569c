"""Every launch file of the package, with sim:=true and for the real robot, resolves: its
includes and args, and every node's package and executable exist (roslaunch's own check, as
rostest's roslaunch_check), and each names the nodes the diploma's files name."""
import pytest

from course_testing.launch_check import check_launch


DIPLOMA_NODES = {
    'robot_config.launch': {('controller_manager', 'spawner'), ('robot_state_publisher', 'robot_state_publisher'),
                            ('imu_filter_madgwick', 'imu_filter_node'),
                            ('robot_localization', 'ekf_localization_node')},
    'gmapping.launch': {('gmapping', 'slam_gmapping')},
    'navigation.launch': {('map_server', 'map_server'), ('amcl', 'amcl'), ('move_base', 'move_base')},
}
REAL_ONLY = {('space_scanner_hw', 'diffbot'), ('rosserial_python', 'serial_node.py'), ('rplidar_ros', 'rplidarNode')}
SIM_ONLY = {('gazebo_ros', 'spawn_model')}


def nodes(launch, args):
    import rospkg
    path = '%s/launch/%s' % (rospkg.RosPack().get_path('space_scanner_bringup'), launch)
    err, found = check_launch(path, args, timeout=120)
    assert err is None, '%s %s: %s' % (launch, ' '.join(args), err)
    return {(pkg, exe) for pkg, exe, _ in found}


@pytest.mark.parametrize('launch', sorted(DIPLOMA_NODES))
@pytest.mark.parametrize('sim', [True, False])
def test_launch_file_resolves_with_the_diploma_nodes(launch, sim):
    found = nodes(launch, ['sim:=%s' % str(sim).lower()])
    want = set(DIPLOMA_NODES['robot_config.launch']) | DIPLOMA_NODES[launch]
    want |= SIM_ONLY if sim else REAL_ONLY
    assert want <= found, 'missing: %s' % sorted(want - found)
    assert not (found & (REAL_ONLY if sim else SIM_ONLY)), sorted(found)
