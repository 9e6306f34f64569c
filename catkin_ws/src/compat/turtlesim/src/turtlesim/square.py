"""draw_square: drive turtle1 around a 2 m square (forward 1 m/s, turn 0.4 rad/s, stop between)."""
import math
from collections import namedtuple

SIDE = 2.0              #: side of the square, m
SPEED = 1.0             #: forward speed, m/s
TURN_RATE = 0.4         #: turning speed, rad/s
POS_TOLERANCE = 0.1     #: m
ANGLE_TOLERANCE = 0.01  #: rad
STOPPED = 0.0001        #: |v| and |w| below this count as stopped
PERIOD = 0.016          #: control period, s

Goal = namedtuple('Goal', 'x y theta')
FORWARD, STOP_FORWARD, TURN, STOP_TURN = 'FORWARD', 'STOP_FORWARD', 'TURN', 'STOP_TURN'


class SquareDriver:
    """State machine; `step(pose)` returns (linear, angular, event) where event is None,
    'new goal' or 'reached goal' (for the log)."""

    def __init__(self):
        self.state = None
        self.goal = None

    def _forward_goal(self, pose):
        return Goal(pose.x + math.cos(pose.theta) * SIDE, pose.y + math.sin(pose.theta) * SIDE,
                    pose.theta)

    def reached(self, pose):
        g = self.goal
        return (abs(pose.x - g.x) < POS_TOLERANCE and abs(pose.y - g.y) < POS_TOLERANCE
                and abs(pose.theta - g.theta) < ANGLE_TOLERANCE)

    @staticmethod
    def stopped(pose):
        return pose.angular_velocity < STOPPED and pose.linear_velocity < STOPPED

    def step(self, pose):
        if self.state is None:
            self.state, self.goal = FORWARD, self._forward_goal(pose)
            return SPEED, 0.0, 'new goal'
        if self.state in (FORWARD, TURN):
            if self.reached(pose):
                self.state = STOP_FORWARD if self.state == FORWARD else STOP_TURN
                return 0.0, 0.0, 'reached goal'
            return (SPEED, 0.0, None) if self.state == FORWARD else (0.0, TURN_RATE, None)
        # a STOP state: wait until the turtle reports zero velocity, then set the next goal
        if not self.stopped(pose):
            return 0.0, 0.0, None
        if self.state == STOP_FORWARD:
            theta = math.fmod(pose.theta + math.pi / 2.0, 2.0 * math.pi)
            if theta >= math.pi:
                theta -= 2.0 * math.pi
            self.state, self.goal = TURN, Goal(pose.x, pose.y, theta)
            return 0.0, TURN_RATE, 'new goal'
        self.state, self.goal = FORWARD, self._forward_goal(pose)
        return SPEED, 0.0, 'new goal'


def main():
    import rospy
    from geometry_msgs.msg import Twist
    from std_srvs.srv import Empty
    from turtlesim.msg import Pose

    rospy.init_node('draw_square')
    latest = {}
    rospy.Subscriber('turtle1/pose', Pose, lambda p: latest.__setitem__('pose', p), queue_size=1)
    pub = rospy.Publisher('turtle1/cmd_vel', Twist, queue_size=1)
    reset_name = rospy.resolve_name('reset')
    try:
        rospy.wait_for_service(reset_name, timeout=10.0)
        rospy.ServiceProxy(reset_name, Empty)()
    except (rospy.ROSException, rospy.ServiceException) as e:
        rospy.logerr('draw_square: could not call %s (is turtlesim_node running?): %s',
                     reset_name, e)
        return 1
    driver = SquareDriver()

    def on_timer(_event):
        pose = latest.get('pose')
        if pose is None:
            return
        lin, ang, event = driver.step(pose)
        if event == 'new goal':
            g = driver.goal
            rospy.loginfo('New goal [%f %f, %f]', g.x, g.y, g.theta)
        elif event == 'reached goal':
            rospy.loginfo('Reached goal')
        twist = Twist()
        twist.linear.x, twist.angular.z = lin, ang
        pub.publish(twist)

    rospy.Timer(rospy.Duration(PERIOD), on_timer)
    rospy.spin()
    return 0
