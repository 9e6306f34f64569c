"""launch/empty_world.launch: the original's arguments build the sim_node command line, the
parameters and the gzclient node (roslaunch's own loader and CLI; no simulator is started)."""
import os
import subprocess


HERE = os.path.dirname(os.path.abspath(__file__))
LAUNCH = os.path.join(os.path.dirname(HERE), 'launch', 'empty_world.launch')


def load(*args):
    import roslaunch.config
    config = roslaunch.config.load_config_default([(LAUNCH, list(args))], None, verbose=False)
    nodes = {n.name: n for n in config.nodes}
    params = {k: v.value for k, v in config.params.items()}
    return nodes, params


def test_defaults():
    nodes, params = load()
    server = nodes['gazebo']
    assert (server.package, server.type, server.namespace) == ('ode_sim', 'sim_node', '/')
    assert server.args.split() == ['-e', 'ode', 'worlds/empty.world']
    assert not server.respawn and not server.required and server.output == 'screen'
    assert server.env_args == []
    gui = nodes['gazebo_gui']
    assert (gui.package, gui.type, gui.args.strip()) == ('gazebo_ros', 'gzclient', '')
    assert params['/use_sim_time'] is True and params['/gazebo/enable_ros_network'] is True
    assert '/gazebo/pub_clock_frequency' not in params


def test_paused_lockstep_verbose_world_and_extra_args():
    nodes, _ = load('paused:=true', 'lockstep:=true', 'verbose:=true', 'physics:=ode',
                    'world_name:=/tmp/my_worlds/a.world',
                    'extra_gazebo_args:=--scene-frame map')
    assert nodes['gazebo'].args.split() == ['-u', '--lockstep', '--verbose', '-e', 'ode',
                                            '--scene-frame', 'map', '/tmp/my_worlds/a.world']
    assert nodes['gazebo_gui'].args.strip() == '--verbose'


def test_other_arguments():
    nodes, params = load('gui:=false', 'use_sim_time:=false', 'use_clock_frequency:=true',
                         'pub_clock_frequency:=50', 'enable_ros_network:=false', 'debug:=true',
                         'respawn_gazebo:=true', 'output:=log', 'headless:=true',
                         'recording:=true', 'physics:=bullet')
    assert set(nodes) == {'gazebo'}
    server = nodes['gazebo']
    assert server.args.split() == ['-e', 'bullet', 'worlds/empty.world']   # sim_node refuses it
    assert server.env_args == [('PYTHONFAULTHANDLER', '1')]
    assert server.respawn and server.output == 'log'
    assert params['/use_sim_time'] is False and params['/gazebo/enable_ros_network'] is False
    assert params['/gazebo/pub_clock_frequency'] == 50
    nodes, _ = load('server_required:=true', 'gui_required:=true')
    assert nodes['gazebo'].required and nodes['gazebo_gui'].required


def test_included_with_the_textbook_arguments(tmp_path):
    """The course's sim.launch includes it with world_name/paused/use_sim_time/gui/headless/debug."""
    outer = tmp_path / 'sim.launch'
    outer.write_text(
        '<launch><include file="%s"><arg name="world_name" value="/w/empty.world"/>'
        '<arg name="paused" value="true"/><arg name="use_sim_time" value="true"/>'
        '<arg name="gui" value="false"/><arg name="headless" value="false"/>'
        '<arg name="debug" value="false"/></include></launch>' % LAUNCH)
    import roslaunch.config
    config = roslaunch.config.load_config_default([str(outer)], None, verbose=False)
    [server] = config.nodes
    assert server.args.split() == ['-u', '-e', 'ode', '/w/empty.world']


def roslaunch_cli(*args):
    return subprocess.run(['roslaunch'] + list(args), capture_output=True, text=True, timeout=60)


def test_roslaunch_nodes_and_args():
    out = roslaunch_cli('--nodes', 'gazebo_ros', 'empty_world.launch')
    assert out.returncode == 0, out.stderr
    assert out.stdout.split() == ['/gazebo', '/gazebo_gui']
    out = roslaunch_cli('--args', '/gazebo', 'gazebo_ros', 'empty_world.launch', 'paused:=true',
                        'lockstep:=true', 'world_name:=worlds/office.world')
    assert 'Cannot locate node' not in out.stderr and 'sim_node' in out.stdout + out.stderr, \
        'ode_sim sim_node is not built (run scripts/setup.sh): %s' % out.stderr.strip()[-200:]
    assert out.returncode == 0, out.stderr
    argv = out.stdout.split()
    assert argv[0].endswith('/sim_node')
    assert argv[1:] == ['-u', '--lockstep', '-e', 'ode', 'worlds/office.world', '__name:=gazebo']
