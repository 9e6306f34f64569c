"""The computation graph as rqt_graph shows it: filtering and dot code (no Qt, no ROS).

A snapshot is what rosgraph.impl.graph.Graph knows: `nn_nodes` (node names), `nt_nodes`
(topic names), `nn_edges` [(node, node, topic)], `nt_edges` / `nt_all_edges`
[(from, to)] between a node and a topic (either direction), `bad_nodes` {name: 'DEAD'|'WONKY'}.
"""
import re

NODE_NODE, NODE_TOPIC, NODE_TOPIC_ALL = 'node_node', 'node_topic', 'node_topic_all'
GRAPH_TYPES = [('Nodes only', NODE_NODE), ('Nodes/Topics (active)', NODE_TOPIC),
               ('Nodes/Topics (all)', NODE_TOPIC_ALL)]
QUIET_NAMES = ['/diag_agg', '/runtime_logger', '/pr2_dashboard', '/rviz', '/rosout', '/cpu_monitor',
               '/monitor', '/hd_monitor', '/rxloggerlevel', '/clock', '/rqt', '/statistics']
QUIET_EDGE_LABELS = ['/time', '/clock', '/rosout', '/statistics']
TF_TOPICS = ['/tf', '/tf_static']
ACTION_SUFFIXES = ['goal', 'cancel', 'status', 'result', 'feedback']
IMAGE_SUFFIXES = ['image_raw', 'compressed', 'compressedDepth', 'theora']

DEFAULT_OPTIONS = {
    'graph_type': NODE_NODE, 'node_filter': '/', 'topic_filter': '/', 'namespace_cluster': 2,
    'group_actions': True, 'group_tf': True, 'group_images': True, 'hide_dead_sinks': True,
    'hide_leaf_topics': True, 'quiet': True, 'hide_tf_nodes': False, 'hide_unreachable': True,
    'hide_dynamic_reconfigure': True,
}


def parse_filter(text):
    """(includes, excludes) of a comma-separated filter; an empty include list means all."""
    inc, exc = [], []
    for item in (text or '').split(','):
        item = item.strip()
        if not item:
            continue
        (exc if item.startswith('-') else inc).append(item.lstrip('-').strip())
    inc = [i for i in inc if i != '/']
    return inc, exc


def _item_matches(item, name):
    if item == name:
        return True
    if re.search(r'[^a-zA-Z0-9_/]', item):
        try:
            return re.match(item, name) is not None
        except re.error:
            return False
    return False


def matches(filter_text, name):
    inc, exc = parse_filter(filter_text)
    if any(_item_matches(e, name) for e in exc):
        return False
    return not inc or any(_item_matches(i, name) for i in inc)


def _quiet(name):
    return any(q in name for q in QUIET_NAMES)


class GraphModel(object):
    """Filtered nodes, topics and edges, plus the dot code drawing them."""

    def __init__(self):
        self.nodes = []           # node names
        self.topics = []          # topic (or group) names
        self.edges = []           # (from, to, label or None); topic ids have no leading space
        self.bad_nodes = {}
        self.graph_type = NODE_NODE

    def node_ids(self):
        return ['n_' + n for n in self.nodes]

    def topic_ids(self):
        return ['t_' + t for t in self.topics]


def build(snapshot, options=None):
    o = dict(DEFAULT_OPTIONS)
    o.update(options or {})
    m = GraphModel()
    m.graph_type = o['graph_type']
    m.bad_nodes = dict(snapshot.get('bad_nodes', {}))
    nodes = [n.strip() for n in snapshot.get('nn_nodes', [])]

    def node_ok(n):
        if o['quiet'] and _quiet(n):
            return False
        if o['hide_unreachable'] and n in m.bad_nodes:
            return False
        return matches(o['node_filter'], n)

    nodes = [n for n in nodes if node_ok(n)]
    if o['graph_type'] == NODE_NODE:
        m.nodes = sorted(nodes)
        m.edges = sorted(set(_node_node_edges(snapshot, nodes, o)))
        return m

    node_set = set(nodes)
    topics, edges = _node_topic_edges(snapshot, node_set, o)
    rename = _group_renames(topics, o)
    topics = set(rename.get(t, t) for t in topics)
    edges = set((rename.get(a, a), rename.get(b, b), None) for a, b in edges)
    used_nodes = set(x for e in edges for x in e[:2] if x in node_set)
    m.nodes = sorted(used_nodes)
    m.topics = sorted(topics)
    m.edges = sorted(edges, key=lambda e: (e[0], e[1]))
    return m


def _node_node_edges(snapshot, nodes, o):
    """(publisher, subscriber, topic) edges between the shown nodes (node graph)."""
    edges = []
    for a, b, label in snapshot.get('nn_edges', []):
        a, b, label = a.strip(), b.strip(), (label or '').strip()
        if a not in nodes or b not in nodes:
            continue
        if o['quiet'] and label in QUIET_EDGE_LABELS:
            continue
        if o['hide_tf_nodes'] and label in TF_TOPICS:
            continue
        if not matches(o['topic_filter'], label):
            continue
        edges.append((a, b, label))
    return edges


def _topic_ok(t, o):
    if o['quiet'] and _quiet(t):
        return False
    if o['hide_tf_nodes'] and t in TF_TOPICS:
        return False
    if o['hide_dynamic_reconfigure'] and (t.endswith('/parameter_updates') or
                                          t.endswith('/parameter_descriptions')):
        return False
    return matches(o['topic_filter'], t)


