"""The thread that publishes the current command (Twist) whenever it changes, or at a fixed
repeat rate, and always finishes with a zero Twist."""
import threading
import time

from geometry_msgs.msg import Twist


def make_twist(x=0.0, y=0.0, z=0.0, th=0.0):
    """Twist with linear (x, y, z) [m/s] and angular z = th [rad/s]; angular x/y stay 0."""
    twist = Twist()
    twist.linear.x, twist.linear.y, twist.linear.z = x, y, z
    twist.angular.x = twist.angular.y = 0.0
    twist.angular.z = th
    return twist


class PublishThread(threading.Thread):
    """publisher: anything with publish(msg) and get_num_connections() (a rospy.Publisher).

    rate [Hz]: 0 publishes only on update(); > 0 also re-publishes the last command at that rate.
    """

    # after the final zero Twist, time [s] for rospy's queued publisher to put it on the wire
    # before the process (and its connections) may go away
    LINGER = 0.2

    def __init__(self, publisher, rate=0.0):
        super().__init__(name='teleop_publish', daemon=True)
        self.publisher = publisher
        self.condition = threading.Condition()
        self.command = (0.0, 0.0, 0.0, 0.0)
        self.pending = False
        self.done = False
        self.period = 1.0 / rate if rate > 0.0 else None
        self.start()

    def wait_for_subscribers(self, is_shutdown, sleep, say=print, topic='cmd_vel'):
        """Block until something subscribes; every 2.5 s say that we are waiting."""
        i = 0
        while not is_shutdown() and self.publisher.get_num_connections() == 0:
            if i == 4:
                say('Waiting for subscriber to connect to %s' % topic)
            sleep(0.5)
            i = (i + 1) % 5
        return not is_shutdown()

    def update(self, x, y, z, th):
        """New command: linear x/y/z and angular z (already scaled by speed/turn)."""
        with self.condition:
            self.command = (x, y, z, th)
            self.pending = True
            self.condition.notify()

    def stop(self):
        """Stop the thread; it publishes one zero Twist as its last message. Idempotent."""
        with self.condition:
            self.done = True
            self.condition.notify()
        self.join()

    def run(self):
        while True:
            with self.condition:
                if not self.pending and not self.done:
                    self.condition.wait(self.period)
                if self.done:
                    break
                command = self.command
                self.pending = False
            self.publisher.publish(make_twist(*command))
        self.publisher.publish(make_twist())
        time.sleep(self.LINGER)
