"""nav_core: the interfaces move_base talks to and the class-name registry that stands in for
pluginlib (the original's plugin names, e.g. navfn/NavfnROS)."""
import importlib

BASE_TYPES = {
    'global': 'nav_core::BaseGlobalPlanner',
    'local': 'nav_core::BaseLocalPlanner',
    'recovery': 'nav_core::RecoveryBehavior',
}

REGISTRY = {
    'global': {
        'navfn/NavfnROS': 'navfn.navfn_ros:NavfnROS',
    },
    'local': {
        'base_local_planner/TrajectoryPlannerROS':
            'base_local_planner.trajectory_planner_ros:TrajectoryPlannerROS',
        'dwa_local_planner/DWAPlannerROS': 'dwa_local_planner.dwa_planner_ros:DWAPlannerROS',
    },
    'recovery': {
        'clear_costmap_recovery/ClearCostmapRecovery':
            'clear_costmap_recovery.clear_costmap_recovery:ClearCostmapRecovery',
        'rotate_recovery/RotateRecovery': 'rotate_recovery.rotate_recovery:RotateRecovery',
    },
}


class PluginError(Exception):
    pass


def resolve_name(kind, name):
    """The registered name for `name` (also the old short class names, e.g. NavfnROS)."""
    table = REGISTRY[kind]
    if name in table:
        return name
    for full in table:
        if full.split('/')[-1] == name:
            return full
    raise PluginError(
        'According to the loaded plugin descriptions the class %s with base class type %s does '
        'not exist. Declared types are  %s' % (name, BASE_TYPES[kind], ' '.join(sorted(table))))


def load_class(kind, name):
    full = resolve_name(kind, name)
    module, cls = REGISTRY[kind][full].split(':')
    try:
        return getattr(importlib.import_module(module), cls)
    except ImportError as e:
        raise PluginError('Failed to load library for %s: %s' % (full, e))


class BaseGlobalPlanner:
    def initialize(self, name, costmap_ros):
        raise NotImplementedError

    def make_plan(self, start, goal):
        """start, goal: geometry_msgs/PoseStamped -> list of PoseStamped ([] on failure)."""
        raise NotImplementedError


class BaseLocalPlanner:
    def initialize(self, name, tf_buffer, costmap_ros):
        raise NotImplementedError

    def set_plan(self, plan):
        raise NotImplementedError

    def compute_velocity_commands(self):
        """geometry_msgs/Twist or None when no valid command was found."""
        raise NotImplementedError

    def is_goal_reached(self):
        raise NotImplementedError


class RecoveryBehavior:
    def initialize(self, name, tf_buffer, global_costmap, local_costmap):
        raise NotImplementedError

    def run_behavior(self):
        raise NotImplementedError
