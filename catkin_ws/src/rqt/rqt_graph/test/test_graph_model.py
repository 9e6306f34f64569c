"""rqt_graph's model without a master: filters, hiding, grouping, dot code and layout parsing."""
from rqt_graph import graph_model as gm

SNAP = {
    'nn_nodes': ['/talker', '/listener', '/rosout', '/cam', '/mover', '/srv'],
    'nt_nodes': [' /chatter', ' /rosout', ' /tf', ' /tf_static', ' /unused', ' /cam/image_raw',
                 ' /cam/image_raw/compressed', ' /cam/image_raw/theora', ' /move/goal', ' /move/cancel',
                 ' /move/status', ' /move/result', ' /move/feedback', ' /srv/parameter_updates',
                 ' /srv/parameter_descriptions'],
    'nn_edges': [('/talker', '/listener', '/chatter'), ('/talker', '/rosout', '/rosout')],
    'nt_edges': [('/talker', ' /chatter'), (' /chatter', '/listener'), ('/talker', ' /rosout'),
                 (' /rosout', '/rosout'), ('/talker', ' /unused'), ('/talker', ' /tf'), (' /tf', '/listener'),
                 ('/mover', ' /tf_static'), (' /tf_static', '/listener'),
                 ('/cam', ' /cam/image_raw'), ('/cam', ' /cam/image_raw/compressed'),
                 ('/cam', ' /cam/image_raw/theora'), (' /cam/image_raw', '/listener'),
                 (' /cam/image_raw/compressed', '/listener'), (' /cam/image_raw/theora', '/listener')]
    + [(' /move/%s' % s, '/mover') for s in ('goal', 'cancel')] + [('/mover', ' /move/%s' % s) for s in
                                                                   ('status', 'result', 'feedback')]
    + [('/listener', ' /move/%s' % s) for s in ('goal', 'cancel')]
    + [(' /move/%s' % s, '/listener') for s in ('status', 'result', 'feedback')]
    + [('/srv', ' /srv/parameter_updates'), (' /srv/parameter_updates', '/listener')],
    'nt_all_edges': [],
    'bad_nodes': {},
}


def test_nodes_only_hides_debug_edges():
    m = gm.build(SNAP)
    assert m.edges == [('/talker', '/listener', '/chatter')]
    assert '/rosout' not in m.nodes


def test_nodes_topics_grouping_and_hiding():
    m = gm.build(SNAP, {'graph_type': gm.NODE_TOPIC})
    assert '/chatter' in m.topics and '/rosout' not in m.topics
    assert '/unused' not in m.topics                           # dead sink / leaf
    assert '/tf' in m.topics and '/tf_static' not in m.topics  # grouped into /tf
    assert '/move/action_topics' in m.topics
    assert '/srv/parameter_updates' not in m.topics           # dynamic reconfigure hidden


def test_groups_off_and_hide_tf():
    m = gm.build(SNAP, {'graph_type': gm.NODE_TOPIC, 'group_actions': False, 'group_tf': False})
    assert '/move/goal' in m.topics and '/tf_static' in m.topics
    m = gm.build(SNAP, {'graph_type': gm.NODE_TOPIC, 'hide_tf_nodes': True})
    assert '/tf' not in m.topics


def test_filters():
    assert gm.matches('/', '/x') and gm.matches('', '/x')
    assert gm.matches('/talker,/listener', '/listener') and not gm.matches('/talker', '/talk')
    assert not gm.matches('-/talker', '/talker') and gm.matches('-/talker', '/other')
    assert gm.matches('/tal.*', '/talker_123')
    m = gm.build(SNAP, {'graph_type': gm.NODE_TOPIC, 'node_filter': '/talker,/listener',
                        'topic_filter': '/chatter'})
    assert m.topics == ['/chatter'] and m.nodes == ['/listener', '/talker']


def test_dead_nodes_are_hidden_or_marked():
    snap = dict(SNAP, bad_nodes={'/listener': 'DEAD'})
    assert gm.build(snap).edges == []
    m = gm.build(snap, {'hide_unreachable': False})
    dot = gm.dot_code(m)
    assert '/listener (DEAD)' in dot and 'color=red' in dot


def test_dot_and_layout():
    m = gm.build(SNAP, {'graph_type': gm.NODE_TOPIC, 'node_filter': '/talker,/listener',
                        'topic_filter': '/chatter'})
    dot = gm.dot_code(m)
    assert '"n_/talker"' in dot and '"t_/chatter"' in dot and 'rankdir=LR' in dot
    width, height, nodes, edges = gm.layout(dot)
    assert set(nodes) == {'n_/talker', 'n_/listener', 't_/chatter'}
    assert nodes['t_/chatter']['shape'] == 'box' and nodes['n_/talker']['shape'] == 'ellipse'
    assert {(e['tail'], e['head']) for e in edges} == {('n_/talker', 't_/chatter'), ('t_/chatter', 'n_/listener')}
    assert nodes['n_/talker']['x'] < nodes['t_/chatter']['x'] < nodes['n_/listener']['x']   # left to right
