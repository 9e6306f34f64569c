"""Reading single key presses from a terminal, one at a time, with an optional timeout."""
import os
import select
import termios
import time
import tty


class NotATerminal(Exception):
    pass


class KeyReader:
    """Puts the terminal into raw mode only while waiting for a key (as the original does), so
    that printed text keeps normal line endings; Ctrl-C arrives as the character '\\x03'."""

    def __init__(self, fd):
        self.fd = fd
        try:
            self.settings = termios.tcgetattr(fd)
        except termios.error:
            raise NotATerminal('standard input is not a terminal: run teleop_twist_keyboard in a '
                               'terminal (in a launch file use launch-prefix="xterm -e" or a '
                               'separate rosrun)')

    def get_key(self, timeout=None, should_stop=lambda: False, poll=0.1):
        """One key, or '' when `timeout` seconds (None = forever) passed without one.

        Returns '' as well when should_stop() turns true (checked every `poll` seconds), so a
        shutdown request never leaves the node blocked on the keyboard."""
        deadline = None if timeout is None else time.monotonic() + timeout
        # TCSANOW, not tty.setraw's default TCSAFLUSH: a key typed while the node was printing
        # (the terminal in normal mode) is read now instead of being thrown away
        tty.setraw(self.fd, termios.TCSANOW)
        try:
            while True:
                wait = poll if deadline is None else min(poll, max(0.0, deadline - time.monotonic()))
                ready, _, _ = select.select([self.fd], [], [], wait)
                if ready:
                    data = os.read(self.fd, 1)
                    return data.decode('latin-1') if data else '\x04'  # EOF acts like Ctrl-D
                if should_stop() or (deadline is not None and time.monotonic() >= deadline):
                    return ''
        finally:
            self.restore()

    def restore(self):
        termios.tcsetattr(self.fd, termios.TCSADRAIN, self.settings)
