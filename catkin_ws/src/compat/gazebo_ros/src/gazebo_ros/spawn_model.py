"""spawn_model: put a URDF or SDF model into the simulator through <gazebo_namespace>/spawn_*_model.

The command line is gazebo_ros' `spawn_model` (ROS Noetic): exactly one format (-urdf | -sdf),
exactly one source (-file | -param | -database | -stdin), -model NAME, the initial pose, -J
joint positions, -unpause, -wait, -package_to_model and -b (bond). The pure parts (arguments,
loading and checking the XML, the pose) need no ROS master and are unit-tested;
`SpawnModelNode.run` does the service calls.
"""
import argparse
import math
import os
import signal
import sys
import threading
import xml.etree.ElementTree as ET
from urllib.parse import urlsplit, urlunsplit

DEFAULT_GAZEBO_NAMESPACE = '/gazebo'


class SpawnError(Exception):
    """A problem with the input; str() is the one line the user sees."""


def build_parser(default_robot_namespace='/'):
    parser = argparse.ArgumentParser(
        prog='spawn_model', description='Spawn a model in the simulator using the ROS API')
    fmt = parser.add_mutually_exclusive_group(required=True)
    fmt.add_argument('-urdf', action='store_true', help='the model XML is URDF')
    fmt.add_argument('-sdf', action='store_true', help='the model XML is SDF')
    src = parser.add_mutually_exclusive_group(required=True)
    src.add_argument('-file', metavar='FILE_NAME', help='load the model XML from a file')
    src.add_argument('-param', metavar='PARAM_NAME', help='load the model XML from a ROS parameter')
    src.add_argument('-database', metavar='MODEL_NAME',
                     help='spawn model://MODEL_NAME (an <include> the simulator finds on '
                          'GAZEBO_MODEL_PATH, ~/.gazebo/models, its library or the model database)')
    src.add_argument('-stdin', action='store_true', help='read the model XML from standard input')
    parser.add_argument('-model', required=True, metavar='MODEL_NAME', help='name of the model')
    parser.add_argument('-reference_frame', default='',
                        help='model/link the initial pose is relative to ("" or "world": world)')
    parser.add_argument('-gazebo_namespace', default=DEFAULT_GAZEBO_NAMESPACE,
                        help='ROS namespace of the simulator interface (default /gazebo)')
    parser.add_argument('-robot_namespace', default=default_robot_namespace,
                        help='ROS namespace given to the model plugins (default: this node\'s)')
    parser.add_argument('-unpause', action='store_true', help='unpause physics after spawning')
    parser.add_argument('-wait', metavar='MODEL_NAME',
                        help='wait until this model is in <gazebo_namespace>/model_states')
    for axis, what in (('x', 'x of the initial position, m'), ('y', 'y of the initial position, m'),
                       ('z', 'z of the initial position, m'), ('R', 'roll, rad'),
                       ('P', 'pitch, rad'), ('Y', 'yaw, rad')):
        parser.add_argument('-' + axis, type=float, default=0.0, help=what)
    parser.add_argument('-J', dest='joints', default=[], action='append', nargs=2,
                        metavar=('JOINT_NAME', 'JOINT_POSITION'),
                        help='initial position of a joint (repeatable)')
    parser.add_argument('-package_to_model', action='store_true',
                        help='rewrite <mesh filename="package://..."> to model://...')
    parser.add_argument('-b', dest='bond', action='store_true',
                        help='delete the model when this program is interrupted')
    return parser


def parse_args(argv, default_robot_namespace='/'):
    """Parse the arguments (without the program name and ROS remappings); argparse exits with
    status 2 and a usage line on bad ones."""
    parser = build_parser(default_robot_namespace)
    args = parser.parse_args(argv)
    joints = []
    for name, value in args.joints:
        try:
            joints.append((name, float(value)))
        except ValueError:
            parser.error('-J %s %s: the joint position is not a number' % (name, value))
    args.joints = joints
    return args


# ---------------------------------------------------------------------------------- model XML

# What the original's -database sends: an include that the simulator resolves as gzserver does
# (GAZEBO_MODEL_PATH, ~/.gazebo/models, the model library, then the model database), so the
# spawned model stays a model:// include (ode_sim's Save World writes it back as one).
MODEL_DATABASE_TEMPLATE = """\
<sdf version="1.4">
    <world name="default">
        <include>
            <uri>model://{}</uri>
        </include>
    </world>
</sdf>"""


