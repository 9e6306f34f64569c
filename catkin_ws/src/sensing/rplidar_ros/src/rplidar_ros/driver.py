"""Host side of the RPLIDAR A1 serial link: open the port, the request/response commands and
the scan stream. No ROS imports; times in seconds, `clock` injectable for tests."""
import errno
import fcntl
import os
import select
import struct
import termios
import time

from . import protocol as P

TIMEOUT = 2.0                 # the SDK's default operation timeout
BAUD = {9600: termios.B9600, 19200: termios.B19200, 38400: termios.B38400,
        57600: termios.B57600, 115200: termios.B115200, 230400: termios.B230400,
        460800: termios.B460800, 921600: termios.B921600,
        256000: getattr(termios, 'B256000', termios.B230400),
        1000000: getattr(termios, 'B1000000', termios.B921600)}


class Timeout(Exception):
    """RESULT_OPERATION_TIMEOUT"""


class Disconnected(Exception):
    """The device vanished (read/write error, end of file)."""


class ScanMode:
    def __init__(self, mode_id, name, us_per_sample, max_distance, ans_type):
        self.id, self.name, self.us_per_sample = mode_id, name, us_per_sample
        self.max_distance, self.ans_type = max_distance, ans_type


def open_serial(port, baudrate):
    """A raw 8N1 file descriptor; raises OSError when the port cannot be opened."""
    fd = os.open(port, os.O_RDWR | os.O_NOCTTY | os.O_NONBLOCK)
    try:
        attrs = termios.tcgetattr(fd)
        attrs[0] = 0                                    # iflag
        attrs[1] = 0                                    # oflag
        attrs[2] = termios.CS8 | termios.CREAD | termios.CLOCAL
        attrs[3] = 0                                    # lflag
        speed = BAUD.get(int(baudrate), termios.B115200)
        attrs[4] = attrs[5] = speed
        attrs[6][termios.VMIN] = 0
        attrs[6][termios.VTIME] = 0
        termios.tcsetattr(fd, termios.TCSANOW, attrs)
        termios.tcflush(fd, termios.TCIOFLUSH)
    except termios.error:
        pass                                            # not a tty (a pipe in tests): raw already
    return fd


