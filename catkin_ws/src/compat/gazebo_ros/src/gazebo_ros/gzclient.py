"""gzclient: the simulator's "GUI client". There is no Gazebo GUI; with a display it runs RViz
on ode_sim's scene configuration (the world is published as markers), without one it says so
once and exits 0, so `gui:=true` launches also work headless."""
import os
import sys

NO_DISPLAY = ('gzclient: no display, the scene is published as RViz markers on '
              '/gazebo/scene_markers')


def scene_config(ode_sim_dir=None):
    """Path of ode_sim's RViz configuration (config/scene.rviz)."""
    if ode_sim_dir is None:
        import rospkg
        ode_sim_dir = rospkg.RosPack().get_path('ode_sim')
    return os.path.join(ode_sim_dir, 'config', 'scene.rviz')


def client_command(argv, env, config):
    """The RViz command line for `gzclient argv...`, or None without a display. Only ROS
    remappings (NAME:=VALUE, e.g. roslaunch's __name:=gazebo_gui) are passed on; Gazebo client
    options such as --verbose have no RViz meaning and are dropped."""
    if not env.get('DISPLAY'):
        return None
    return ['rviz', '-d', config] + [a for a in argv if ':=' in a]


def main(argv=None):
    argv = sys.argv[1:] if argv is None else argv
    if not os.environ.get('DISPLAY'):
        print('[INFO] ' + NO_DISPLAY, flush=True)
        return 0
    try:
        config = scene_config()
    except Exception as e:                      # rospkg.ResourceNotFound and friends
        print('[ERROR] gzclient: cannot find package ode_sim: %s' % e, file=sys.stderr)
        return 1
    if not os.path.isfile(config):
        print('[ERROR] gzclient: RViz configuration %s does not exist' % config, file=sys.stderr)
        return 1
    cmd = client_command(argv, os.environ, config)
    sys.stdout.flush()
    os.execvp(cmd[0], cmd)