def database_include(name):
    """The SDF -database MODEL_NAME sends: the original's <sdf><world><include> of model://NAME
    (the simulator applies the request's model name and initial pose, and finds the model)."""
    return MODEL_DATABASE_TEMPLATE.format(name)


def read_file(path):
    if not os.path.exists(path):
        raise SpawnError('Error: specified file %s does not exist' % path)
    if not os.path.isfile(path):
        raise SpawnError('Error: specified file %s is not a file' % path)
    try:
        with open(path, encoding='utf-8') as f:
            text = f.read()
    except (OSError, UnicodeDecodeError) as e:
        raise SpawnError('Error reading file %s: %s' % (path, e))
    if not text.strip():
        raise SpawnError('Error: file %s is empty' % path)
    return text


def load_model_xml(args, get_param=None, stdin=None):
    """The model XML named by the source argument. `get_param(name)` returns the parameter's
    value or None; `stdin` is a file to read for -stdin; -database gives
    database_include(MODEL_NAME)."""
    if args.file:
        return read_file(args.file)
    if args.param:
        value = get_param(args.param) if get_param else None
        if not isinstance(value, str) or not value.strip():
            raise SpawnError('Error: param %s does not exist or is empty' % args.param)
        return value
    if args.database:
        return database_include(args.database)
    if args.stdin:
        text = (stdin if stdin is not None else sys.stdin).read()
        if not text.strip():
            raise SpawnError('Error: stdin buffer was empty')
        return text
    raise SpawnError('no model source given (-file, -param, -database or -stdin)')


def package_to_model(root):
    """Rewrite package://PKG/... mesh filenames under `root` to model://PKG/...; returns the
    number of rewritten meshes."""
    count = 0
    for mesh in root.iter('mesh'):
        filename = mesh.get('filename')
        if filename is None:
            continue
        url = urlsplit(filename)
        if url.scheme == 'package':
            mesh.set('filename', urlunsplit(('model',) + tuple(url[1:])))
            count += 1
    return count


def process_xml(text, rewrite_package_uris=False):
    """Check that `text` is well-formed XML ("Invalid XML: ..." otherwise); with
    rewrite_package_uris, return it with package:// mesh URIs rewritten to model://.
    Otherwise the text is returned unchanged (comments, namespaces and declaration kept)."""
    try:
        root = ET.fromstring(text.encode('utf-8') if isinstance(text, str) else text)
    except ET.ParseError as e:
        raise SpawnError('Invalid XML: %s' % e)
    if rewrite_package_uris and package_to_model(root):
        return ET.tostring(root, encoding='unicode')
    return text


# ---------------------------------------------------------------------------------------- pose

def quaternion_from_euler(roll, pitch, yaw):
    """(x, y, z, w) of rotations about the static axes x (roll), y (pitch), z (yaw) in that
    order: tf.transformations.quaternion_from_euler's default 'sxyz' convention."""
    cr, sr = math.cos(roll / 2.0), math.sin(roll / 2.0)
    cp, sp = math.cos(pitch / 2.0), math.sin(pitch / 2.0)
    cy, sy = math.cos(yaw / 2.0), math.sin(yaw / 2.0)
    return (sr * cp * cy - cr * sp * sy,
            cr * sp * cy + sr * cp * sy,
            cr * cp * sy - sr * sp * cy,
            cr * cp * cy + sr * sp * sy)


def initial_pose(args):
    """geometry_msgs/Pose from -x -y -z -R -P -Y."""
    from geometry_msgs.msg import Point, Pose, Quaternion
    return Pose(Point(args.x, args.y, args.z),
                Quaternion(*quaternion_from_euler(args.R, args.P, args.Y)))


# ---------------------------------------------------------------------------------------- node

