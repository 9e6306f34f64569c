"""A private roscore on a free port, for tests that must not share a master."""
import os
import tempfile

from course_runtime.proc import Proc, free_port, wait_for


class RosCore:
    """Start `roscore -p PORT`; `env` is os.environ pointed at it (ROS_MASTER_URI, logs,
    unbuffered Python output)."""

    def __init__(self, port=None, log_dir=None):
        self.log_dir = log_dir or tempfile.mkdtemp(prefix='roscore-')
        os.makedirs(self.log_dir, exist_ok=True)
        self.env = dict(os.environ)
        # nodes started with this env print line by line into their log files, as on a
        # terminal (Python buffers 8 KiB when its output is a file)
        self.env.update(ROS_IP='127.0.0.1', ROS_LOG_DIR=self.log_dir, PYTHONUNBUFFERED='1')
        self.env.pop('ROS_HOSTNAME', None)
        self._use_port(port or free_port())
        self.proc = None

    def start(self, timeout=120.0, attempts=3):
        """Start and wait until the master and /rosout answer. A port taken by another process
        between choosing and binding it (tests run concurrently) is retried on a new port.
        roscore is three Python processes (roslaunch, rosmaster, rosout) that need ~1.5 s of
        CPU: on 2 cores at load 24 that took more than 30 s once, hence the generous wait."""
        for attempt in range(attempts):
            self.proc = Proc(['roscore', '-p', str(self.port)], env=self.env,
                             log=os.path.join(self.log_dir, 'roscore.out'))
            try:
                wait_for(self._up, timeout, 0.1, 'roscore on port %d' % self.port)
                return self
            except RuntimeError:
                self.proc.stop()
                if attempt == attempts - 1:
                    raise
                self._use_port(free_port())
        return self

    def _use_port(self, port):
        self.port = port
        self.uri = 'http://127.0.0.1:%d' % port
        self.env['ROS_MASTER_URI'] = self.uri

    def _up(self):
        if not self.proc.alive():
            raise RuntimeError('roscore exited early:\n' + self.proc.output()[-2000:])
        import rosgraph
        try:
            master = rosgraph.Master('/course_runtime', master_uri=self.uri)
            # the master answering must be ours (our roscore's child), not another test's
            if not _descends_from(master.getPid(), self.proc.pid):
                return False
            # /rosout must be up too, or the first nodes lose their log messages
            return '/rosout' in [n for n in _nodes(master)]
        except Exception:
            return False

    def stop(self):
        if self.proc:
            self.proc.stop()
            self.proc = None

    def __enter__(self):
        return self.start()

    def __exit__(self, *exc):
        self.stop()


def _nodes(master):
    pubs, subs, srvs = master.getSystemState()
    names = set()
    for _, nodes in pubs + subs + srvs:
        names.update(nodes)
    return names


def _descends_from(pid, ancestor):
    """True when process `pid` is `ancestor` or one of its descendants (walks /proc ppids)."""
    for _ in range(64):
        if pid == ancestor:
            return True
        if pid <= 1:
            return False
        try:
            with open('/proc/%d/stat' % pid) as f:
                pid = int(f.read().rsplit(')', 1)[1].split()[1])
        except (OSError, ValueError, IndexError):
            return False
    return False
