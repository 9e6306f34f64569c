"""Command line of sim_node (what gzserver's arguments map to)."""
import argparse
import sys

USAGE = 'sim_node [WORLD] [-u] [--lockstep] [--verbose] [-e ode]'


def parse_args(argv):
    import rospy
    args = rospy.myargv(argv)[1:]
    p = argparse.ArgumentParser(prog='sim_node', usage=USAGE,
                                description='ODE simulator with the gazebo_ros ROS API')
    p.add_argument('world', nargs='?', default='worlds/empty.world',
                   help='SDF world file (path, or worlds/NAME via GAZEBO_RESOURCE_PATH and '
                        'ode_sim/worlds)')
    p.add_argument('-u', '--pause', action='store_true', help='start paused')
    p.add_argument('--lockstep', action='store_true',
                   help='ros_control bridge waits for the command of every control period')
    p.add_argument('--verbose', action='store_true')
    p.add_argument('-e', '--physics', default='ode', help='physics engine (only ode)')
    p.add_argument('--scene-frame', default=None,
                   help='frame of the RViz scene markers (default: param ~scene_frame or odom)')
    known, unknown = p.parse_known_args(args)
    return known, unknown


def param_bool(name, default):
    """A boolean parameter given as a bool or as text (roslaunch <param value="false"/>)."""
    import rospy
    v = rospy.get_param(name, default)
    if isinstance(v, str):
        return v.strip().lower() in ('1', 'true', 'yes')
    return bool(v)


def main(argv):
    known, unknown = parse_args(argv)
    import rospy
    from ode_sim.description.model import ModelError
    rospy.init_node('gazebo', anonymous=False)
    for u in unknown:
        rospy.logwarn('sim_node: ignoring argument %r (a gzserver option ode_sim does not have)'
                      % u)
    if known.physics != 'ode':
        rospy.logerr("sim_node: physics engine '%s' is not available; ode_sim simulates with ODE"
                     % known.physics)
        return 2
    from ode_sim.description import sdf
    from ode_sim.description.resolve import resolve_world
    try:
        path = resolve_world(known.world)
        world = sdf.load_world(path)
    except ModelError as e:
        rospy.logfatal('sim_node: %s' % e)
        sys.stderr.write('sim_node: error: %s\n' % e)
        return 1
    from ode_sim.ros.gazebo_api import GazeboApi
    from ode_sim.ros.node import SimNode
    lockstep = known.lockstep or bool(rospy.get_param('~lockstep', False))
    try:
        node = SimNode(world, paused=known.pause, lockstep=lockstep, verbose=known.verbose)
    except ModelError as e:
        rospy.logfatal('sim_node: %s' % e)
        sys.stderr.write('sim_node: error: %s\n' % e)
        return 1
    # a saved world's <state>: every link where it was (joint positions of robots)
    from ode_sim.description.save_world import apply_link_states, read_state
    with node.lock:
        apply_link_states(node.physics.models, read_state(path))
    # as gazebo_ros_api_plugin: /use_sim_time true unless the user set it
    if not rospy.has_param('/use_sim_time'):
        rospy.set_param('/use_sim_time', True)
    if param_bool('~enable_ros_network', True):
        frame = known.scene_frame or rospy.get_param('~scene_frame', 'odom')
        api = GazeboApi(node, scene_frame=frame,
                        scene_markers=param_bool('~scene_markers', False))
        from ode_sim.ros.physics_reconfigure import PhysicsReconfigure
        api.reconfigure = PhysicsReconfigure(api, log=rospy.loginfo).server()
        from ode_sim.ros.world_control import WorldControl
        api.world_control = WorldControl(node, api)
    else:
        rospy.loginfo('ROS gazebo topics/services are disabled')
    rospy.loginfo('ode_sim: world %s loaded (%d models, step %g s, update rate %g Hz%s)%s'
                  % (path, len(world.models), world.physics.max_step_size,
                     world.physics.real_time_update_rate,
                     ', as fast as possible' if world.physics.real_time_update_rate == 0 else '',
                     ', paused' if known.pause else ''))
    node.spin()
    return 0
