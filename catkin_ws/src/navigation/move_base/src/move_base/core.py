"""move_base's state machine without ROS (the part of move_base.cpp that is not messaging):
PLANNING / CONTROLLING / CLEARING, the planner's and controller's patience, oscillation
detection and the recovery sequence.

Everything comes in as plain data: times are seconds from an injected clock, the robot's
position is an (x, y) pair, plans and velocity commands are opaque objects handed between the
planners and the outputs. The local planner (``set_plan``, ``is_goal_reached``,
``compute_velocity_commands``) and the recovery behaviours (``run_behavior``,
``behavior_name``) are the nav_core interfaces; what the core sends out goes through an
``out`` object (see ``Outputs``). The node (``move_base.py``) keeps the parameters, the action
server, the planner thread's timing and the topics."""
import math
import threading
from dataclasses import dataclass

PLANNING, CONTROLLING, CLEARING = 'PLANNING', 'CONTROLLING', 'CLEARING'
PLANNING_R, CONTROLLING_R, OSCILLATION_R = 'PLANNING_R', 'CONTROLLING_R', 'OSCILLATION_R'

SUCCEEDED, ABORTED = 'SUCCEEDED', 'ABORTED'

_ABORT_TEXT = {
    CONTROLLING_R: ('Aborting because a valid control could not be found. Even after executing '
                    'all recovery behaviors',
                    'Failed to find a valid control. Even after executing recovery behaviors.'),
    PLANNING_R: ('Aborting because a valid plan could not be found. Even after executing all '
                 'recovery behaviors',
                 'Failed to find a valid plan. Even after executing recovery behaviors.'),
    OSCILLATION_R: ('Aborting because the robot appears to be oscillating over and over. Even '
                    'after executing all recovery behaviors',
                    'Robot is oscillating. Even after executing recovery behaviors.'),
}


@dataclass
class Config:
    """The state machine's parameters with the original's defaults."""
    planner_frequency: float = 0.0
    planner_patience: float = 5.0
    controller_patience: float = 15.0
    max_planning_retries: int = -1
    oscillation_timeout: float = 0.0
    oscillation_distance: float = 0.5
    recovery_behavior_enabled: bool = True


@dataclass(frozen=True)
class Result:
    """How a goal ended: SUCCEEDED or ABORTED with the original's text."""
    status: str
    text: str


class Outputs:
    """What the core sends out; the node publishes, tests record. The defaults do nothing."""

    def zero_velocity(self):
        pass

    def command(self, cmd):
        pass

    def recovery_status(self, number, total, name):
        pass

    def debug(self, msg):
        pass

    def error(self, msg):
        pass

    def warn_throttle(self, period, msg):
        pass


