"""Waiting for a node's /rosout lines to really reach a test's subscriber (rostest runs no rosout
node: a line published before the subscriber's connection carries data is never seen)."""
import time


def rosout_connected(subscriber, node):
    """True once `subscriber` (a rospy Subscriber on /rosout) lists a connection to `node`."""
    import rosgraph
    import rospy
    try:
        uri = rosgraph.Master(rospy.get_name()).lookupNode(node)
    except Exception:
        return False
    return any(c[1] == uri for c in subscriber.impl.get_stats_info())


class RosoutProbe(object):
    """A condition for a wait loop: true once a line containing `marker` has been received.
    A listed connection is not yet proof that lines flow (roscpp adds the subscriber to its
    publication after answering the handshake; a line logged in between is lost), so `poke()` —
    something that makes the node log such a line, e.g. loading a controller without a type —
    is repeated every `every` seconds until one arrives."""

    def __init__(self, lines, marker, poke, every=2.0):
        self.lines, self.marker, self.poke, self.every = lines, marker, poke, every
        self.poked = None

    def __call__(self):
        if any(self.marker in m for m in list(self.lines)):
            return True
        now = time.monotonic()
        if self.poked is None or now - self.poked > self.every:
            self.poked = now
            self.poke()
        return False
