"""TF tree model (no Qt, no ROS): tf2's frame YAML -> frames, edges and dot code."""
import yaml


def parse_frames(frame_yaml):
    """{child: {'parent', 'broadcaster', 'rate', 'buffer_length', 'most_recent_transform',
    'oldest_transform'}} from tf2's all_frames_as_yaml() text ('[]' or '' when empty)."""
    data = yaml.safe_load(frame_yaml) if frame_yaml and frame_yaml.strip() else {}
    if not isinstance(data, dict):
        return {}
    return {str(k): v for k, v in data.items() if isinstance(v, dict)}


def edges(frames):
    """[(parent, child)] sorted."""
    return sorted((str(v.get('parent')), child) for child, v in frames.items())


def roots(frames):
    children = set(frames)
    parents = set(str(v.get('parent')) for v in frames.values())
    return sorted(parents - children)


def edge_label(info):
    return ('"Broadcaster: %s\\nAverage rate: %s\\nBuffer length: %s\\nMost recent transform: %s\\n'
            'Oldest transform: %s"' % (info.get('broadcaster'), info.get('rate'), info.get('buffer_length'),
                                       info.get('most_recent_transform'), info.get('oldest_transform')))


def dot_code(frames, now=None):
    import pydot
    g = pydot.Dot('frames', graph_type='digraph', rankdir='TB', ranksep='0.2', rank='same')

    def q(s):
        return '"%s"' % s
    if not frames:
        g.add_node(pydot.Node(q('No tf data received'), shape='box'))
        return g.to_string()
    names = set(frames) | set(str(v.get('parent')) for v in frames.values())
    for n in sorted(names):
        g.add_node(pydot.Node(q(n), label=q(n), shape='ellipse', URL=q(n), tooltip=q(n)))
    for parent, child in edges(frames):
        g.add_edge(pydot.Edge(q(parent), q(child), label=edge_label(frames[child])))
    if now is not None:
        legend = 'Recorded at time: %.3f' % now
        g.add_node(pydot.Node(q(legend), shape='plaintext'))
        for r in roots(frames):
            g.add_edge(pydot.Edge(q(legend), q(r), style='invis'))
    return g.to_string()
