#!/usr/bin/env python3
"""A ros_control-side client of the bridge contract (doc/ros_control_bridge.md), used by
test_control_bridge_launch.py: answers every NS/ode_sim/joint_states with a joint_commands
message stamped like it — arm held at 0.5 rad (position interface), wheel at 2 rad/s (velocity
interface) — for `seconds` of sim time, then prints one JSON line of what it saw."""
import json
import math
import sys

import rospy
from sensor_msgs.msg import JointState


def main():
    seconds = float(sys.argv[1])
    rospy.init_node('control_client')
    joints = rospy.get_param('/ode_sim/joints')
    period = rospy.get_param('/ode_sim/control_period')
    seen = {'stamps': [], 'arm': [], 'wheel_vel': []}
    pub = rospy.Publisher('/ode_sim/joint_commands', JointState, queue_size=10)

    def on_state(msg):
        t = msg.header.stamp.to_sec()
        seen['stamps'].append(t)
        i = list(msg.name)
        seen['arm'].append(msg.position[i.index('arm_joint')])
        seen['wheel_vel'].append(msg.velocity[i.index('wheel_joint')])
        cmd = JointState()
        cmd.header.stamp = msg.header.stamp
        cmd.name = ['arm_joint', 'wheel_joint']
        cmd.position = [0.5, math.nan]
        cmd.velocity = [math.nan, 2.0]
        pub.publish(cmd)

    rospy.Subscriber('/ode_sim/joint_states', JointState, on_state, queue_size=10)
    while not rospy.is_shutdown() and (not seen['stamps'] or seen['stamps'][-1] < seconds):
        rospy.sleep(0.05)
    # done: leave the lockstep (the simulator stops waiting for a controller that is gone)
    # before reporting, so the simulator never waits for answers that will not come
    pub.unregister()
    seen['joints'] = joints
    seen['period'] = period
    print(json.dumps(seen), flush=True)


if __name__ == '__main__':
    main()
