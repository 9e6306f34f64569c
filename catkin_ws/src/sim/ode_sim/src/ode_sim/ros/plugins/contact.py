"""Contact sensor plugin: libgazebo_ros_bumper.so (gazebo_plugins noetic-devel 2.9.2) on the
engine's contact sensor (engine/contacts.py, Gazebo's ContactSensor).

In a <sensor type="contact"> whose <contact><collision> elements name collisions of the
sensor's link (as Gazebo names them: a URDF link's collisions are LINK_collision,
LINK_collision_1, ...; those of a link lumped into its parent by a fixed joint
PARENT_fixed_joint_lump__CHILD_collision — a name that is not on the link is an error listing
the names that are, where Gazebo would report nothing). Tags:
  bumperTopicName  default "bumper_states"; relative names go under robotNamespace
  frameName        default "world" (INFO line when missing); resolved with the namespace's
                   tf_prefix parameter as tf::resolve does. As in the original, positions,
                   normals and forces stay in the world frame whatever frameName says: it
                   only fills header.frame_id
  robotNamespace   default: the root namespace
Publishes gazebo_msgs/ContactsState (queue 1) at the sensor's <update_rate> (0 = every physics
step) while someone subscribes: every contact of the sensor's collisions in the steps since its
last update (at most the last 100 steps with contacts), one ContactState per touching pair and
step with collision1 = the sensor's collision (scoped model::link::collision names), the force
and torque on collision1's body per point (torque about the body's centre of mass) and their
sum, points and normals, depths, and the original's "Debug:  i:(k/n) ..." info line. The header
stamp is the sim time of the update.
"""
import rospy
from gazebo_msgs.msg import ContactsState

from ode_sim.ros.plugins.base import Plugin
from ode_sim.ros.plugins.laser import tf_resolve
from ode_sim.ros.plugins.rosio import close


class BumperPlugin(Plugin):
    """libgazebo_ros_bumper.so"""

    sensor_plugin = True

    def __init__(self, ctx, model, desc, sensor=None):
        super().__init__(ctx, model, desc, sensor)
        if sensor is None or sensor.type != 'contact':
            raise self.error('Contact sensor parent is not of type ContactSensor '
                             '(must be inside a <sensor type="contact">)')
        self.ns = self.params['robotNamespace'].strip() if self.has('robotNamespace') else ''
        topic = self.param('bumperTopicName', 'bumper_states', warn=False).strip()
        if not self.has('frameName'):
            rospy.loginfo('bumper plugin missing <frameName>, defaults to world')
        frame = self.param('frameName', 'world', warn=False).strip()
        self.frame_id = tf_resolve(self._ns_tf_prefix(), frame)
        self.link_obj = self.link(sensor.link)
        by_name = {g.shape.name: g for g in self.link_obj.geoms}
        missing = [n for n in sensor.params['collisions'] if n not in by_name]
        if missing:
            raise self.error("contact sensor '%s': no collision named %s on link '%s' "
                             "(its collisions: %s)"
                             % (sensor.name, ', '.join(repr(n) for n in missing),
                                self.link_obj.name, ', '.join(sorted(by_name)) or 'none'))
        self.key = ('contact', model.name, self.link_obj.name, sensor.name, id(self))
        ctx.physics.contacts.watch(self.key, [by_name[n] for n in sensor.params['collisions']])
        self.pub = self.ctx.io.publisher(self.topic(topic), ContactsState, queue_size=1)
        self.set_rate(sensor.update_rate)
        self.messages = 0

    def next_update(self):
        return self._next_due_for(self.pub)

    def update(self):
        if not self.due():
            return
        points = self.ctx.physics.contacts.take(self.key)
        if self.pub.get_num_connections() <= 0:
            return
        from ode_sim.ros.convert import contacts_state
        self.pub.publish(contacts_state(points, self.ctx.now(), self.frame_id))
        self.messages += 1

    def reset(self):
        super().reset()
        self.ctx.physics.contacts.take(self.key)

    def shutdown(self):
        self.ctx.physics.contacts.unwatch(self.key)
        close(self.pub)


PLUGINS = {
    'libgazebo_ros_bumper.so': BumperPlugin,
}
