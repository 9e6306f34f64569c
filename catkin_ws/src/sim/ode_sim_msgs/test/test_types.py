"""ode_sim_msgs: the generated types have the fields of the window API's contract (the desktop
window and the course web page code against them)."""
from ode_sim_msgs.msg import PoseInfo, WorldStatistics
from ode_sim_msgs.srv import GetWorldSDF, StepWorld


def fields(cls):
    return list(zip(cls.__slots__, cls._slot_types))


def test_world_statistics():
    assert fields(WorldStatistics) == [
        ('sim_time', 'time'), ('real_time', 'time'), ('pause_time', 'time'),
        ('iterations', 'uint64'), ('paused', 'bool'), ('real_time_factor', 'float64'),
        ('max_step_size', 'float64')]


def test_get_world_sdf():
    assert GetWorldSDF._type == 'ode_sim_msgs/GetWorldSDF'
    assert fields(GetWorldSDF._request_class) == []
    assert fields(GetWorldSDF._response_class) == [
        ('sdf', 'string'), ('success', 'bool'), ('status_message', 'string')]


def test_step_world():
    assert fields(StepWorld._request_class) == [('steps', 'uint32')]
    assert fields(StepWorld._response_class) == [
        ('success', 'bool'), ('status_message', 'string'), ('sim_time', 'float64'),
        ('iterations', 'uint64')]


def test_pose_info():
    assert fields(PoseInfo) == [
        ('sim_time', 'time'), ('iterations', 'uint64'), ('model_name', 'string[]'),
        ('model_pose', 'geometry_msgs/Pose[]'), ('link_name', 'string[]'),
        ('link_pose', 'geometry_msgs/Pose[]')]
