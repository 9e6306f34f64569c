"""What bench/navigation/run watches while move_base drives the robot (commands, recoveries,
the simulator's contacts, the local planner's believed pose), the simulator's robot (pose,
teleport) and the summary the bench prints. Needs rospy (a sourced workspace)."""
import math
import time

from course_runtime.geometry import yaw_of


class Watch:
    """Subscriptions that record, for the goal being driven: move_base's commands (sim time,
    v, w), its recoveries, the contact sensors' touches of anything but the floor (sim time of
    the step, robot collision, other collision, depth) and what the local planner believed
    (the first and last pose of its local plan, in the map frame)."""

    def __init__(self, contact_links, floor):
        import rospy
        import tf2_ros
        from gazebo_msgs.msg import ContactsState
        from geometry_msgs.msg import Twist
        from move_base_msgs.msg import RecoveryStatus
        from nav_msgs.msg import Path
        self.floor = floor
        self.cmds, self.recoveries, self.touches, self.beliefs = [], [], [], []
        self.heard = {}                      # sensor topic -> [messages, floor contacts]
        rospy.Subscriber('/diffbot_controller/cmd_vel', Twist,
                         lambda m: self.cmds.append((rospy.Time.now().to_sec(), m.linear.x,
                                                     m.angular.z)), queue_size=50)
        for link in contact_links:
            rospy.Subscriber('/bench_contacts/%s' % link, ContactsState, self._contacts,
                             callback_args='/bench_contacts/%s' % link, queue_size=100)
        # the local plan's first pose (odom frame) taken to the map frame with map -> odom at
        # the plan's stamp (diagnostics: the belief's error against the simulator's pose)
        self.tf_buffer = tf2_ros.Buffer(rospy.Duration(30.0))
        tf2_ros.TransformListener(self.tf_buffer)
        rospy.Subscriber('/move_base/TrajectoryPlannerROS/local_plan', Path, self._local_plan,
                         queue_size=20)
        rospy.Subscriber('/move_base/recovery_status', RecoveryStatus,
                         lambda m: self.recoveries.append((rospy.Time.now().to_sec(),
                                                           m.recovery_behavior_name)),
                         queue_size=10)

    def clear(self):
        for records in (self.cmds, self.recoveries, self.beliefs, self.touches):
            del records[:]

    def _contacts(self, msg, topic):
        seen = self.heard.setdefault(topic, [0, 0])
        seen[0] += 1
        for s in msg.states:
            if s.collision2_name.split('::')[0] == self.floor:
                seen[1] += 1
                continue
            t = float(s.info.rsplit('time:', 1)[1]) if 'time:' in s.info \
                else msg.header.stamp.to_sec()
            self.touches.append((t, s.collision1_name, s.collision2_name, max(s.depths or [0.0])))

    def _local_plan(self, msg):
        import rospy
        if not msg.poses:
            return
        try:
            t = self.tf_buffer.lookup_transform('map', msg.header.frame_id, msg.header.stamp,
                                                rospy.Duration(0.3))
        except Exception:
            return
        tyaw = yaw_of(t.transform.rotation)
        c, s = math.cos(tyaw), math.sin(tyaw)
        out = []
        for k in (0, len(msg.poses) - 1):
            p = msg.poses[k].pose
            out += [t.transform.translation.x + c * p.position.x - s * p.position.y,
                    t.transform.translation.y + s * p.position.x + c * p.position.y,
                    yaw_of(p.orientation) + tyaw]
        self.beliefs.append([msg.header.stamp.to_sec()] + out)


