"""Generated ros_lib headers, compiled with the host's g++ (AddressSanitizer on), serialise byte
for byte as rospy does, for every field type (float64 in the AVR representation included); the
node handle negotiates, refuses oversized frames without writing past its buffers."""
import os
import shutil
import struct
import subprocess

import numpy as np
import pytest
import rospkg

from rosserial_client.make_library import PRIMITIVES_ARDUINO, make_library

HERE = os.path.dirname(os.path.abspath(__file__))

ALLTYPES = """bool b
int8 i8
uint8 u8
byte by
char ch
int16 i16
uint16 u16
int32 i32
uint32 u32
int64 i64
uint64 u64
float32 f32
float64 f64
string s
time t
duration d
Header header
geometry_msgs/Point p
int32[3] fixed
float64[] f64s
string[] names
geometry_msgs/Point[] points
uint8[] bytes
int32 CONST_I=-5
string CONST_S=hello
"""
ECHO = "string a\nfloat64 x\n---\nint32[] out\n"


@pytest.fixture(scope='module')
def host(tmp_path_factory):
    tmp = tmp_path_factory.mktemp('rs')
    pkg = tmp / 'rs_test'
    (pkg / 'msg').mkdir(parents=True)
    (pkg / 'srv').mkdir()
    (pkg / 'msg' / 'AllTypes.msg').write_text(ALLTYPES)
    (pkg / 'srv' / 'Echo.srv').write_text(ECHO)
    rp = rospkg.RosPack()
    pkgs = {'rs_test': str(pkg)}
    for p in ('std_msgs', 'geometry_msgs', 'rosserial_msgs'):
        pkgs[p] = rp.get_path(p)
    lib = str(tmp / 'ros_lib')
    assert make_library(lib, [], PRIMITIVES_ARDUINO, packages=pkgs, log=print) == []
    exe = str(tmp / 'host_check')
    gxx = shutil.which('g++')
    assert gxx, 'g++ is missing (Debian package g++ / build-essential)'
    cmd = [gxx, '-std=c++17', '-Wall', '-Wextra', '-Werror', '-Wno-unused-parameter', '-g',
           '-fsanitize=address', '-I', lib,
           os.path.join(HERE, 'host_check.cpp'), os.path.join(lib, 'time.cpp'),
           os.path.join(lib, 'duration.cpp'), '-o', exe]
    p = subprocess.run(cmd, capture_output=True, text=True, timeout=600)
    assert p.returncode == 0, p.stderr[-4000:]
    return exe, tmp


def run(host, *args):
    p = subprocess.run([host[0]] + list(args), capture_output=True, text=True, timeout=60)
    assert p.returncode == 0, p.stderr[-3000:]
    return p.stdout.split('\n')


def rospy_class(tmp):
    import genpy.dynamic
    import genmsg
    import genmsg.gentools
    import genmsg.msg_loader
    rp = rospkg.RosPack()
    ctx = genmsg.MsgContext.create_default()
    search = {'rs_test': [str(tmp / 'rs_test' / 'msg')],
              'std_msgs': [os.path.join(rp.get_path('std_msgs'), 'msg')],
              'geometry_msgs': [os.path.join(rp.get_path('geometry_msgs'), 'msg')]}
    spec = genmsg.msg_loader.load_msg_from_file(ctx, str(tmp / 'rs_test' / 'msg' / 'AllTypes.msg'),
                                                'rs_test/AllTypes')
    genmsg.msg_loader.load_depends(ctx, spec, search)
    text = genmsg.gentools.compute_full_text(ctx, spec)
    return genpy.dynamic.generate_dynamic('rs_test/AllTypes', text)['rs_test/AllTypes'], \
        genmsg.gentools.compute_md5(ctx, spec)


