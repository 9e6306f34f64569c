#!/usr/bin/env python3
"""record_states.py SECONDS: records /rig/joint_states (stamp, names, positions, velocities)
until a stamp passes SECONDS of sim time, then prints them as one JSON line."""
import json
import sys
import time

import rospy
from sensor_msgs.msg import JointState


def main():
    until = float(sys.argv[1])
    rospy.init_node('record_states', anonymous=True)
    rows = []
    rospy.Subscriber('/rig/joint_states', JointState,
                     lambda m: rows.append([m.header.stamp.to_nsec(), list(m.name), list(m.position),
                                            list(m.velocity)]), queue_size=1000)
    print('recording', flush=True)
    while not rospy.is_shutdown() and (not rows or rows[-1][0] < until * 1e9):
        time.sleep(0.01)
    print(json.dumps(rows), flush=True)


if __name__ == '__main__':
    main()
