"""rostest check: robot_state_publisher + joint_state_publisher give a transform for every link.

Each package's test/check_tf.py calls `main(package)`. The test reads robot_description, waits
(up to ~time_limit) until tf2 can transform every link into the root link, and checks that the
transform of each fixed joint equals the joint's <origin> and every moving joint is in
/joint_states.
"""
import math
import time
import unittest

from my_robot_model import model_check

TOL = 1e-6


def quaternion_from_rpy(roll, pitch, yaw):
    cr, sr = math.cos(roll / 2), math.sin(roll / 2)
    cp, sp = math.cos(pitch / 2), math.sin(pitch / 2)
    cy, sy = math.cos(yaw / 2), math.sin(yaw / 2)
    return (sr * cp * cy - cr * sp * sy, cr * sp * cy + sr * cp * sy,
            cr * cp * sy - sr * sp * cy, cr * cp * cy + sr * sp * sy)


def main(package, timeout=60.0):
    import rospy
    import rostest
    import tf2_ros
    from sensor_msgs.msg import JointState

    rospy.init_node('check_tf', anonymous=True)

    class TfTree(unittest.TestCase):
        def test_every_link_has_a_transform(self):
            deadline = time.time() + timeout
            while not rospy.has_param('robot_description') and time.time() < deadline:
                time.sleep(0.1)
            model = model_check.parse(rospy.get_param('robot_description'))
            root = model.root()
            buf = tf2_ros.Buffer()
            tf2_ros.TransformListener(buf)
            missing = sorted(model.links)
            while missing and time.time() < deadline and not rospy.is_shutdown():
                missing = [l for l in missing if not buf.can_transform(root, l, rospy.Time(0))]
                time.sleep(0.2)
            self.assertEqual(missing, [], 'no transform %s -> these links' % root)

            for name, j in sorted(model.tree.joints.items()):   # urdf_tree.Joint
                if j.type != 'fixed':
                    continue
                t = buf.lookup_transform(j.parent, j.child, rospy.Time(0)).transform
                xyz, rpy = j.origin.xyz, j.origin.rpy
                got = (t.translation.x, t.translation.y, t.translation.z)
                for a, b in zip(got, xyz):
                    self.assertAlmostEqual(a, b, delta=TOL, msg='joint %s: %s != origin %s' % (name, got, xyz))
                q = quaternion_from_rpy(*rpy)
                r = (t.rotation.x, t.rotation.y, t.rotation.z, t.rotation.w)
                dot = abs(sum(a * b for a, b in zip(q, r)))
                self.assertAlmostEqual(dot, 1.0, delta=1e-6, msg='joint %s: rotation %s != rpy %s' % (name, r, rpy))

            if model.moving_joints():   # joint_state_publisher publishes nothing for a robot of fixed joints
                msg = rospy.wait_for_message('joint_states', JointState, timeout=max(1.0, deadline - time.time()))
                self.assertEqual(sorted(set(msg.name) & set(model.moving_joints())), model.moving_joints(),
                                 'joint_states lacks moving joints')

    rostest.rosrun(package, 'tf_tree', TfTree)
