"""What the /rosapi/* graph services answer, computed from the master's answers (no ROS
imports): `state` is getSystemState's [publishers, subscribers, services] (each a list of
[name, [node, ...]]), `topic_types` is getTopicTypes' [[topic, type], ...]. Globs (fnmatch
patterns) hide whatever they do not match; an empty glob list hides nothing."""
import fnmatch
import json

ACTION_SUFFIXES = ('goal', 'cancel', 'status', 'feedback', 'result')


def allowed(name, globs):
    return not globs or any(fnmatch.fnmatch(name, g) for g in globs)


def filter_names(names, globs):
    return [n for n in names if allowed(n, globs)]


def topics_and_types(topic_types, globs):
    pairs = sorted((t, ty) for t, ty in topic_types if allowed(t, globs))
    return [t for t, _ in pairs], [ty for _, ty in pairs]


def topics_for_type(topic_types, msg_type, globs):
    return sorted(t for t, ty in topic_types if ty == msg_type and allowed(t, globs))


def topic_type(topic_types, topic, globs):
    if not allowed(topic, globs):
        return ''
    return dict(topic_types).get(topic, '')


def services(state, globs):
    return sorted(s for s, _ in state[2] if allowed(s, globs))


def nodes(state):
    found = set()
    for section in state:
        for _, node_list in section:
            found.update(node_list)
    return sorted(found)


def node_details(state, node, topics_globs, services_globs):
    """(subscribing, publishing, services) of one node."""
    pubs = sorted(t for t, ns in state[0] if node in ns and allowed(t, topics_globs))
    subs = sorted(t for t, ns in state[1] if node in ns and allowed(t, topics_globs))
    srvs = sorted(s for s, ns in state[2] if node in ns and allowed(s, services_globs))
    return subs, pubs, srvs


def private_param_owner(name, node_names):
    """The node whose private namespace holds parameter `name` (/turtlesim/background_r ->
    /turtlesim), or None."""
    name = '/' + name.strip('/')
    owners = [n for n in node_names if name.startswith(n.rstrip('/') + '/')]
    return max(owners, key=len) if owners else None


def publishers(state, topic, globs):
    if not allowed(topic, globs):
        return []
    return sorted(dict(state[0]).get(topic, []))


def subscribers(state, topic, globs):
    if not allowed(topic, globs):
        return []
    return sorted(dict(state[1]).get(topic, []))


def service_providers(state, service, globs):
    if not allowed(service, globs):
        return []
    return sorted(dict(state[2]).get(service, []))


def action_servers(topic_types, globs):
    """Namespaces with the five topics of an actionlib server (goal, cancel, status,
    feedback, result)."""
    by_ns = {}
    for topic, _ in topic_types:
        ns, _, leaf = topic.rpartition('/')
        if leaf in ACTION_SUFFIXES and ns:
            by_ns.setdefault(ns, set()).add(leaf)
    return sorted(ns for ns, leaves in by_ns.items()
                  if len(leaves) == len(ACTION_SUFFIXES) and allowed(ns, globs))


def host_of_uri(uri):
    """'rosrpc://host:port' -> 'host'."""
    if not uri:
        return ''
    rest = uri.split('://', 1)[-1]
    return rest.rsplit(':', 1)[0] if ':' in rest else rest.split('/', 1)[0]


# ---------------------------------------------------------------------------- parameters
def param_to_json(value):
    return json.dumps(value)


def json_to_param(text):
    """SetParam's value: JSON text (anything else is refused, as the original)."""
    try:
        return json.loads(text)
    except ValueError:
        raise ValueError('Due to the type flexibility of the ROS parameter server, the value '
                         'argument to set_param must be a JSON-formatted string.')


def default_param(text):
    """GetParam's default: '' -> None (null), JSON text -> its value, other text -> itself."""
    if text == '':
        return None
    try:
        return json.loads(text)
    except ValueError:
        return text


def param_names(names, globs):
    return sorted(n for n in names if allowed(n, globs))
