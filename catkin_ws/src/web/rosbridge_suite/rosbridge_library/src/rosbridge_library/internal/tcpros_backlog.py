"""rospy listens for TCPROS connections (topics and services) with a backlog of 5: when a
page's parallel service calls open 60 connections to one node at once, the kernel drops the
SYNs past it and the callers time out ("Unable to communicate with service"). Linux lets
listen() be called again on a listening socket to raise it."""


def deepen_tcpros_backlog(backlog=256):
    """Raise this process' TCPROS listen backlog (after rospy started its server); True if
    done."""
    from rospy.impl import tcpros_base
    server = getattr(tcpros_base, '_tcpros_server', None)
    tcp = getattr(server, 'tcp_ros_server', None) if server is not None else None
    sock = getattr(tcp, 'server_sock', None) if tcp is not None else None
    if sock is None:
        return False
    sock.listen(backlog)
    return True
