"""rqt's command line without a GUI (in-process; QT_QPA_PLATFORM=offscreen from the runner):
--list-plugins, --standalone matching and the original's option errors."""

import pytest
from rqt_gui.main import Main

EXPECTED = ['rqt_console.console.Console', 'rqt_graph.ros_graph.RosGraph',
            'rqt_image_view.image_view.ImageView', 'rqt_plot.plot.Plot',
            'rqt_publisher.publisher.Publisher', 'rqt_robot_steering.robot_steering.RobotSteering',
            'rqt_tf_tree.tf_tree.RosTfTree', 'rqt_topic.topic.Topic']


@pytest.fixture(autouse=True)
def config(tmp_path, monkeypatch):
    monkeypatch.setenv('XDG_CONFIG_HOME', str(tmp_path))
    monkeypatch.setenv('QT_QPA_PLATFORM', 'offscreen')


def test_list_plugins(capsys):
    assert Main().main(['rqt', '--list-plugins']) == 0
    lines = capsys.readouterr().out.split()
    assert lines == sorted(lines)
    for name in EXPECTED:
        assert name in lines


@pytest.mark.parametrize('argv, line', [
    (['--args', 'x'], 'Option --args can only be used together with either --standalone, '
                      '--command-start-plugin or --embed-plugin option'),
    (['-f'], 'Option --freeze_layout can only be used together with the --lock_perspective option'),
    (['--list-plugins', '--list-perspectives'], 'Only one --list-* option can be used at a time'),
    (['-p', 'a', '--perspective-file', __file__], 'Only one --perspective-* option can be used at a time'),
    (['--perspective-file', '/nonexistent.perspective'], 'Option --perspective-file must reference existing file'),
])
def test_option_errors(argv, line, capsys):
    assert Main().main(['rqt'] + argv) == 1
    assert capsys.readouterr().out.strip() == line


def test_standalone_matching_errors(capsys):
    assert Main().main(['rqt', '-s', 'no_such_plugin']) == 1
    out = capsys.readouterr().out
    assert 'qt_gui_main() found no plugin matching "no_such_plugin"' in out
    assert 'try passing the option "--force-discover"' in out
    assert Main().main(['rqt', '-s', 'rqt_']) == 1
    assert 'qt_gui_main() found multiple plugins matching "rqt_"' in capsys.readouterr().out


def test_no_ros_package_path(monkeypatch, capsys):
    monkeypatch.delenv('ROS_PACKAGE_PATH')
    assert Main().main(['rqt', '--list-plugins']) == 1
    assert 'ROS_PACKAGE_PATH is not set' in capsys.readouterr().err