def _node_topic_edges(snapshot, node_set, o):
    """(shown topics, [(from, to)] edges between them and the shown nodes) of the node/topic
    graphs, after the topic filters and the dead sink / leaf topic options."""
    raw = snapshot.get('nt_all_edges' if o['graph_type'] == NODE_TOPIC_ALL else 'nt_edges', [])
    all_topics = set(t.strip() for t in snapshot.get('nt_nodes', []))
    edges = []
    for a, b in raw:
        a, b = a.strip(), b.strip()
        if a in all_topics and b in node_set:
            edges.append((a, b))          # topic -> subscriber
        elif b in all_topics and a in node_set:
            edges.append((a, b))          # publisher -> topic
    topics = set(t for e in edges for t in e if t in all_topics)
    topics = set(t for t in topics if _topic_ok(t, o))
    edges = [e for e in edges if (e[0] in topics) != (e[1] in topics)]
    if o['hide_dead_sinks']:
        has_sub = set(a for a, b in edges if a in topics)
        topics = set(t for t in topics if t in has_sub)
    if o['hide_leaf_topics']:
        count = {}
        for a, b in edges:
            for t in (a, b):
                if t in topics:
                    count[t] = count.get(t, 0) + 1
        topics = set(t for t in topics if count.get(t, 0) >= 2)
    return topics, [e for e in edges if e[0] in topics or e[1] in topics]


def _group_by_suffix(topics, suffixes, complete, group_name):
    """{topic: HEAD/group_name} for the topics HEAD/SUFFIX whose HEAD has `complete(tails)`."""
    prefixes = {}
    for t in topics:
        head, _, tail = t.rpartition('/')
        if tail in suffixes:
            prefixes.setdefault(head, set()).add(tail)
    rename = {}
    for head, tails in prefixes.items():
        if complete(tails):
            for tail in tails:
                rename['%s/%s' % (head, tail)] = '%s/%s' % (head, group_name)
    return rename


def _group_renames(topics, o):
    """Grouping of tf, action and image topics: {topic: group node}."""
    rename = {}
    if o['group_tf']:
        for t in TF_TOPICS:
            if t in topics:
                rename[t] = '/tf'
    if o['group_actions']:
        rename.update(_group_by_suffix(topics, ACTION_SUFFIXES,
                                       lambda tails: len(tails) == len(ACTION_SUFFIXES),
                                       'action_topics'))
    if o['group_images']:
        rename.update(_group_by_suffix(topics, IMAGE_SUFFIXES, lambda tails: len(tails) >= 3,
                                       'image_topics'))
    return rename


def dot_code(model, namespace_cluster=0):
    """Graphviz dot code (through pydot) of a model: nodes ellipses, topics boxes."""
    import pydot
    g = pydot.Dot('graphname', graph_type='digraph', rankdir='LR', ranksep='0.2', rank='same',
                  simplify='True', compound='True')

    def q(s):
        return '"%s"' % s

    for n in model.nodes:
        label = n
        url = n
        color = None
        if n in model.bad_nodes:
            url = '%s (%s)' % (n, model.bad_nodes[n])
            color = 'red' if model.bad_nodes[n] == 'DEAD' else 'orange'
        attrs = dict(label=q(label), shape='ellipse', URL=q(url), tooltip=q(url))
        if color:
            attrs['color'] = color
        g.add_node(pydot.Node(q('n_' + n), **attrs))
    for t in model.topics:
        shape = 'box3d' if t.endswith('/action_topics') or t.endswith('/image_topics') else 'box'
        g.add_node(pydot.Node(q('t_' + t), label=q(t), shape=shape, URL=q('topic:' + t),
                              tooltip=q('topic:' + t)))
    topics = set(model.topics)
    for a, b, label in model.edges:
        ida = ('t_' if a in topics and model.graph_type != NODE_NODE else 'n_') + a
        idb = ('t_' if b in topics and model.graph_type != NODE_NODE else 'n_') + b
        attrs = {}
        if label:
            attrs['label'] = q(label)
        g.add_edge(pydot.Edge(q(ida), q(idb), **attrs))
    return g.to_string()


def parse_plain(text):
    """Layout from `dot -Tplain`: (width, height, nodes {id: dict}, edges [dict]) in inches."""
    import shlex
    nodes, edges = {}, []
    width = height = 0.0
    for line in text.splitlines():
        parts = shlex.split(line)
        if not parts:
            continue
        if parts[0] == 'graph':
            width, height = float(parts[2]), float(parts[3])
        elif parts[0] == 'node':
            nodes[parts[1]] = {'x': float(parts[2]), 'y': float(parts[3]), 'w': float(parts[4]),
                               'h': float(parts[5]), 'label': parts[6], 'shape': parts[8]}
        elif parts[0] == 'edge':
            n = int(parts[3])
            pts = [(float(parts[4 + 2 * i]), float(parts[5 + 2 * i])) for i in range(n)]
            rest = parts[4 + 2 * n:]
            label = None
            lpos = None
            if len(rest) >= 5:
                label = rest[0]
                lpos = (float(rest[1]), float(rest[2]))
            edges.append({'tail': parts[1], 'head': parts[2], 'points': pts, 'label': label,
                          'label_pos': lpos})
    return width, height, nodes, edges


def layout(dot, timeout=30):
    """Run graphviz `dot` on dot code; the parsed plain layout."""
    import subprocess
    try:
        out = subprocess.run(['dot', '-Tplain'], input=dot.encode(), stdout=subprocess.PIPE,
                             stderr=subprocess.PIPE, timeout=timeout)
    except FileNotFoundError:
        raise RuntimeError('graphviz "dot" not found (install the graphviz package)')
    if out.returncode != 0:
        raise RuntimeError('dot failed: %s' % out.stderr.decode(errors='replace').strip())
    return parse_plain(out.stdout.decode())
