"""The one conversion module: rosgraph's Graph (master + getBusInfo) -> a snapshot dict."""
import rosgraph.impl.graph


class RosGraphData(object):

    def __init__(self, node_ns='/', topic_ns='/'):
        self._graph = rosgraph.impl.graph.Graph(node_ns=node_ns, topic_ns=topic_ns)
        self._graph.set_master_stale(5.0)
        self._graph.set_node_stale(5.0)

    def snapshot(self):
        g = self._graph
        g.update()

        def edges(es):
            return [(e.start, e.end, e.label) for e in es]
        return {
            'nn_nodes': sorted(g.nn_nodes),
            'nt_nodes': sorted(g.nt_nodes),
            'nn_edges': edges(g.nn_edges),
            'nt_edges': [(a, b) for a, b, _ in edges(g.nt_edges)],
            'nt_all_edges': [(a, b) for a, b, _ in edges(g.nt_all_edges)],
            'bad_nodes': {n: ('DEAD' if getattr(v, 'type', None) == rosgraph.impl.graph.BadNode.DEAD else 'WONKY')
                          for n, v in g.bad_nodes.items()},
        }
