"""course_testing.launch_check: the nodes of a launch file that resolves, with its name:=value
args, and roslaunch's message for one that does not (no roscore needed)."""
from course_testing.launch_check import check_launch

LAUNCH = '''<launch>
  <arg name="pkg" default="rosbag"/>
  <node ns="ns" name="rec" pkg="$(arg pkg)" type="record" args="-a"/>
</launch>
'''


def test_nodes_of_a_launch_file_with_its_args(tmp_path):
    f = tmp_path / 'ok.launch'
    f.write_text(LAUNCH)
    assert check_launch(str(f)) == (None, [('rosbag', 'record', '/ns/rec')])


def test_a_missing_package_is_roslaunchs_error(tmp_path):
    f = tmp_path / 'bad.launch'
    f.write_text(LAUNCH)
    err, nodes = check_launch(str(f), ['pkg:=no_such_package_here'])
    assert nodes == [] and 'no_such_package_here' in err, err
