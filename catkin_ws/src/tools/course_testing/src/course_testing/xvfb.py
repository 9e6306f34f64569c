"""A private Xvfb display and root-window screenshots (imagemagick `import`)."""
import os
import subprocess

from course_testing.proc import Proc, wait_for


def _free_display(start=90):
    for n in range(start, start + 200):
        if not os.path.exists('/tmp/.X11-unix/X%d' % n) and not os.path.exists('/tmp/.X%d-lock' % n):
            return n
    raise RuntimeError('no free X display number between :%d and :%d' % (start, start + 200))


class Xvfb:
    """Start Xvfb on a free display; `env` is os.environ with DISPLAY set to it."""

    def __init__(self, width=1024, height=768, depth=24):
        self.size = (width, height, depth)
        self.display = None
        self.proc = None
        self.env = None

    def start(self, timeout=15.0):
        last = None
        for _ in range(5):  # another process may grab the same number: retry
            n = _free_display()
            self.display = ':%d' % n
            self.proc = Proc(['Xvfb', self.display, '-screen', '0', '%dx%dx%d' % self.size,
                              '-nolisten', 'tcp'])
            try:
                wait_for(lambda: not self.proc.alive() or os.path.exists('/tmp/.X11-unix/X%d' % n),
                         timeout, 0.05, 'Xvfb %s' % self.display)
            except TimeoutError as e:
                last = e
            if self.proc.alive():
                self.env = dict(os.environ, DISPLAY=self.display)
                self.env.pop('QT_QPA_PLATFORM', None)
                return self
            self.proc.stop()
        raise RuntimeError('could not start Xvfb: %s' % last)

    def stop(self):
        if self.proc:
            self.proc.stop(timeout=5.0)
            self.proc = None

    def __enter__(self):
        return self.start()

    def __exit__(self, *exc):
        self.stop()


def screenshot(display, path, window='root'):
    """Save a PNG of the whole screen of `display` (imagemagick's `import`)."""
    subprocess.run(['import', '-display', display, '-window', window, path],
                   check=True, timeout=30, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    return path