def expected_bytes(cls):
    import genpy
    import io
    from geometry_msgs.msg import Point
    m = cls()
    m.b, m.i8, m.u8, m.by, m.ch = True, -8, 200, -3, ord('x')
    m.i16, m.u16, m.i32, m.u32 = -1600, 60000, -320000, 4000000000
    m.i64, m.u64 = -64000000000, 18000000000000000000
    m.f32, m.f64, m.s = 3.25, 1.5, 'hello'
    m.t = genpy.Time(1700000000, 123456789)
    m.d = genpy.Duration(-5, 500000000)
    m.header.seq, m.header.stamp, m.header.frame_id = 7, genpy.Time(11, 22), 'base'
    m.p.x, m.p.y, m.p.z = 0.5, -2.0, 1e10
    m.fixed = [1, -2, 3]
    m.f64s = [0.25, -3.0]
    m.names = ['a', '', 'long name']
    m.points = [Point(1, 0, 0), Point(0, 0, -1)]
    m.bytes = bytes([0, 255, 128])
    buf = io.BytesIO()
    m.serialize(buf)
    return buf.getvalue()


def test_every_field_type_serialises_like_rospy(host):
    cls, md5 = rospy_class(host[1])
    want = expected_bytes(cls)
    out = run(host, 'alltypes')
    n, length = map(int, out[0].split())
    assert bytes.fromhex(out[1]) == want
    assert n == length == len(want)


def test_deserialise_rospy_bytes_and_serialise_again(host):
    cls, _ = rospy_class(host[1])
    want = expected_bytes(cls)
    out = run(host, 'roundtrip', want.hex())
    used, n, s, name = out[0].split(' ', 3)
    assert (int(used), int(n), s, name) == (len(want), len(want), 'hello', 'long name')
    assert bytes.fromhex(out[1]) == want


def test_header_has_type_md5_and_constants(host):
    cls, md5 = rospy_class(host[1])
    text = open(os.path.join(str(host[1]), 'ros_lib', 'rs_test', 'AllTypes.h')).read()
    assert '"rs_test/AllTypes"' in text and '"%s"' % md5 in text
    assert 'enum { CONST_I = -5 };' in text
    assert 'typedef float _f64_type;' in text          # AVR: float64 held as a 4-byte float


def test_service_halves(host):
    req_t, req_md5, res_t, res_md5 = run(host, 'srv')[0].split()
    import genmsg
    import genmsg.gentools
    import genmsg.msg_loader
    ctx = genmsg.MsgContext.create_default()
    spec = genmsg.msg_loader.load_srv_from_file(
        ctx, str(host[1] / 'rs_test' / 'srv' / 'Echo.srv'), 'rs_test/Echo')
    genmsg.msg_loader.load_depends(ctx, spec, {})
    assert (req_t, res_t) == ('rs_test/Echo', 'rs_test/Echo')
    assert req_md5 == genmsg.gentools.compute_md5(ctx, spec.request)
    assert res_md5 == genmsg.gentools.compute_md5(ctx, spec.response)


AVR_VALUES = ['0', '-0', '1.5', '1.1', '-3.4e38', '1e-40', '1e-45', 'inf', '-inf', 'nan', '65504']


def test_avr_float64_out(host):
    """Widening is exact (subnormal floats become normal doubles); as the original, the sign is
    set only for f < 0: -0.0 leaves as +0.0 and NaN as a positive NaN."""
    out = run(host, 'avr64', *AVR_VALUES)
    for v, h in zip(AVR_VALUES, out):
        f32 = np.float32(float(v))
        got = bytes.fromhex(h)
        if v == 'nan':
            assert np.isnan(struct.unpack('<d', got)[0]) and got[7] & 0x80 == 0
        elif v == '-0':
            assert got == bytes(8)
        else:
            assert got == struct.pack('<d', float(f32)), v


