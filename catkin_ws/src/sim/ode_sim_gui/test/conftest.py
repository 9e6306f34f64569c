"""The scripted scenarios' ROS node (student_scenario.py, editor_scenario.py: each run by its
test in a process of its own, on that test's roscore)."""
import pytest


@pytest.fixture(scope='module')
def ros():
    import rospy
    rospy.init_node('student', anonymous=True, disable_signals=True)
    yield
    rospy.signal_shutdown('done')
