"""Python side of the simavr harness for tests: build sketches once per session (cached in
build/firmware), run one on the emulated Mega, talk to its side channel."""
import os
import queue
import subprocess
import threading
import time

FIRMWARE = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SKETCHES = os.path.join(FIRMWARE, 'sketches')
# practical work 7's sketches are rosserial_arduino's own examples (one copy, in ros_lib)
EXAMPLES = os.path.join(os.path.dirname(FIRMWARE), 'catkin_ws', 'src', 'rosserial',
                        'rosserial_arduino', 'src', 'ros_lib', 'examples')
EXAMPLE_NAMES = {'hello_world': 'HelloWorld', 'blink': 'Blink', 'ultrasound': 'Ultrasound',
                 'service_server': 'ServiceServer'}


def build(sketch, env=None, timeout=600):
    """firmware/build SKETCH → path of the ELF (raises with the build output on failure)."""
    if os.path.isdir(sketch):
        path = sketch
    elif sketch in EXAMPLE_NAMES:
        path = os.path.join(EXAMPLES, EXAMPLE_NAMES[sketch])
    else:
        path = os.path.join(SKETCHES, sketch)
    p = subprocess.run([os.path.join(FIRMWARE, 'build'), path], env=env, timeout=timeout,
                       stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    if p.returncode != 0:
        raise RuntimeError('firmware/build %s failed:\n%s' % (sketch, p.stdout[-4000:]))
    return p.stdout.strip().splitlines()[-1]


class Simulation(object):
    """firmware/simulate ELF: `.pty` is UART0's pty; `.events` collects the side-channel lines
    (e.g. 'pin 13 1 1234.5'); command() writes to its stdin."""

    def __init__(self, elf, *args, env=None, timeout=30.0):
        import tempfile
        # stderr to a file, never a pipe nobody reads: a full pipe would stall the simulator
        self._err = tempfile.TemporaryFile(mode='w+')
        self.proc = subprocess.Popen([os.path.join(FIRMWARE, 'simulate'), elf] + list(args),
                                     stdin=subprocess.PIPE, stdout=subprocess.PIPE,
                                     stderr=self._err, text=True, env=env,
                                     start_new_session=True)
        self.lines = queue.Queue()
        self.events = []
        self.lock = threading.Lock()
        first = self.proc.stdout.readline()
        if not first.startswith('pty: '):
            self.stop()
            raise RuntimeError('firmware/simulate did not print its pty: %r %s'
                               % (first, self.stop()))
        self.pty = first.split(' ', 1)[1].strip()
        self.stderr = ''
        self.reader = threading.Thread(target=self._read, daemon=True)
        self.reader.start()

    def _read(self):
        for line in self.proc.stdout:
            with self.lock:
                self.events.append(line.strip())

    def events_starting(self, prefix):
        with self.lock:
            return [e for e in self.events if e.startswith(prefix)]

    def command(self, text):
        self.proc.stdin.write(text + '\n')
        self.proc.stdin.flush()

    def wait_event(self, prefix, count=1, timeout=60.0):
        end = time.monotonic() + timeout
        while time.monotonic() < end:
            found = self.events_starting(prefix)
            if len(found) >= count:
                return found
            if self.proc.poll() is not None:
                break
            time.sleep(0.05)
        raise AssertionError('simulator: %d "%s" event(s) not seen within %.0f s (have %r)'
                             % (count, prefix, timeout, self.events[-10:]))

    def stop(self):
        """Stop it (SIGTERM); returns its stderr (speed report)."""
        if self.proc.poll() is None:
            self.proc.terminate()
            try:
                self.proc.wait(10)
            except subprocess.TimeoutExpired:
                self.proc.kill()
                self.proc.wait()
        try:
            self._err.seek(0)
            self.stderr = self._err.read()[-2000:]
            self._err.close()
        except ValueError:
            pass
        for f in (self.proc.stdin, self.proc.stdout):
            try:
                f.close()
            except Exception:
                pass
        return self.stderr

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.stop()
