"""move_base's state machine without a master: planning and its patience/retries, the plan
handed to the controller, goal reached, the controller's patience, oscillation and the
recovery sequence, the three abort texts."""
import pytest

from move_base import core
from move_base.core import (ABORTED, CLEARING, CONTROLLING, CONTROLLING_R, OSCILLATION_R,
                            PLANNING, PLANNING_R, SUCCEEDED, Config, MoveBaseCore)


class Clock:
    def __init__(self):
        self.t = 100.0

    def __call__(self):
        return self.t


class Controller:
    """A local planner whose answers the test sets."""

    def __init__(self):
        self.plans = []
        self.accept = True
        self.reached = False
        self.cmd = 'cmd'

    def set_plan(self, plan):
        self.plans.append(plan)
        return self.accept

    def is_goal_reached(self):
        return self.reached

    def compute_velocity_commands(self):
        return self.cmd


class Behavior:
    def __init__(self, name, log):
        self.behavior_name = name
        self.log = log

    def run_behavior(self):
        self.log.append(('run', self.behavior_name))


class Out(core.Outputs):
    def __init__(self):
        self.log = []

    def zero_velocity(self):
        self.log.append('zero')

    def command(self, cmd):
        self.log.append(('cmd', cmd))

    def recovery_status(self, number, total, name):
        self.log.append(('status', number, total, name))

    def error(self, msg):
        self.log.append(('error', msg))

    def warn_throttle(self, period, msg):
        self.log.append(('warn', msg))


def make(**cfg):
    clock, tc, out = Clock(), Controller(), Out()
    behaviors = [Behavior(n, out.log) for n in ('conservative_reset', 'rotate_recovery',
                                                'aggressive_reset')]
    mb = MoveBaseCore(Config(**cfg), tc, behaviors, out, clock)
    return mb, clock, tc, out


def test_plan_then_control_then_goal_reached():
    mb, clock, tc, out = make()
    mb.start_goal('goal')
    assert (mb.state, mb.run_planner, mb.planner_goal) == (PLANNING, True, 'goal')
    assert mb.cycle((0, 0), True) is None           # no plan yet: keep the planner awake
    mb.plan_done(['p0', 'p1'])
    assert mb.state == CONTROLLING and not mb.run_planner   # planner_frequency 0: plan once
    assert mb.cycle((0, 0), True) is None
    assert tc.plans == [['p0', 'p1']] and out.log == [('cmd', 'cmd')]
    assert mb.cycle((0.1, 0), True) is None
    assert tc.plans == [['p0', 'p1']]                 # the plan is handed over once
    tc.reached = True
    assert mb.cycle((0.2, 0), True) == core.Result(SUCCEEDED, 'Goal reached.')
    assert out.log[-1] == 'zero' and mb.state == PLANNING and not mb.run_planner


def test_planner_frequency_keeps_planning():
    mb, clock, tc, out = make(planner_frequency=1.0)
    mb.start_goal('goal')
    mb.plan_done(['p'])
    assert mb.state == CONTROLLING and mb.run_planner


def test_stale_sensors_stop_the_base_and_keep_the_goal():
    mb, clock, tc, out = make()
    mb.start_goal('goal')
    mb.plan_done(['p'])
    assert mb.cycle((0, 0), False) is None
    assert out.log[-1] == 'zero' and out.log[0][0] == 'warn' and tc.plans == []
    assert mb.cycle((0, 0), True) is None and tc.plans == [['p']]


def test_rejected_plan_aborts():
    mb, clock, tc, out = make()
    tc.accept = False
    mb.start_goal('goal')
    mb.plan_done(['p'])
    assert mb.cycle((0, 0), True) == core.Result(
        ABORTED, 'Failed to pass global plan to the controller.')


def test_planner_patience_then_recoveries_then_abort():
    mb, clock, tc, out = make(planner_patience=5.0)
    mb.start_goal('goal')
    mb.plan_done([])
    assert mb.state == PLANNING and mb.planning_retries == 1    # within patience: retry
    clock.t += 5.5
    mb.plan_done([])
    assert (mb.state, mb.recovery_trigger, mb.run_planner) == (CLEARING, PLANNING_R, False)
    assert out.log == ['zero']
    for i, name in enumerate(('conservative_reset', 'rotate_recovery', 'aggressive_reset')):
        assert mb.cycle((0, 0), True) is None
        assert out.log[-2:] == [('status', i, 3, name), ('run', name)]
        assert (mb.state, mb.run_planner, mb.recovery_index) == (PLANNING, True, i + 1)
        clock.t += 5.5
        mb.plan_done([])
        assert mb.state == CLEARING
    r = mb.cycle((0, 0), True)
    assert r == core.Result(ABORTED, 'Failed to find a valid plan. Even after executing '
                                     'recovery behaviors.')
    assert ('error', 'Aborting because a valid plan could not be found. Even after executing '
                     'all recovery behaviors') in out.log