class Driver:
    def __init__(self, fd, clock=time.monotonic):
        self.fd = fd
        self.clock = clock
        self.rx = bytearray()
        self.scanning = None          # the ScanMode being streamed
        self.decoder = None
        self.assembler = P.ScanAssembler()

    def close(self):
        if self.fd is not None:
            try:
                os.close(self.fd)
            except OSError:
                pass
            self.fd = None

    # ---- raw I/O ------------------------------------------------------------------------------
    def _write(self, data):
        try:
            os.write(self.fd, data)
        except OSError as e:
            raise Disconnected(str(e))

    def _fill(self, deadline):
        """Read what is available (waiting until deadline); False on timeout."""
        remaining = deadline - self.clock()
        if remaining <= 0:
            return False
        try:
            r, _, _ = select.select([self.fd], [], [], remaining)
        except (OSError, ValueError) as e:
            raise Disconnected(str(e))
        if not r:
            return False
        try:
            data = os.read(self.fd, 4096)
        except OSError as e:
            if e.errno in (errno.EAGAIN, errno.EWOULDBLOCK):
                return True
            raise Disconnected(str(e))
        if not data:
            raise Disconnected('end of file')
        self.rx += data
        return True

    def _read_exact(self, n, deadline):
        while len(self.rx) < n:
            if not self._fill(deadline):
                raise Timeout()
        out = bytes(self.rx[:n])
        del self.rx[:n]
        return out

    def _wait_descriptor(self, deadline):
        """Skip bytes until A5 5A, then parse the 7-byte descriptor."""
        while True:
            i = self.rx.find(bytes([P.SYNC_BYTE, P.SYNC_BYTE2]))
            if i >= 0 and len(self.rx) >= i + 7:
                d = P.parse_descriptor(self.rx[i:i + 7])
                del self.rx[:i + 7]
                return d
            if i < 0 and len(self.rx) > 1:
                del self.rx[:-1]
            if not self._fill(deadline):
                raise Timeout()

    def flush_input(self):
        self.rx.clear()
        try:
            while os.read(self.fd, 4096):
                pass
        except OSError:
            pass

    # ---- commands -----------------------------------------------------------------------------
    def send(self, cmd, payload=b''):
        self._write(P.request(cmd, payload))

    def _query(self, cmd, ans_type, size, timeout=TIMEOUT):
        self.flush_input()
        self.send(cmd)
        deadline = self.clock() + timeout
        d = self._wait_descriptor(deadline)
        if d.type != ans_type or d.size < size:
            raise P.ProtocolError('unexpected answer type 0x%02x (size %d) to command 0x%02x'
                                  % (d.type, d.size, cmd))
        return self._read_exact(d.size, deadline)

    def get_info(self, timeout=TIMEOUT):
        return P.parse_info(self._query(P.CMD_GET_INFO, P.ANS_DEVINFO, 20, timeout))

    def get_health(self, timeout=TIMEOUT):
        return P.parse_health(self._query(P.CMD_GET_HEALTH, P.ANS_HEALTH, 3, timeout))

    def get_samplerate(self, timeout=TIMEOUT):
        return P.parse_samplerate(self._query(P.CMD_GET_SAMPLERATE, P.ANS_SAMPLE_RATE, 4, timeout))

    def scan_modes(self, info):
        """Legacy firmware (< 1.24, no configuration commands): Standard and, from firmware
        1.17, Express; max distance 16 m as the SDK assumes."""
        fw = (info.firmware_major << 8) | info.firmware_minor
        std_us, exp_us = 500, 250
        if fw >= 0x0111:
            try:
                std_us, exp_us = self.get_samplerate()
            except (Timeout, P.ProtocolError):
                pass
        modes = [ScanMode(0, 'Standard', std_us, 16.0, P.ANS_MEASUREMENT)]
        if fw >= 0x0111:
            modes.append(ScanMode(1, 'Express', exp_us, 16.0, P.ANS_MEASUREMENT_CAPSULED))
        typical = 1 if fw >= 0x0111 else 0
        return modes, typical

    def set_motor(self, on):
        """A1: the adapter's DTR line enables the motor (DTR set = stopped)."""
        try:
            fcntl.ioctl(self.fd, termios.TIOCMBIC if on else termios.TIOCMBIS,
                        struct.pack('I', termios.TIOCM_DTR))
        except OSError:
            pass                      # a pty has no modem lines: the emulator spins anyway

    def start_scan(self, mode, timeout=TIMEOUT):
        self.stop()
        self.flush_input()
        if mode.ans_type == P.ANS_MEASUREMENT_CAPSULED:
            self.send(P.CMD_EXPRESS_SCAN, P.express_scan_payload(0, 0, 0))
            self.decoder = P.ExpressDecoder()
        else:
            self.send(P.CMD_SCAN)
            self.decoder = P.StandardDecoder()
        d = self._wait_descriptor(self.clock() + timeout)
        if d.type != mode.ans_type:
            raise P.ProtocolError('unexpected answer type 0x%02x to the scan request' % d.type)
        self.assembler.reset()
        self.scanning = mode

    def stop(self):
        self._write(P.request(P.CMD_STOP))
        self.scanning = None
        time.sleep(0.001)

    def reset(self):
        self._write(P.request(P.CMD_RESET))
        self.scanning = None

    def grab_scan(self, timeout=TIMEOUT):
        """Nodes of the next complete 360-degree scan; raises Timeout."""
        deadline = self.clock() + timeout
        while True:
            if self.rx:
                data = bytes(self.rx)
                self.rx.clear()
                scans = self.assembler.add(self.decoder.feed(data))
                if scans:
                    return scans[-1]
            if not self._fill(deadline):
                raise Timeout()

    @property
    def resyncs(self):
        return self.decoder.resyncs if self.decoder else 0
