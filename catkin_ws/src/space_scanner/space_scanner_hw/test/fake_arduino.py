#!/usr/bin/python3
"""The Arduino side of the space scanner, faked for tests: subscribes motor_left_cmd /
motor_right_cmd (std_msgs/Int32, wheel speed set-points in rad/s) and publishes the measured
wheel speeds on motor_left_vel / motor_right_vel (std_msgs/Float64) every ~period (sim time,
default 0.02 s). The wheel speed follows the set-point as a first-order lag (~tau, 0.05 s),
as the firmware's PID loop does."""
import rospy
from std_msgs.msg import Float64, Int32


class FakeArduino:
    def __init__(self):
        self.tau = rospy.get_param("~tau", 0.05)
        self.period = rospy.get_param("~period", 0.02)
        self.cmd = {"left": 0.0, "right": 0.0}
        self.vel = {"left": 0.0, "right": 0.0}
        self.pubs = {s: rospy.Publisher("motor_%s_vel" % s, Float64, queue_size=10) for s in self.cmd}
        self.subs = [rospy.Subscriber("motor_%s_cmd" % s, Int32, self.on_cmd, callback_args=s)
                     for s in self.cmd]

    def on_cmd(self, msg, side):
        self.cmd[side] = float(msg.data)

    def step(self, dt):
        a = min(1.0, dt / self.tau) if self.tau > 0 else 1.0
        for s in self.vel:
            self.vel[s] += (self.cmd[s] - self.vel[s]) * a
            self.pubs[s].publish(Float64(self.vel[s]))

    def spin(self):
        rate = rospy.Rate(1.0 / self.period)
        while not rospy.is_shutdown():
            self.step(self.period)
            try:
                rate.sleep()
            except rospy.ROSInterruptException:
                break


if __name__ == "__main__":
    rospy.init_node("fake_arduino")
    FakeArduino().spin()