def test_max_planning_retries():
    mb, clock, tc, out = make(max_planning_retries=1)
    mb.start_goal('goal')
    mb.plan_done([])
    assert mb.state == PLANNING
    mb.plan_done([])
    assert mb.state == CLEARING                  # second failure, no time has passed


def test_a_new_plan_resets_the_planning_recoveries():
    mb, clock, tc, out = make()
    mb.start_goal('goal')
    clock.t += 6
    mb.plan_done([])
    mb.cycle((0, 0), True)                        # first recovery
    assert mb.recovery_index == 1
    mb.plan_done(['p'])
    mb.cycle((0, 0), True)
    assert mb.recovery_index == 0 and mb.state == CONTROLLING


def test_controller_patience():
    mb, clock, tc, out = make(controller_patience=15.0)
    mb.start_goal('goal')
    mb.plan_done(['p'])
    tc.cmd = None
    clock.t += 10
    assert mb.cycle((0, 0), True) is None         # within patience: plan again
    assert (mb.state, mb.run_planner, out.log[-1]) == (PLANNING, True, 'zero')
    mb.plan_done(['p2'])
    clock.t += 16
    assert mb.cycle((0, 0), True) is None
    assert (mb.state, mb.recovery_trigger) == (CLEARING, CONTROLLING_R)
    for _ in range(3):
        mb.cycle((0, 0), True)
        mb.plan_done(['p'])
        mb.cycle((0, 0), True)                    # controlling: fails, patience long gone
    assert mb.recovery_index == 3 and mb.state == CLEARING
    assert mb.cycle((0, 0), True).text == 'Failed to find a valid control. Even after ' \
                                          'executing recovery behaviors.'


def test_oscillation():
    mb, clock, tc, out = make(oscillation_timeout=10.0, oscillation_distance=0.5)
    mb.start_goal('goal')
    mb.plan_done(['p'])
    mb.cycle((0, 0), True)
    clock.t += 8
    mb.cycle((0.6, 0), True)                      # moved far enough: timer reset
    assert mb.last_oscillation_reset == clock.t
    clock.t += 8
    mb.cycle((0.9, 0.3), True)                    # 0.42 m from (0.6, 0): not enough
    assert mb.state == CONTROLLING
    clock.t += 3
    assert mb.cycle((0.9, 0.3), True) is None
    assert (mb.state, mb.recovery_trigger, out.log[-1]) == (CLEARING, OSCILLATION_R, 'zero')
    mb.cycle((0.9, 0.3), True)                    # a recovery resets the timer
    assert mb.recovery_index == 1 and mb.last_oscillation_reset == clock.t
    mb.cycle((2.0, 0.3), True)                    # moving away resets the recovery sequence
    assert mb.recovery_index == 0


def test_oscillation_abort_text():
    mb, clock, tc, out = make(oscillation_timeout=1.0, recovery_behavior_enabled=False)
    mb.start_goal('goal')
    mb.plan_done(['p'])
    mb.cycle((0, 0), True)
    clock.t += 2
    mb.cycle((0, 0), True)
    r = mb.cycle((0, 0), True)
    assert r.status == ABORTED
    assert r.text == 'Robot is oscillating. Even after executing recovery behaviors.'
    assert not any(e[0] == 'run' for e in out.log if isinstance(e, tuple))


def test_no_oscillation_check_without_timeout():
    mb, clock, tc, out = make()
    mb.start_goal('goal')
    mb.plan_done(['p'])
    for _ in range(5):
        clock.t += 100
        assert mb.cycle((0, 0), True) is None
    assert mb.state == CONTROLLING


def test_unknown_position_keeps_the_oscillation_reference():
    mb, clock, tc, out = make(oscillation_timeout=5.0)
    mb.start_goal('goal')
    mb.plan_done(['p'])
    mb.cycle((0, 0), True)
    t0 = mb.last_oscillation_reset
    clock.t += 1
    mb.cycle(None, True)
    assert mb.last_oscillation_reset == t0 and mb.oscillation_position == (0, 0)


@pytest.mark.parametrize('trigger', [PLANNING_R, CONTROLLING_R])
def test_start_goal_resets_everything(trigger):
    mb, clock, tc, out = make()
    mb.state, mb.recovery_trigger, mb.recovery_index, mb.planning_retries = \
        CLEARING, trigger, 2, 4
    clock.t = 500
    mb.start_goal('g2')
    assert (mb.state, mb.recovery_trigger, mb.recovery_index, mb.planning_retries) == \
        (PLANNING, PLANNING_R, 0, 0)
    assert mb.last_valid_plan == mb.last_valid_control == mb.last_oscillation_reset == 500
