"""Lab 3's observer stops waiting once nothing changes any more (no roscore)."""
from grading.lab3 import rules
from grading.lab3.observer import Lab3Observer


def test_settled_only_after_the_graph_and_tf_stay_the_same_with_rviz_up(tmp_path):
    obs = Lab3Observer('123451', str(tmp_path), str(tmp_path))
    res = {'robot_description': '<robot/>'}
    nodes, frames = {'/rviz', '/joint_state_publisher'}, {'base_link'}
    obs.rviz_up = True
    assert obs._settled(0.0, nodes, frames, res) is None
    assert obs._settled(rules.SETTLED - 1, nodes, frames, res) is None
    # a new frame (or node) starts the wait again
    assert obs._settled(rules.SETTLED + 1, nodes, frames | {'arm_link_1'}, res) is None
    assert obs._settled(2 * rules.SETTLED, nodes, frames | {'arm_link_1'}, res) is None
    assert obs._settled(2 * rules.SETTLED + 2, nodes, frames | {'arm_link_1'}, res) == 'settled'
    # RViz not up, or no description yet: the launch limit decides, not this
    for up, desc in ((False, '<robot/>'), (True, None)):
        obs = Lab3Observer('123451', str(tmp_path), str(tmp_path))
        obs.rviz_up = up
        r = {'robot_description': desc}
        assert obs._settled(0.0, nodes, frames, r) is None
        assert obs._settled(10 * rules.SETTLED, nodes, frames, r) is None
