"""The RPLIDAR A-series serial protocol (A1: 115200 8N1): requests, response descriptors,
standard 5-byte samples and express 84-byte capsules, both directions. No ROS imports.

A decoded measurement is a Node(angle_z_q14, dist_mm_q2, quality, flag) as the SDK's
"HQ" nodes: angle in degrees = angle_z_q14 * 90 / 16384, distance in mm = dist_mm_q2 / 4,
quality 0..255 (standard: 6-bit quality << 2), flag bit0 = start of a new 360-degree scan.
"""
import collections
import struct

SYNC_BYTE = 0xA5
SYNC_BYTE2 = 0x5A
CMD_STOP = 0x25
CMD_SCAN = 0x20
CMD_FORCE_SCAN = 0x21
CMD_RESET = 0x40
CMD_GET_INFO = 0x50
CMD_GET_HEALTH = 0x52
CMD_GET_SAMPLERATE = 0x59
CMD_EXPRESS_SCAN = 0x82
CMD_GET_ACC_BOARD_FLAG = 0xFF

ANS_MEASUREMENT = 0x81
ANS_MEASUREMENT_CAPSULED = 0x82
ANS_DEVINFO = 0x04
ANS_HEALTH = 0x06
ANS_SAMPLE_RATE = 0x15
ANS_ACC_BOARD_FLAG = 0xFF

SEND_SINGLE = 0
SEND_MULTIPLE = 1

HEALTH_OK, HEALTH_WARNING, HEALTH_ERROR = 0, 1, 2
CAPSULE_SIZE = 84

Node = collections.namedtuple('Node', 'angle_z_q14 dist_mm_q2 quality flag')
DeviceInfo = collections.namedtuple('DeviceInfo', 'model firmware_major firmware_minor hardware serial')
Health = collections.namedtuple('Health', 'status error_code')
Descriptor = collections.namedtuple('Descriptor', 'size mode type')


class ProtocolError(Exception):
    pass


# ---- requests ---------------------------------------------------------------------------------
def request(cmd, payload=b''):
    """Bytes of one request; commands with bit 0x80 carry a payload and a checksum."""
    if cmd & 0x80:
        body = bytes([SYNC_BYTE, cmd, len(payload)]) + bytes(payload)
        c = 0
        for b in body:
            c ^= b
        return body + bytes([c])
    return bytes([SYNC_BYTE, cmd])


def express_scan_payload(working_mode=0, working_flags=0, param=0):
    return struct.pack('<BHH', working_mode, working_flags, param)


def parse_request(buf):
    """(cmd, payload, consumed) from the start of buf, or None if incomplete.
    Raises ProtocolError on a bad sync byte or checksum (caller drops one byte)."""
    if len(buf) < 2:
        return None
    if buf[0] != SYNC_BYTE:
        raise ProtocolError('bad request sync byte 0x%02x' % buf[0])
    cmd = buf[1]
    if not cmd & 0x80:
        return cmd, b'', 2
    if len(buf) < 3:
        return None
    size = buf[2]
    if len(buf) < 4 + size:
        return None
    c = 0
    for b in buf[:3 + size]:
        c ^= b
    if c != buf[3 + size]:
        raise ProtocolError('bad request checksum for command 0x%02x' % cmd)
    return cmd, bytes(buf[3:3 + size]), 4 + size


# ---- response descriptors --------------------------------------------------------------------
def descriptor(size, mode, ans_type):
    return bytes([SYNC_BYTE, SYNC_BYTE2]) + struct.pack('<I', (size & 0x3FFFFFFF) | (mode << 30)) + \
        bytes([ans_type])


def parse_descriptor(buf):
    if len(buf) != 7 or buf[0] != SYNC_BYTE or buf[1] != SYNC_BYTE2:
        raise ProtocolError('bad response descriptor %s' % bytes(buf).hex())
    v = struct.unpack('<I', bytes(buf[2:6]))[0]
    return Descriptor(v & 0x3FFFFFFF, v >> 30, buf[6])


# ---- single replies ----------------------------------------------------------------------------
def pack_info(info):
    return struct.pack('<BHB', info.model, (info.firmware_major << 8) | info.firmware_minor,
                       info.hardware) + bytes(info.serial)


def parse_info(data):
    model, fw, hw = struct.unpack('<BHB', bytes(data[:4]))
    return DeviceInfo(model, fw >> 8, fw & 0xFF, hw, bytes(data[4:20]))


def pack_health(h):
    return struct.pack('<BH', h.status, h.error_code)


def parse_health(data):
    return Health(*struct.unpack('<BH', bytes(data[:3])))


def pack_samplerate(std_us, express_us):
    return struct.pack('<HH', std_us, express_us)


def parse_samplerate(data):
    return struct.unpack('<HH', bytes(data[:4]))


# ---- standard samples ----------------------------------------------------------------------
def encode_standard(angle_q6, distance_q2, quality, start):
    """5 bytes of one standard measurement (quality 0..63)."""
    s = 1 if start else 0
    b0 = (quality << 2) | ((1 - s) << 1) | s
    return bytes([b0]) + struct.pack('<HH', ((angle_q6 & 0x7FFF) << 1) | 1, distance_q2)


def standard_valid(b):
    s, ns = b[0] & 1, (b[0] >> 1) & 1
    return s != ns and (b[1] & 1) == 1


