"""rosauth's MAC check and the clients' side of it (no ROS imports).

The MAC is what rosauth's ros_mac_authentication compares: the lowercase hex SHA-512 of the
concatenation secret + client + dest + rand + str(t.secs) + level + str(end.secs), where the
secret is the first line of the secret file (16 characters). A request is accepted when
|now - t| < allowed_time_delta (whole seconds, as the original), end > now, and the MAC
matches. Ours adds: a MAC accepted once is refused afterwards (replay), and the comparison
is constant-time.
"""
import collections
import hashlib
import hmac
import os
import secrets
import stat
import threading
import time

SECRET_LENGTH = 16


class SecretError(Exception):
    """The secret file is missing, unreadable or not one line of SECRET_LENGTH characters."""


def parse_secret(text, where='the secret file'):
    line = text.split('\n', 1)[0].rstrip('\r')
    if len(line) != SECRET_LENGTH:
        raise SecretError('%s: the secret must be one line of %d characters, found %d'
                          % (where, SECRET_LENGTH, len(line)))
    return line


def read_secret(path):
    try:
        with open(path, encoding='utf-8') as f:
            return parse_secret(f.read(), path)
    except (OSError, UnicodeDecodeError) as e:
        raise SecretError('Could not read from file %r: %s' % (path, getattr(e, 'strerror', e)))


def new_secret():
    """SECRET_LENGTH random characters (letters and digits)."""
    alphabet = 'abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789'
    return ''.join(secrets.choice(alphabet) for _ in range(SECRET_LENGTH))


def write_secret(path, secret=None):
    """Write a secret file readable by its owner only (atomically: a reader sees the old or
    the new file). Returns the secret."""
    secret = parse_secret(secret if secret is not None else new_secret())
    d = os.path.dirname(os.path.abspath(path))
    os.makedirs(d, exist_ok=True)
    tmp = '%s.%d.tmp' % (path, os.getpid())
    fd = os.open(tmp, os.O_WRONLY | os.O_CREAT | os.O_TRUNC, stat.S_IRUSR | stat.S_IWUSR)
    try:
        os.write(fd, (secret + '\n').encode())
    finally:
        os.close(fd)
    os.replace(tmp, path)
    return secret


def mac(secret, client, dest, rand, t, level, end):
    """The MAC of one request (t and end in whole seconds)."""
    text = '%s%s%s%s%d%s%d' % (secret, client, dest, rand, int(t), level, int(end))
    return hashlib.sha512(text.encode('utf-8')).hexdigest()


def auth_message(secret, client, dest, level='user', duration=3600, now=None, rand=None):
    """The rosbridge `auth` op a client sends first (roslibjs' ros.authenticate fields)."""
    t = int(now if now is not None else time.time())
    end = t + int(duration)
    rand = rand if rand is not None else secrets.token_hex(16)
    return {'op': 'auth', 'mac': mac(secret, client, dest, rand, t, level, end),
            'client': client, 'dest': dest, 'rand': rand, 't': t, 'level': level, 'end': end}


class SecretFile(object):
    """The secret of a file, read again whenever the file changes (course_web writes a new one
    on each start); `get()` raises SecretError while there is no valid secret."""

    def __init__(self, path):
        self.path = path
        self.key = None
        self.secret = None
        self.error = None
        self.lock = threading.Lock()

    def get(self):
        with self.lock:
            try:
                st = os.stat(self.path)
                key = (st.st_ino, st.st_mtime_ns, st.st_size)
            except OSError as e:
                self.key, self.secret = None, None
                raise SecretError('Could not read from file %r: %s' % (self.path, e.strerror))
            if key != self.key:
                self.key = key
                try:
                    self.secret, self.error = read_secret(self.path), None
                except SecretError as e:
                    self.secret, self.error = None, e
            if self.secret is None:
                raise self.error
            return self.secret


class Authenticator(object):
    """authenticate(...) -> (accepted, reason). `secret` is a callable returning the secret
    (SecretFile.get) or a string; `clock` gives wall-clock seconds."""

    def __init__(self, secret, allowed_time_delta=5.0, clock=time.time, max_remembered=100000):
        self.secret = secret if callable(secret) else (lambda: secret)
        self.allowed_time_delta = float(allowed_time_delta)
        self.clock = clock
        self.lock = threading.Lock()
        self.used = {}                       # mac -> t of MACs already accepted
        self.order = collections.deque()     # (t, mac) in acceptance order
        self.max_remembered = max_remembered

    def _forget_old(self, now):
        while self.order:
            t, m = self.order[0]
            # a MAC whose t is this far in the past fails the time check anyway
            old = self.allowed_time_delta >= 0 and now - t >= self.allowed_time_delta + 1
            if not old and len(self.order) <= self.max_remembered:
                break
            self.order.popleft()
            self.used.pop(m, None)

    def authenticate(self, mac_text, client, dest, rand, t, level, end):
        now = self.clock()
        t, end = float(t), float(end)
        if self.allowed_time_delta >= 0:
            # the original compares the whole seconds of |t - now|, and end with now
            if int(abs(t - now)) >= self.allowed_time_delta:
                return False, 'the request time t is %.0f s away from now (allowed %g s)' % (
                    t - now, self.allowed_time_delta)
            if not end > now:
                return False, 'the session end is in the past'
        try:
            secret = self.secret()
        except SecretError as e:
            return False, str(e)
        expected = mac(secret, client, dest, rand, t, level, end)
        if not isinstance(mac_text, str) or not hmac.compare_digest(
                expected.encode(), mac_text.encode('utf-8', 'replace')):
            return False, 'wrong MAC'
        with self.lock:
            self._forget_old(now)
            if mac_text in self.used:
                return False, 'this MAC was used before (replay)'
            self.used[mac_text] = t
            self.order.append((t, mac_text))
        return True, 'authenticated'