def original_narrowing(d):
    """The original rosserial_client's double -> AVR float rule, written from its definition:
    the top 24 mantissa bits, +1 then >> 1 (unless all ones), exponent clamped to inf above
    float's range, zero below 2^-150, a subnormal float in between, the sign copied."""
    bits = struct.unpack('<Q', struct.pack('<d', d))[0]
    sign = bits >> 63
    exp = (bits >> 52) & 0x7FF
    mant = (bits >> 28) & 0xFFFFFF
    e = exp - 1023
    if exp == 0x7FF:
        exp = 0xFF
    elif e > 127:
        exp, mant = 0xFF, 0
    elif e >= -126:
        exp = e + 127
    elif e < -150:
        exp, mant = 0, 0
    else:
        mant = (mant | 0x1000000) >> (-126 - e)
        exp = 0
    if mant != 0xFFFFFF:
        mant += 1
    mant >>= 1
    return (sign << 31) | (exp << 23) | mant


def test_avr_float64_in(host):
    doubles = [0.0, -0.0, 1.1, 0.1, -2.5, 1e300, -1e300, 1e-300, 3.0e-39, 1e-40, 1e-45, 2e-45,
               float('inf'), -float('inf'), np.nextafter(1.0, 2.0), 16777217.0, 1.0 + 2 ** -24,
               1.0 - 2 ** -25, 3.4028235677973366e38, -0.321, 123456.789, 1e-60]
    out = run(host, 'avr64in', *[struct.pack('<d', d).hex() for d in doubles])
    for d, h in zip(doubles, out):
        assert int(h, 16) == original_narrowing(d), (d, h, hex(original_narrowing(d)))
        got = struct.unpack('<f', struct.pack('<I', int(h, 16)))[0]
        if abs(d) < 2 ** -150 or abs(d) > 3.4e38:
            continue
        with np.errstate(over='ignore'):
            want = float(np.float32(d))
        # round half up on one extra bit: within one unit in the last place of C's (float) cast
        assert abs(got - want) <= abs(float(np.spacing(np.float32(want)))) or got == want, d


def test_avr_float64_round_trip_is_exact_for_every_float(host):
    """The original's float64 test: serialise a float, read it back: the same float (subnormals,
    +-inf and the extremes included)."""
    vals = ['0', '10', '15642.1', '-50.2', '0.0001', '-0.321', '3.4e38', '-3.4e38', '1e-38',
            '-1e-38', '1e-39', '-1e-39', '3.14159e-43', '-3.14159e-43', '1e-45', '-1e-45',
            '0.99999999999999', '-127.999999999999', 'inf', '-inf', '1e39']
    out = run(host, 'avr64', *vals)
    back = run(host, 'avr64in', *out[:len(vals)])
    for v, h in zip(vals, back):
        with np.errstate(over='ignore'):
            f32 = np.float32(float(v))
        got = np.uint32(int(h, 16)).view(np.float32)
        assert got == f32, (v, got, f32)


def test_node_handle_negotiates_and_guards_its_buffers(host):
    out = run(host, 'nodehandle')
    assert out[0] == 'configured 1'
    sent = bytes.fromhex(out[1])
    from rosserial_python import protocol as p
    frames = [e for e in p.FrameParser().feed(sent)]
    assert [f.kind for f in frames] == ['frame'] * 3
    assert frames[0].topic_id == p.ID_TIME
    pub = p.TopicInfo.decode(frames[1].payload)
    sub = p.TopicInfo.decode(frames[2].payload)
    assert (frames[1].topic_id, pub.topic_id, pub.topic_name, pub.message_type,
            pub.buffer_size) == (p.ID_PUBLISHER, 102, 'chatter', 'std_msgs/String', 128)
    assert (frames[2].topic_id, sub.topic_id, sub.topic_name, sub.buffer_size) == \
        (p.ID_SUBSCRIBER, 100, 'words', 64)
    assert pub.md5sum == '992ce8a1687cec8c8bd883ec73ca41d1'
    # the 300-byte frame was dropped (no overrun: ASan), the good one delivered
    assert out[2] == 'received 1 hello'
    # oversized publish refused (-1), a normal one framed (8 + 4 + 2 bytes)
    assert out[3:5] == ['publish -1', 'publish 14']