def decode_standard(b):
    angle_q6 = (b[1] | (b[2] << 8)) >> 1
    dist_q2 = b[3] | (b[4] << 8)
    return Node((angle_q6 << 8) // 90, dist_q2, (b[0] >> 2) << 2, b[0] & 1)


class StandardDecoder:
    """Stream decoder with resync: a 5-byte window failing the S/!S or C checks drops one byte."""

    def __init__(self):
        self.buf = bytearray()
        self.resyncs = 0

    def feed(self, data):
        self.buf += data
        out = []
        buf = self.buf
        i = 0
        n = len(buf)
        while n - i >= 5:
            w = buf[i:i + 5]
            if standard_valid(w):
                out.append(decode_standard(w))
                i += 5
            else:
                self.resyncs += 1
                i += 1
        del buf[:i]
        return out


# ---- express capsules ----------------------------------------------------------------------
def encode_capsule(start_angle_q6, start, cabins):
    """84 bytes: cabins = 16 tuples (dist1_mm, dist2_mm, offset1_q3, offset2_q3), offsets 0..63."""
    body = bytearray(struct.pack('<H', (start_angle_q6 & 0x7FFF) | (0x8000 if start else 0)))
    for d1, d2, o1, o2 in cabins:
        body += struct.pack('<HHB', ((d1 & 0x3FFF) << 2) | (o1 >> 4),
                            ((d2 & 0x3FFF) << 2) | (o2 >> 4), (o1 & 0xF) | ((o2 & 0xF) << 4))
    c = 0
    for b in body:
        c ^= b
    return bytes([0xA0 | (c & 0xF), 0x50 | (c >> 4)]) + bytes(body)


def capsule_valid(b):
    if (b[0] >> 4) != 0xA or (b[1] >> 4) != 0x5:
        return False
    c = 0
    for x in b[2:CAPSULE_SIZE]:
        c ^= x
    return c == ((b[0] & 0xF) | ((b[1] & 0xF) << 4))


class ExpressDecoder:
    """Express capsules -> nodes. The samples of a capsule are emitted when the next capsule
    arrives (its start angle gives the angular span), as the SDK does."""

    def __init__(self):
        self.buf = bytearray()
        self.prev = None
        self.resyncs = 0

    def reset(self):
        self.prev = None

    def feed(self, data):
        self.buf += data
        buf = self.buf
        out = []
        i = 0
        while len(buf) - i >= CAPSULE_SIZE:
            cap = buf[i:i + CAPSULE_SIZE]
            if not capsule_valid(cap):
                self.resyncs += 1
                self.prev = None
                i += 1
                continue
            i += CAPSULE_SIZE
            start_word = cap[2] | (cap[3] << 8)
            if start_word & 0x8000:
                # first capsule after EXPRESS_SCAN: nothing to interpolate against yet
                self.prev = bytes(cap)
                continue
            if self.prev is not None:
                out.extend(self._emit(self.prev, start_word & 0x7FFF))
            self.prev = bytes(cap)
        del buf[:i]
        return out

    @staticmethod
    def _emit(prev, current_start_q6):
        prev_start_q8 = ((prev[2] | (prev[3] << 8)) & 0x7FFF) << 2
        cur_start_q8 = current_start_q6 << 2
        diff_q8 = cur_start_q8 - prev_start_q8
        if prev_start_q8 > cur_start_q8:
            diff_q8 += 360 << 8
        inc_q16 = diff_q8 << 3
        angle_q16 = prev_start_q8 << 8
        full = 360 << 16
        nodes = []
        for k in range(16):
            off = 4 + 5 * k
            da1 = prev[off] | (prev[off + 1] << 8)
            da2 = prev[off + 2] | (prev[off + 3] << 8)
            oa = prev[off + 4]
            for da, o in ((da1, (oa & 0xF) | ((da1 & 0x3) << 4)),
                          (da2, (oa >> 4) | ((da2 & 0x3) << 4))):
                dist_q2 = da & 0xFFFC
                angle_q6 = (angle_q16 - (o << 13)) >> 10
                sync = 1 if ((angle_q16 + inc_q16) % full) < inc_q16 else 0
                angle_q16 += inc_q16
                if angle_q6 < 0:
                    angle_q6 += 360 << 6
                if angle_q6 >= 360 << 6:
                    angle_q6 -= 360 << 6
                quality = (0x2F << 2) if dist_q2 else 0
                nodes.append(Node((angle_q6 << 8) // 90, dist_q2, quality, sync))
        return nodes


def node_angle_deg(node):
    return node.angle_z_q14 * 90.0 / 16384.0


class ScanAssembler:
    """Groups nodes into 360-degree scans. A scan starts at a start flag near 0 degrees, or where
    the angle wraps from the last quarter to the first (the flagged sample was lost); a flag
    elsewhere (corrupted data that passed the check bits) is ignored. The partial scan before
    the first start is dropped."""

    MIN_SCAN = 10

    def __init__(self):
        self.current = None
        self.last_angle = self.last_angle2 = None

    def reset(self):
        self.current = None
        self.last_angle = self.last_angle2 = None

    def add(self, nodes):
        done = []
        for n in nodes:
            a = node_angle_deg(n)
            near_zero = a < 5.0 or a > 355.0
            # two samples in the last quarter, so that one corrupted sample cannot fake a wrap
            wrapped = self.last_angle is not None and self.last_angle > 270.0 and \
                self.last_angle2 is not None and self.last_angle2 > 270.0 and a < 90.0
            ready = self.current is None or len(self.current) >= self.MIN_SCAN
            if ready and ((n.flag & 1 and near_zero) or (wrapped and self.current is not None)):
                if self.current:
                    done.append(self.current)
                self.current = [n]
            elif self.current is not None:
                self.current.append(n)
                if len(self.current) > 8192:
                    self.current = None
            self.last_angle2, self.last_angle = self.last_angle, a
        return done
