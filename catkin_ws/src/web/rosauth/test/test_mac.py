"""rosauth's MAC check without ROS: the original's string, time window, replay, secret file."""
import hashlib
import os

import pytest

from rosauth import mac as M

SECRET = 'abcdefghij012345'


class Clock(object):
    def __init__(self, t):
        self.t = t

    def __call__(self):
        return self.t


def test_mac_is_sha512_of_the_originals_concatenation():
    text = SECRET + '192.168.1.101' + '192.168.1.111' + 'xyzabc' + '1000' + 'admin' + '2000'
    assert M.mac(SECRET, '192.168.1.101', '192.168.1.111', 'xyzabc', 1000, 'admin', 2000) == \
        hashlib.sha512(text.encode()).hexdigest()
    # floats count as their whole seconds (the original hashes t.sec, end.sec)
    assert M.mac(SECRET, 'a', 'b', 'r', 1000.7, 'l', 2000.2) == M.mac(SECRET, 'a', 'b', 'r', 1000,
                                                                      'l', 2000)


def test_accepts_once_then_refuses_replay():
    clock = Clock(1000.0)
    a = M.Authenticator(SECRET, 5, clock)
    msg = M.auth_message(SECRET, '10.0.0.2', '10.0.0.1', now=1000, rand='r1')
    args = [msg[k] for k in ('mac', 'client', 'dest', 'rand', 't', 'level', 'end')]
    assert a.authenticate(*args) == (True, 'authenticated')
    ok, reason = a.authenticate(*args)
    assert not ok and 'replay' in reason
    msg2 = M.auth_message(SECRET, '10.0.0.2', '10.0.0.1', now=1000, rand='r2')
    assert a.authenticate(*[msg2[k] for k in ('mac', 'client', 'dest', 'rand', 't', 'level',
                                              'end')])[0]


def test_time_window_and_end():
    clock = Clock(1000.0)
    a = M.Authenticator(SECRET, 5, clock)

    def check(t, end, rand):
        return a.authenticate(M.mac(SECRET, 'c', 'd', rand, t, 'user', end), 'c', 'd', rand, t,
                              'user', end)
    assert check(996, 2000, 'a')[0]          # 4 s old
    ok, reason = check(995, 2000, 'b')       # 5 s old: outside
    assert not ok and 'away from now' in reason
    assert not check(1006, 2000, 'c')[0]     # 6 s ahead
    assert check(1004, 2000, 'd')[0]         # clocks out of sync: 4 s ahead is fine
    ok, reason = check(1000, 1000, 'e')      # the session already ended
    assert not ok and 'end' in reason
    clock.t = 1100.0                         # expired later: same MAC refused by time
    assert not check(1000, 2000, 'f')[0]
    # a negative delta disables the time check, as the original
    b = M.Authenticator(SECRET, -1, clock)
    assert b.authenticate(M.mac(SECRET, 'c', 'd', 'g', 1, 'user', 2), 'c', 'd', 'g', 1, 'user',
                          2)[0]


def test_wrong_mac_or_field_refused():
    a = M.Authenticator(SECRET, 5, Clock(1000.0))
    msg = M.auth_message(SECRET, 'c', 'd', now=1000, rand='r')
    fields = ['mac', 'client', 'dest', 'rand', 't', 'level', 'end']
    for changed in ('client', 'dest', 'rand', 'level'):
        m = dict(msg)
        m[changed] = m[changed] + 'x'
        assert a.authenticate(*[m[k] for k in fields]) == (False, 'wrong MAC')
    other = M.auth_message('0123456789abcdef', 'c', 'd', now=1000, rand='r')
    assert not a.authenticate(*[other[k] for k in fields])[0]
    assert not a.authenticate(None, 'c', 'd', 'r', 1000, 'user', 2000)[0]
    assert a.authenticate(*[msg[k] for k in fields])[0]


def test_forgets_macs_that_can_no_longer_pass():
    clock = Clock(1000.0)
    a = M.Authenticator(SECRET, 5, clock)
    for i in range(10):
        m = M.auth_message(SECRET, 'c', 'd', now=1000, rand=str(i))
        assert a.authenticate(*[m[k] for k in ('mac', 'client', 'dest', 'rand', 't', 'level',
                                               'end')])[0]
    assert len(a.used) == 10
    clock.t = 1010.0
    m = M.auth_message(SECRET, 'c', 'd', now=1010, rand='new')
    assert a.authenticate(*[m[k] for k in ('mac', 'client', 'dest', 'rand', 't', 'level',
                                           'end')])[0]
    assert len(a.used) == 1


def test_secret_file(tmp_path):
    path = str(tmp_path / 'sub' / 'secret')
    f = M.SecretFile(path)
    with pytest.raises(M.SecretError, match='Could not read'):
        f.get()
    s1 = M.write_secret(path)
    assert len(s1) == M.SECRET_LENGTH and f.get() == s1
    assert os.stat(path).st_mode & 0o777 == 0o600
    s2 = M.write_secret(path)
    assert s2 != s1 and f.get() == s2          # a new file is read again
    with open(path, 'w') as out:
        out.write('short\n')
    with pytest.raises(M.SecretError, match='16 characters, found 5'):
        f.get()
    with pytest.raises(M.SecretError):
        M.write_secret(path, 'x' * 17)
    a = M.Authenticator(f.get, 5, Clock(1000.0))
    m = M.auth_message(s2, 'c', 'd', now=1000)
    ok, reason = a.authenticate(*[m[k] for k in ('mac', 'client', 'dest', 'rand', 't', 'level',
                                                 'end')])
    assert not ok and '16 characters' in reason
