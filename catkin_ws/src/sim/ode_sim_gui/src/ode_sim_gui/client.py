"""The window's side of the simulator's client API (docs: notes/sim_client_api.md and
ode_sim's README): the /gazebo/* services and topics, as gzclient talks to gzserver. Never
imports the engine. Callbacks only store the latest message; the Qt thread reads them.
"""
import threading

import rospy
import rosservice
from gazebo_msgs import msg as gm
from gazebo_msgs import srv as gs
from geometry_msgs.msg import Pose as PoseMsg
from std_srvs.srv import Empty

from ode_sim.description.transforms import Pose

try:
    from ode_sim_msgs import msg as om, srv as osrv
except ImportError as e:                     # the workspace is not built / sourced
    raise ImportError('ode_sim_gui: cannot import ode_sim_msgs (%s): build the workspace and '
                      'source devel/setup.bash' % e) from None


class SimError(Exception):
    """A refused or failed call: the message is the one line to show."""


def pose_from_msg(p):
    return Pose.unit((p.position.x, p.position.y, p.position.z),
                     (p.orientation.x, p.orientation.y, p.orientation.z, p.orientation.w))


def msg_from_pose(pose):
    m = PoseMsg()
    m.position.x, m.position.y, m.position.z = (float(v) for v in pose.p)
    m.orientation.x, m.orientation.y, m.orientation.z, m.orientation.w = (float(v) for v in pose.q)
    return m


class SimClient:
    def __init__(self, ns='/gazebo'):
        self.ns = ns.rstrip('/')
        self._lock = threading.Lock()
        self._raw = None
        self._cache = [None, None]
        self.stats = None
        self.version = 0          # bumps on every new pose message
        self._subs = [
            # every model's and link's pose, at most 60 times a wall second (the simulator's
            # /gazebo/pose_info, as Gazebo's ~/pose/info for gzclient: unlike link_states it
            # never makes the simulator publish every step); kept as raw bytes (AnyMsg), only
            # the latest one is decoded, when the view draws
            rospy.Subscriber(self.ns + '/pose_info', rospy.AnyMsg, self._on_poses,
                             queue_size=1, buff_size=2 ** 22),
            rospy.Subscriber(self.ns + '/world_stats', om.WorldStatistics, self._on_stats,
                             queue_size=1),
        ]
        self._proxies = {}

    def close(self):
        for s in self._subs:
            s.unregister()
        self._subs = []

    # -------------------------------------------------------------- topics
    def _on_poses(self, msg):
        with self._lock:
            self._raw = msg
            self.version += 1

    def _on_stats(self, msg):
        self.stats = msg

    def _latest(self):
        with self._lock:
            raw = self._raw
        if raw is None:
            return None
        if self._cache[0] is not raw:
            self._cache = [raw, om.PoseInfo().deserialize(raw._buff)]
        return self._cache[1]

    def poses(self):
        """({'model::link': Pose}, {model: Pose}) from the latest pose message."""
        m = self._latest()
        if m is None:
            return {}, {}
        return ({n: pose_from_msg(p) for n, p in zip(m.link_name, m.link_pose)},
                {n: pose_from_msg(p) for n, p in zip(m.model_name, m.model_pose)})

    def model_names(self):
        m = self._latest()
        return list(m.model_name) if m is not None else None

    # ------------------------------------------------------------ services
    def available(self):
        """True while the simulator offers its world service (it is running)."""
        try:
            return rosservice.get_service_uri(self.ns + '/get_world_sdf') is not None
        except Exception:  # noqa: BLE001 - master unreachable
            return False

    def wait(self, timeout=None):
        rospy.wait_for_service(self.ns + '/get_world_sdf', timeout=timeout)

    def _call(self, name, cls, *args, **kw):
        proxy = self._proxies.get(name)
        if proxy is None:
            proxy = self._proxies[name] = rospy.ServiceProxy(self.ns + '/' + name, cls)
        try:
            res = proxy(*args, **kw)
        except (rospy.ServiceException, rospy.ROSException) as e:
            raise SimError('%s/%s: %s' % (self.ns, name, e)) from None
        if hasattr(res, 'success') and not res.success:
            raise SimError('%s/%s: %s' % (self.ns, name, res.status_message))
        return res

    def world_sdf(self):
        return self._call('get_world_sdf', osrv.GetWorldSDF).sdf

    def pause(self):
        self._call('pause_physics', Empty)

    def unpause(self):
        self._call('unpause_physics', Empty)

    def step(self, steps):
        return self._call('step_world', osrv.StepWorld, steps=int(steps))

    def reset_world(self):
        """Edit -> Reset Model Poses."""
        self._call('reset_world', Empty)

    def reset_simulation(self):
        """Edit -> Reset World."""
        self._call('reset_simulation', Empty)

    def set_model_pose(self, name, pose):
        st = gm.ModelState(model_name=name, pose=msg_from_pose(pose), reference_frame='world')
        self._call('set_model_state', gs.SetModelState, model_state=st)

    def delete_model(self, name):
        self._call('delete_model', gs.DeleteModel, model_name=name)

    def delete_light(self, name):
        self._call('delete_light', gs.DeleteLight, light_name=name)

    def spawn_sdf(self, name, xml, pose):
        self._call('spawn_sdf_model', gs.SpawnModel, model_name=name, model_xml=xml,
                   robot_namespace='', initial_pose=msg_from_pose(pose),
                   reference_frame='world')

    def model_properties(self, name):
        return self._call('get_model_properties', gs.GetModelProperties, model_name=name)

    def link_properties(self, link_name):
        return self._call('get_link_properties', gs.GetLinkProperties, link_name=link_name)