class SimRobot:
    """The simulator's model 'robot': its pose (ground truth) and a teleport that clears
    move_base's costmaps; step_s is the physics step [s]."""

    def __init__(self):
        import rospy
        from gazebo_msgs.srv import GetModelState, GetPhysicsProperties, SetModelState
        from std_srvs.srv import Empty
        rospy.wait_for_service('/gazebo/get_model_state', 120)
        self.get_state = rospy.ServiceProxy('/gazebo/get_model_state', GetModelState,
                                            persistent=True)
        self.set_state = rospy.ServiceProxy('/gazebo/set_model_state', SetModelState)
        self.clear = rospy.ServiceProxy('/move_base/clear_costmaps', Empty)
        self.step_s = rospy.ServiceProxy('/gazebo/get_physics_properties',
                                         GetPhysicsProperties)().time_step

    def teleport(self, x, y, yaw):
        import rospy
        from gazebo_msgs.msg import ModelState
        cur = self.get_state('robot', '').pose
        st = ModelState()
        st.model_name = 'robot'
        st.reference_frame = 'world'
        st.pose.position.x, st.pose.position.y, st.pose.position.z = x, y, cur.position.z + 0.02
        st.pose.orientation.z, st.pose.orientation.w = math.sin(yaw / 2), math.cos(yaw / 2)
        self.set_state(st)
        t = rospy.Time.now().to_sec()
        while rospy.Time.now().to_sec() < t + 1.5:
            time.sleep(0.05)
        self.clear()

    def pose(self, stamped=False):
        st = self.get_state('robot', '')
        p = st.pose
        out = (p.position.x, p.position.y, yaw_of(p.orientation))
        return (st.header.stamp.to_sec(), out) if stamped else out


def print_summary(results, traces, heard, step_s, reach, contact_links):
    """The bench's closing figures against their targets. results: per goal (reached, sim s,
    driven, shortest, ratio, footprint poses, commands Hz, map-cell poses, least clearance,
    contact steps, depth, touched pairs)."""
    n = len(results)
    reached = [r for r in results if r[0]]
    ratios = sorted(r[4] for r in reached)
    collisions = sum(r[5] for r in results)
    sim_time = sum(r[1] for r in results)
    hz = sum(r[6] * r[1] for r in results) / max(sim_time, 1e-6)
    print()
    print('goals reached      %d / %d = %.0f %%   (target >= 95 %%)'
          % (len(reached), n, 100.0 * len(reached) / n))
    touched = sorted({pair for r in results for pair in r[11]})
    silent = ['/bench_contacts/%s' % l for l in contact_links
              if not heard.get('/bench_contacts/%s' % l, [0, 0])[0]]
    if silent:
        print('contact sensors    NO MESSAGES from %s: the collision count below is not '
              'measured' % ', '.join(silent))
    else:
        print('contact sensors    %d messages from %d sensors, %d wheel-floor contact states in '
              'them (the sensors see what they touch)'
              % (sum(v[0] for v in heard.values()), len(heard),
                 sum(v[1] for v in heard.values())))
    print('collisions         the simulator: %d physics steps (%.2f s) in contact in %d goals, '
          'deepest %.4f m   (target 0)'
          % (sum(r[9] for r in results), sum(r[9] for r in results) * step_s,
             sum(1 for r in results if r[9]), max(r[10] for r in results)))
    for a, b in touched:
        print('                   touched: %s - %s' % (a.split('::', 1)[1], b))
    print('footprint          %d poses where the padded diploma footprint overlaps the world in '
          '%d goals, least clearance %.3f m (map-cell test: %d poses)'
          % (collisions, sum(1 for r in results if r[5]), min(r[8] for r in results),
             sum(r[7] for r in results)))
    if ratios:
        print('path / shortest    median %.2f, worst %.2f   (target <= 1.2)'
              % (ratios[len(ratios) // 2], ratios[-1]))
    print('controller rate    %.2f Hz achieved / 10 Hz set = %.2f   (target >= 0.95)'
          % (hz, hz / 10.0))
    if reach:
        half, vmax = reach
        every = [c for tr in traces for c in tr['cmds']]
        beyond = [c for c in every if abs(c[1]) + abs(c[2]) * half > vmax + 1e-9]
        print("commands beyond    %d of %d = %.0f %% ask a wheel for more than it drives "
              "(|v| + |w| * %.3f m > %.3f m/s: the robot turns less than planned)"
              % (len(beyond), len(every), 100.0 * len(beyond) / max(len(every), 1), half, vmax))
