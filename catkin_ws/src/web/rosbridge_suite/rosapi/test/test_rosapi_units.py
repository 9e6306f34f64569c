"""rosapi's answers from canned master replies, and type definitions (no master)."""
import pytest

from rosapi import graph, objectutils

STATE = [
    [['/turtle1/pose', ['/turtlesim']], ['/rosout', ['/turtlesim', '/rosapi']],
     ['/fib/goal', ['/client']]],
    [['/turtle1/cmd_vel', ['/turtlesim']], ['/rosout', ['/rosout']]],
    [['/spawn', ['/turtlesim']], ['/rosapi/topics', ['/rosapi']]],
]
TYPES = [['/turtle1/pose', 'turtlesim/Pose'], ['/turtle1/cmd_vel', 'geometry_msgs/Twist'],
         ['/rosout', 'rosgraph_msgs/Log']] + \
    [['/fib/' + s, 'x/Y'] for s in graph.ACTION_SUFFIXES]


def test_topics_and_globs():
    topics, types = graph.topics_and_types(TYPES, ['*'])
    assert topics[0] == '/fib/cancel' and len(topics) == len(types) == 8
    assert graph.topics_and_types(TYPES, ['/turtle1/*'])[0] == ['/turtle1/cmd_vel',
                                                                '/turtle1/pose']
    assert graph.topics_for_type(TYPES, 'geometry_msgs/Twist', []) == ['/turtle1/cmd_vel']
    assert graph.topic_type(TYPES, '/rosout', ['/turtle1/*']) == ''


def test_nodes_services_and_details():
    assert graph.nodes(STATE) == ['/client', '/rosapi', '/rosout', '/turtlesim']
    assert graph.services(STATE, ['/spawn']) == ['/spawn']
    subs, pubs, srvs = graph.node_details(STATE, '/turtlesim', [], [])
    assert subs == ['/turtle1/cmd_vel'] and pubs == ['/rosout', '/turtle1/pose']
    assert srvs == ['/spawn']
    assert graph.publishers(STATE, '/rosout', []) == ['/rosapi', '/turtlesim']
    assert graph.subscribers(STATE, '/turtle1/cmd_vel', []) == ['/turtlesim']
    assert graph.service_providers(STATE, '/spawn', []) == ['/turtlesim']
    assert graph.action_servers(TYPES, []) == ['/fib']
    assert graph.host_of_uri('rosrpc://myhost:4567') == 'myhost'


def test_params_cross_as_json():
    assert graph.param_to_json({'a': [1, 2.5]}) == '{"a": [1, 2.5]}'
    assert graph.json_to_param('3') == 3
    with pytest.raises(ValueError) as e:
        graph.json_to_param('hello')
    assert 'must be a JSON-formatted string' in str(e.value)
    assert graph.default_param('') is None and graph.default_param('[1]') == [1]
    assert graph.default_param('plain') == 'plain'
    assert graph.param_names(['/a', '/b/c'], ['/b/*']) == ['/b/c']


def test_typedefs():
    defs = objectutils.message_typedefs('geometry_msgs/PoseWithCovarianceStamped')
    assert [d['type'] for d in defs][:3] == ['geometry_msgs/PoseWithCovarianceStamped',
                                             'std_msgs/Header', 'geometry_msgs/PoseWithCovariance']
    pwc = [d for d in defs if d['type'] == 'geometry_msgs/PoseWithCovariance'][0]
    assert pwc['fieldnames'] == ['pose', 'covariance']
    assert pwc['fieldtypes'] == ['geometry_msgs/Pose', 'float64']
    assert pwc['fieldarraylen'] == [-1, 36] and pwc['examples'] == ['{}', '[]']
    log = objectutils.message_typedefs('rosgraph_msgs/Log')[0]
    assert 'ERROR' in log['constnames'] and log['constvalues'][log['constnames'].index('ERROR')] \
        == '8'
    assert objectutils.full_text('sensor_msgs/Image').count('MSG: std_msgs/Header') == 1
    req = objectutils.service_request_typedefs('std_srvs/SetBool')[0]
    assert req['fieldnames'] == ['data'] and req['fieldtypes'] == ['bool']


def test_private_param_owner():
    nodes = ['/turtlesim', '/rosapi', '/ns/turtlesim']
    assert graph.private_param_owner('/turtlesim/background_r', nodes) == '/turtlesim'
    assert graph.private_param_owner('/ns/turtlesim/x', nodes) == '/ns/turtlesim'
    assert graph.private_param_owner('turtlesim/background_r', nodes) == '/turtlesim'
    assert graph.private_param_owner('/turtlesim', nodes) is None     # the node's name itself
    assert graph.private_param_owner('/turtlesim_extra/x', nodes) is None
    assert graph.private_param_owner('/robot_description', nodes) is None