class MoveBaseCore:
    """One goal at a time. Thread-safe the way the original is: the planner thread and the
    control loop share ``lock``; ``planner_cond`` wakes the planner thread."""

    def __init__(self, config, controller, recovery_behaviors, out, clock):
        self.cfg = config
        self.tc = controller
        self.recovery_behaviors = list(recovery_behaviors)
        self.out = out
        self.clock = clock
        self.lock = threading.RLock()
        self.planner_cond = threading.Condition(self.lock)
        self.run_planner = False
        self.planner_goal = None
        self.latest_plan = None
        self.new_global_plan = False
        self.state = PLANNING
        self.recovery_trigger = PLANNING_R
        self.recovery_index = 0
        self.planning_retries = 0
        now = clock()
        self.last_valid_plan = now
        self.last_valid_control = now
        self.last_oscillation_reset = now
        self.oscillation_position = None

    # ---- goal ------------------------------------------------------------------------------
    def start_goal(self, goal):
        """A new goal (already in the planner's frame): plan from scratch."""
        with self.lock:
            self.planner_goal = goal
            self.run_planner = True
            self.state = PLANNING
            self.recovery_index = 0
            self.recovery_trigger = PLANNING_R
            self.planning_retries = 0
            now = self.clock()
            self.last_valid_control = now
            self.last_valid_plan = now
            self.last_oscillation_reset = now
            self._wake()

    def reset(self):
        """resetState: stop planning, back to PLANNING, zero velocity."""
        with self.lock:
            self.run_planner = False
            self.state = PLANNING
            self.recovery_index = 0
            self.recovery_trigger = PLANNING_R
        self.out.zero_velocity()

    def _wake(self):
        self.run_planner = True
        self.planner_cond.notify_all()

    # ---- the planner thread's result -------------------------------------------------------
    def plan_done(self, plan):
        """The planner thread's answer for the current goal (an empty plan is a failure)."""
        with self.lock:
            if plan:
                self.latest_plan = plan
                self.last_valid_plan = self.clock()
                self.planning_retries = 0
                self.new_global_plan = True
                if self.run_planner:
                    self.state = CONTROLLING
                if self.cfg.planner_frequency <= 0:
                    self.run_planner = False
            elif self.state == PLANNING:
                attempt_end = self.last_valid_plan + self.cfg.planner_patience
                self.planning_retries += 1
                retries_exceeded = (self.cfg.max_planning_retries >= 0 and
                                    self.planning_retries > self.cfg.max_planning_retries)
                if self.run_planner and (self.clock() > attempt_end or retries_exceeded):
                    self.state = CLEARING
                    self.run_planner = False
                    self.out.zero_velocity()
                    self.recovery_trigger = PLANNING_R

    # ---- one control cycle -----------------------------------------------------------------
    def track_oscillation(self, position):
        """The robot at (x, y): moving oscillation_distance from where it was resets the
        oscillation timer (and the recovery sequence if oscillation triggered it)."""
        if position is None:
            return
        if self.oscillation_position is None or math.hypot(
                position[0] - self.oscillation_position[0],
                position[1] - self.oscillation_position[1]) >= self.cfg.oscillation_distance:
            self.last_oscillation_reset = self.clock()
            self.oscillation_position = tuple(position)
            if self.recovery_trigger == OSCILLATION_R:
                self.recovery_index = 0

    def cycle(self, position, sensors_current):
        """executeCycle: the robot's position (None when unknown) and whether the local
        costmap's sensors are current. Returns None while the goal is running, else a
        Result."""
        self.track_oscillation(position)
        if not sensors_current:
            self.out.warn_throttle(1.0, 'Sensor data is out of date, we\'re not going to '
                                        'allow commanding of the base for safety')
            self.out.zero_velocity()
            return None
        with self.lock:
            if self.new_global_plan:
                self.new_global_plan = False
                if not self.tc.set_plan(self.latest_plan):
                    self.out.error('Failed to pass global plan to the controller, aborting.')
                    self.reset()
                    return Result(ABORTED, 'Failed to pass global plan to the controller.')
                if self.recovery_trigger == PLANNING_R:
                    self.recovery_index = 0
            state = self.state
        if state == PLANNING:
            with self.lock:
                self._wake()
            return None
        if state == CONTROLLING:
            return self._control()
        return self._clear()

    def _control(self):
        if self.tc.is_goal_reached():
            self.out.debug('Goal reached!')
            self.reset()
            return Result(SUCCEEDED, 'Goal reached.')
        if self.cfg.oscillation_timeout > 0 and \
                self.last_oscillation_reset + self.cfg.oscillation_timeout < self.clock():
            self.out.zero_velocity()
            with self.lock:
                self.state = CLEARING
                self.recovery_trigger = OSCILLATION_R
            return None
        cmd = self.tc.compute_velocity_commands()
        if cmd is not None:
            self.last_valid_control = self.clock()
            self.out.command(cmd)
            if self.recovery_trigger == CONTROLLING_R:
                self.recovery_index = 0
            return None
        self.out.debug('The local planner could not find a valid plan.')
        attempt_end = self.last_valid_control + self.cfg.controller_patience
        with self.lock:
            if self.clock() > attempt_end:
                self.out.zero_velocity()
                self.state = CLEARING
                self.recovery_trigger = CONTROLLING_R
            else:
                self.last_valid_plan = self.clock()
                self.planning_retries = 0
                self.state = PLANNING
                self.out.zero_velocity()
                self._wake()
        return None

    def _clear(self):
        total = len(self.recovery_behaviors)
        if self.cfg.recovery_behavior_enabled and self.recovery_index < total:
            b = self.recovery_behaviors[self.recovery_index]
            self.out.debug('Executing behavior %u of %u' % (self.recovery_index + 1, total))
            self.out.recovery_status(self.recovery_index, total, b.behavior_name)
            b.run_behavior()
            with self.lock:
                self.last_oscillation_reset = self.clock()
                self.state = PLANNING
                self.planning_retries = 0
                self.recovery_index += 1
                self._wake()
            return None
        self.out.debug('All recovery behaviors have failed, locking the planner and disabling '
                       'it.')
        with self.lock:
            self.run_planner = False
            trigger = self.recovery_trigger
        log, text = _ABORT_TEXT.get(trigger, _ABORT_TEXT[OSCILLATION_R])
        self.out.error(log)
        self.reset()
        return Result(ABORTED, text)