class SpawnModelNode:
    """The ROS side: wait, spawn, configure joints, unpause, hold the bond."""

    def __init__(self, args):
        self.args = args
        self._model_seen = False
        self._delete_lock = threading.Lock()
        self._deleted = False

    def _models_cb(self, msg):
        if self.args.wait in msg.name:
            self._model_seen = True

    def wait_for_model(self):
        """Block until -wait's model is in model_states; False when ROS shut down first."""
        import rospy
        from gazebo_msgs.msg import ModelStates
        sub = rospy.Subscriber(self.args.gazebo_namespace + '/model_states', ModelStates,
                               self._models_cb, queue_size=1)
        rospy.loginfo('Waiting for model %s before proceeding.', self.args.wait)
        rate = rospy.Rate(10)
        try:
            while not rospy.is_shutdown() and not self._model_seen:
                rate.sleep()
        except rospy.ROSInterruptException:
            pass
        sub.unregister()
        return self._model_seen

    def _get_param(self, name):
        import rospy
        return rospy.get_param(name, None)

    def run(self):
        """Exit status: 0 success, 1 failure."""
        import rospy
        from gazebo_ros import gazebo_interface
        args = self.args
        if args.wait and not self.wait_for_model():
            return 0
        try:
            if args.file:
                rospy.loginfo('Loading model XML from file %s', args.file)
            elif args.param:
                rospy.loginfo('Loading model XML from ros parameter %s', args.param)
            elif args.database:
                rospy.loginfo('Loading model XML from Gazebo Model Database')
            else:
                rospy.loginfo('Loading model XML from stdin')
            model_xml = load_model_xml(args, get_param=self._get_param)
            model_xml = process_xml(model_xml, args.package_to_model)
        except SpawnError as e:
            rospy.logerr('%s', e)
            return 1

        spawn = (gazebo_interface.spawn_urdf_model_client if args.urdf
                 else gazebo_interface.spawn_sdf_model_client)
        if not spawn(args.model, model_xml, args.robot_namespace, initial_pose(args),
                     args.reference_frame, args.gazebo_namespace):
            rospy.logerr('Spawn service failed. Exiting.')
            return 1

        if args.joints:
            if not gazebo_interface.set_model_configuration_client(
                    args.model, '', [j[0] for j in args.joints], [j[1] for j in args.joints],
                    args.gazebo_namespace):
                rospy.logerr('SetModelConfiguration service failed. Exiting.')
                return 1

        if args.unpause:
            from std_srvs.srv import Empty
            name = args.gazebo_namespace + '/unpause_physics'
            rospy.loginfo('Unpausing physics')
            rospy.wait_for_service(name)
            try:
                rospy.ServiceProxy(name, Empty)()
            except rospy.ServiceException as e:
                rospy.logerr('Unpause physics service call failed: %s', e)
                return 1

        if args.bond:
            # Ctrl-C / SIGTERM only set a flag: the model is deleted here, in the main thread. A
            # signal handler that logs and calls a service can deadlock when the signal lands
            # while the main thread itself is inside a log call (rospy's /rosout publisher lock).
            # Shut down otherwise (rosnode kill), rospy's shutdown hook deletes it.
            interrupted = threading.Event()
            for sig in (signal.SIGINT, signal.SIGTERM):
                signal.signal(sig, lambda *_: interrupted.set())
            rospy.on_shutdown(self.delete_model)
            rospy.loginfo('Waiting for shutdown to delete model %s', args.model)
            while not interrupted.wait(0.1) and not rospy.is_shutdown():
                pass
            if interrupted.is_set():
                self.delete_model()
                rospy.signal_shutdown('spawn_model -b interrupted')
        return 0

    def delete_model(self):
        """Deletes the model of -b once: on an interrupt (main thread) or as rospy's shutdown
        hook, which runs before rospy stops, so the service call still works."""
        import rospy
        from gazebo_msgs.srv import DeleteModel
        with self._delete_lock:
            if self._deleted:
                return
            self._deleted = True
        rospy.loginfo('Deleting model %s', self.args.model)
        try:
            rospy.ServiceProxy(self.args.gazebo_namespace + '/delete_model', DeleteModel)(
                model_name=self.args.model)
        except (rospy.ServiceException, rospy.ROSException) as e:
            rospy.logerr('Delete model service call failed: %s', e)


def main(argv=None):
    import rospy
    argv = rospy.myargv(sys.argv if argv is None else argv)
    # rospy.get_namespace() already honours __ns:= and ROS_NAMESPACE before init_node
    args = parse_args(argv[1:], rospy.get_namespace())
    rospy.init_node('spawn_model', anonymous=True)
    try:
        return SpawnModelNode(args).run()
    except rospy.ROSInterruptException:
        return 1
