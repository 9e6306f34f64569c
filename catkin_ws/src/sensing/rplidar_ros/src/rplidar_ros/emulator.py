"""An emulated RPLIDAR A1 of our own: answers the serial protocol on a byte stream and spins
a configurable rectangular room (plus round pillars). No ROS imports.

The device core (`A1Device`) is fed request bytes and asked for output bytes up to a time, so
it can be driven by a pty (`PtyPort`) or directly by unit tests.
"""
import math
import os
import random
import termios
import tty

from . import protocol as P

MAX_RANGE_MM = 12000.0
BOOT_BANNER = b'RP LIDAR System.\r\nFirmware Ver %d.%02d - rc, HW Ver %d\r\nModel: %d\r\n'


class Room:
    """Axis-aligned rectangle [0, width] x [0, length] with circular pillars (x, y, r); the
    lidar at (x, y) with heading yaw (rad). Distances in m."""

    def __init__(self, width=6.0, length=4.0, x=2.0, y=1.5, yaw=0.0, pillars=((4.0, 3.0, 0.3),)):
        self.width, self.length = width, length
        self.x, self.y, self.yaw = x, y, yaw
        self.pillars = list(pillars)

    def distance(self, laser_angle):
        """Range along laser_angle (rad, counter-clockwise from the laser frame's x axis)."""
        a = self.yaw + laser_angle
        dx, dy = math.cos(a), math.sin(a)
        best = math.inf
        for d, lo, hi, p0, pd in ((dx, 0.0, self.width, self.x, dx), (dy, 0.0, self.length, self.y, dy)):
            if abs(pd) > 1e-12:
                for wall in (lo, hi):
                    t = (wall - p0) / pd
                    if t > 1e-9:
                        best = min(best, t)
        for cx, cy, r in self.pillars:
            fx, fy = self.x - cx, self.y - cy
            b = fx * dx + fy * dy
            c = fx * fx + fy * fy - r * r
            disc = b * b - c
            if disc >= 0.0:
                t = -b - math.sqrt(disc)
                if t > 1e-9:
                    best = min(best, t)
        return best


def device_angle_to_laser(angle_deg):
    """The published (laser frame) angle of a clockwise device angle."""
    return math.pi - math.radians(angle_deg)


