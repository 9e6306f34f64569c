"""A private Xvfb display and root-window screenshots (imagemagick `import`)."""
import os
import select
import subprocess

from course_runtime.proc import Proc

# OpenGL drawn by Mesa's softpipe, which has no JIT: Debian 12's llvmpipe compiles every shader
# with LLVM 15, which crashes now and then inside libLLVM (RViz died at start-up with SIGSEGV
# in libLLVM-15.so.1 in a CI run and in 1 of 5 navigation.rviz runs here; the same crash as
# llvm-project#57850). The same GL 3.3 pictures; the test suite and the lab 3 grader's own
# screen use it, bench/ and users keep llvmpipe (or their GPU).
SOFTWARE_GL = {'GALLIUM_DRIVER': 'softpipe', 'DRAW_USE_LLVM': '0'}


class Xvfb:
    """Start Xvfb on a display number the X server picks itself (-displayfd), so concurrent
    test runs never race for the same number; `env` is os.environ with DISPLAY set.

    -noreset: by default an X server resets itself whenever its last client disconnects, and a
    client connecting during that reset fails with "could not connect to display" — what two
    turtlesim windows of one launch file hit when a short-lived client (a probe, the first
    window's helper connection) had just left. A test's display must simply stay up."""

    def __init__(self, width=1024, height=768, depth=24):
        self.size = (width, height, depth)
        self.display = None
        self.proc = None
        self.env = None

    def start(self, timeout=15.0):
        rfd, wfd = os.pipe()
        try:
            self.proc = Proc(['Xvfb', '-displayfd', str(wfd), '-screen', '0', '%dx%dx%d' % self.size,
                              '-nolisten', 'tcp', '-noreset'], pass_fds=(wfd,))
            os.close(wfd)
            wfd = None
            number = b''
            while not number.endswith(b'\n'):
                ready, _, _ = select.select([rfd], [], [], timeout)
                chunk = os.read(rfd, 16) if ready else b''
                if not chunk:
                    self.stop()
                    raise RuntimeError('Xvfb did not report a display within %.0f s' % timeout)
                number += chunk
        finally:
            os.close(rfd)
            if wfd is not None:
                os.close(wfd)
        self.display = ':%d' % int(number)
        self.env = dict(os.environ, DISPLAY=self.display)
        self.env.pop('QT_QPA_PLATFORM', None)
        return self

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
