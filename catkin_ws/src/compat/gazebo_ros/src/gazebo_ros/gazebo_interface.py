"""Client helpers for the simulator's ROS API, with the signatures of gazebo_ros.gazebo_interface.

Each helper waits for its service under `gazebo_namespace` (e.g. '/gazebo'), calls it once and
returns the response's `success`; a failed call is logged and returns False.
"""
import rospy

from gazebo_msgs.srv import SetModelConfiguration, SpawnModel

# The original sleeps 1 s before set_model_configuration (a race in Gazebo, its issue #93);
# ode_sim applies a configuration atomically, so no sleep is needed. Kept as a knob.
SET_MODEL_CONFIGURATION_DELAY = 0.0


def _spawn(service, model_name, model_xml, robot_namespace, initial_pose, reference_frame,
           gazebo_namespace):
    name = gazebo_namespace + '/' + service
    rospy.loginfo('Waiting for service %s', name)
    rospy.wait_for_service(name)
    try:
        rospy.loginfo('Calling service %s', name)
        resp = rospy.ServiceProxy(name, SpawnModel)(
            model_name, model_xml, robot_namespace, initial_pose, reference_frame)
    except (rospy.ServiceException, rospy.ROSException) as e:
        rospy.logerr('Service call failed: %s', e)
        return False
    rospy.loginfo('Spawn status: %s', resp.status_message)
    return resp.success


def spawn_sdf_model_client(model_name, model_xml, robot_namespace, initial_pose, reference_frame,
                           gazebo_namespace):
    """Spawn an SDF model through <gazebo_namespace>/spawn_sdf_model; True on success."""
    return _spawn('spawn_sdf_model', model_name, model_xml, robot_namespace, initial_pose,
                  reference_frame, gazebo_namespace)


def spawn_urdf_model_client(model_name, model_xml, robot_namespace, initial_pose, reference_frame,
                            gazebo_namespace):
    """Spawn a URDF model through <gazebo_namespace>/spawn_urdf_model; True on success."""
    return _spawn('spawn_urdf_model', model_name, model_xml, robot_namespace, initial_pose,
                  reference_frame, gazebo_namespace)


def set_model_configuration_client(model_name, model_param_name, joint_names, joint_positions,
                                   gazebo_namespace):
    """Set joint positions through <gazebo_namespace>/set_model_configuration; True on success."""
    name = gazebo_namespace + '/set_model_configuration'
    rospy.loginfo('Waiting for service %s', name)
    rospy.wait_for_service(name)
    if SET_MODEL_CONFIGURATION_DELAY > 0:
        rospy.sleep(SET_MODEL_CONFIGURATION_DELAY)
    try:
        rospy.loginfo('Calling service %s', name)
        resp = rospy.ServiceProxy(name, SetModelConfiguration)(
            model_name, model_param_name, list(joint_names), list(joint_positions))
    except (rospy.ServiceException, rospy.ROSException) as e:
        rospy.logerr('Service call failed: %s', e)
        return False
    rospy.loginfo('Set model configuration status: %s', resp.status_message)
    return resp.success