class A1Device:
    """Protocol state machine of an A1M8 (legacy firmware: Standard and Express modes)."""

    def __init__(self, room=None, scan_frequency=10.0, firmware=(1, 20), hardware=7, model=0x18,
                 health=P.HEALTH_OK, serial=bytes(range(16)), std_us=500, express_us=250,
                 garbage_every=0.0, seed=1):
        self.room = room or Room()
        self.scan_frequency = scan_frequency
        self.info = P.DeviceInfo(model, firmware[0], firmware[1], hardware, bytes(serial))
        self.health = P.Health(health, 0x1234 if health else 0)
        self.std_us, self.express_us = std_us, express_us
        self.garbage_every = garbage_every
        self.rnd = random.Random(seed)
        self.rx = bytearray()
        self.mode = None                  # None, 'standard', 'express'
        self.t0 = 0.0
        self.sent = 0                     # samples (standard) or capsules (express) emitted
        self.next_garbage = None          # index of the sample/capsule that garbage hits next
        self.requests = []                # commands received (for tests)
        self.emitted = []                 # (angle_q6, dist_q2) of emitted standard samples

    # ---- geometry ------------------------------------------------------------------------------
    def samples_per_rev(self, us):
        return int(round(1e6 / us / self.scan_frequency))

    def dist_q2(self, angle_q6):
        d = self.room.distance(device_angle_to_laser(angle_q6 / 64.0)) * 1000.0
        if not d <= MAX_RANGE_MM:
            return 0
        return int(round(d * 4.0))

    def standard_sample(self, k):
        n = self.samples_per_rev(self.std_us)
        idx = k % n
        angle_q6 = (idx * 360 * 64) // n
        dq2 = self.dist_q2(angle_q6)
        return angle_q6, dq2, idx == 0

    def capsule_start_q6(self, c):
        n = self.samples_per_rev(self.express_us)
        return ((c * 32) * 360 * 64 // n) % (360 * 64)

    def capsule(self, c):
        start = self.capsule_start_q6(c)
        diff = (self.capsule_start_q6(c + 1) - start) % (360 * 64)
        cabins = []
        for k in range(16):
            d = []
            for j in (2 * k, 2 * k + 1):
                a = (start + (j * diff) // 32) % (360 * 64)
                dq2 = self.dist_q2(a)
                d.append(min(16383, int(round(dq2 / 4.0))))
            cabins.append((d[0], d[1], 0, 0))
        return P.encode_capsule(start, c == 0, cabins)

    # ---- protocol ------------------------------------------------------------------------------
    def receive(self, data, now):
        """Feed request bytes; returns immediate reply bytes."""
        self.rx += data
        out = bytearray()
        while self.rx:
            try:
                r = P.parse_request(self.rx)
            except P.ProtocolError:
                del self.rx[:1]
                continue
            if r is None:
                break
            cmd, payload, used = r
            del self.rx[:used]
            self.requests.append(cmd)
            out += self._handle(cmd, payload, now)
        return bytes(out)

    def _handle(self, cmd, payload, now):
        if cmd == P.CMD_STOP:
            self.mode = None
            return b''
        if cmd == P.CMD_RESET:
            self.mode = None
            i = self.info
            return BOOT_BANNER % (i.firmware_major, i.firmware_minor, i.hardware, i.model >> 4)
        if self.mode is not None and cmd not in (P.CMD_SCAN, P.CMD_FORCE_SCAN, P.CMD_EXPRESS_SCAN):
            return b''                    # busy streaming: the A1 ignores other requests
        if cmd == P.CMD_GET_INFO:
            return P.descriptor(20, P.SEND_SINGLE, P.ANS_DEVINFO) + P.pack_info(self.info)
        if cmd == P.CMD_GET_HEALTH:
            return P.descriptor(3, P.SEND_SINGLE, P.ANS_HEALTH) + P.pack_health(self.health)
        if cmd == P.CMD_GET_SAMPLERATE:
            return P.descriptor(4, P.SEND_SINGLE, P.ANS_SAMPLE_RATE) + \
                P.pack_samplerate(self.std_us, self.express_us)
        if cmd in (P.CMD_SCAN, P.CMD_FORCE_SCAN):
            if self.health.status == P.HEALTH_ERROR:
                return b''
            self._start('standard', now)
            return P.descriptor(5, P.SEND_MULTIPLE, P.ANS_MEASUREMENT)
        if cmd == P.CMD_EXPRESS_SCAN:
            fw = (self.info.firmware_major << 8) | self.info.firmware_minor
            if fw < 0x0111 or self.health.status == P.HEALTH_ERROR:
                return b''
            self._start('express', now)
            return P.descriptor(P.CAPSULE_SIZE, P.SEND_MULTIPLE, P.ANS_MEASUREMENT_CAPSULED)
        return b''                        # unsupported command: no answer, as the device

    def _start(self, mode, now):
        self.mode = mode
        self.t0 = now
        self.sent = 0
        self.next_garbage = self._garbage_slot(0) if self.garbage_every > 0 else None

    def _garbage_period(self):
        """Packets (standard samples or express capsules) between two bursts of garbage:
        `garbage_every` seconds of the device's own timeline, so where garbage lands is fixed
        by the stream, not by how the machine's load slices the wall clock."""
        us = self.std_us if self.mode == 'standard' else self.express_us * 32
        return max(1, int(round(self.garbage_every * 1e6 / us)))

    def _garbage_slot(self, start):
        """The packet hit in the period that begins at packet `start`: a seeded place within
        the period, so bursts do not fall in step with the revolution's start packets."""
        return start + self.rnd.randrange(self._garbage_period())

    def _packet(self, data):
        """One encoded packet, with garbage spliced in when its index is due."""
        if self.next_garbage is None or self.sent != self.next_garbage:
            return data
        period = self._garbage_period()
        self.next_garbage = self._garbage_slot(self.sent - self.sent % period + period)
        cut = self.rnd.randrange(len(data))
        junk = bytes(self.rnd.randrange(256) for _ in range(self.rnd.randrange(1, 12)))
        return data[:cut] + junk + data[cut:]

    def stream(self, now):
        """Measurement bytes due by time `now` (s)."""
        out = bytearray()
        if self.mode == 'standard':
            due = int((now - self.t0) * 1e6 / self.std_us)
            while self.sent < due:
                a, d, s = self.standard_sample(self.sent)
                q = 47 if d else 0
                out += self._packet(P.encode_standard(a, d, q, s))
                self.emitted.append((a, d))
                self.sent += 1
        elif self.mode == 'express':
            due = int((now - self.t0) * 1e6 / self.express_us) // 32
            while self.sent < due:
                out += self._packet(self.capsule(self.sent))
                self.sent += 1
        return bytes(out)


class PtyPort:
    """A pseudo-terminal whose slave is reachable under `path` (a symlink)."""

    def __init__(self, path):
        self.path = path
        self.master, self.slave = os.openpty()
        tty.setraw(self.slave, termios.TCSANOW)
        os.set_blocking(self.master, False)
        name = os.ttyname(self.slave)
        if os.path.lexists(path):
            os.remove(path)
        os.symlink(name, path)

    def close(self):
        for fd in (self.master, self.slave):
            try:
                os.close(fd)
            except OSError:
                pass
        if os.path.islink(self.path):
            os.remove(self.path)

    def read(self):
        try:
            return os.read(self.master, 4096)
        except (BlockingIOError, OSError):
            return b''

    def write(self, data):
        try:
            os.write(self.master, data)
        except (BlockingIOError, OSError):
            pass                          # nobody reads: the bytes are lost, as on a real line


def parse_pillars(text):
    """'x,y,r; x,y,r' -> [(x, y, r)], ValueError with a clear message otherwise."""
    out = []
    for part in filter(None, (p.strip() for p in str(text).split(';'))):
        v = [float(c) for c in part.split(',')]
        if len(v) != 3 or v[2] <= 0:
            raise ValueError("pillar '%s' must be 'x,y,radius' with radius > 0" % part)
        out.append(tuple(v))
    return out
