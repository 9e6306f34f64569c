"""TF tree model without a roscore."""
from rqt_tf_tree.tf_tree_model import dot_code, edges, parse_frames, roots

YAML = """
base_link: {parent: odom, broadcaster: /robot_state_publisher, rate: 50.2, buffer_length: 4.9,
  most_recent_transform: 12.3, oldest_transform: 7.4}
odom: {parent: map, broadcaster: /amcl, rate: 10.0, buffer_length: 4.8,
  most_recent_transform: 12.2, oldest_transform: 7.4}
laser: {parent: base_link, broadcaster: /robot_state_publisher, rate: 10000.0, buffer_length: 0.0,
  most_recent_transform: 0.0, oldest_transform: 0.0}
"""


def test_tree_of_three_transforms():
    f = parse_frames(YAML)
    assert edges(f) == [('base_link', 'laser'), ('map', 'odom'), ('odom', 'base_link')]
    assert roots(f) == ['map']


def test_dot_has_every_frame_and_labels():
    dot = dot_code(parse_frames(YAML), now=12.5)
    for name in ('map', 'odom', 'base_link', 'laser'):
        assert '"%s"' % name in dot
    assert 'Broadcaster: /amcl' in dot and 'Average rate: 10.0' in dot
    assert 'Recorded at time: 12.500' in dot and 'rankdir=TB' in dot


def test_no_data():
    assert parse_frames('[]') == {} and parse_frames('') == {}
    assert 'No tf data received' in dot_code({})
