"""rosserial frame encoding/decoding against INTERFACES.md §4.1's byte examples."""
import struct

import pytest

from rosserial_python import protocol as p


def hx(s):
    return bytes.fromhex(s.replace(' ', ''))


def test_reference_frames():
    assert p.REQUEST_TOPICS == hx('FF FE 00 00 FF 00 00 FF')
    assert p.TX_STOP == hx('FF FE 00 00 FF 0B 00 F4')
    assert p.encode_frame(p.ID_TIME, bytes(8)) == hx('FF FE 08 00 F7 0A 00' + '00' * 8 + 'F5')


def test_checksums_sum_to_255():
    frame = p.encode_frame(125, b'hello world!' * 30)
    assert (frame[2] + frame[3] + frame[4]) % 256 == 255
    assert sum(frame[5:]) % 256 == 255


def test_round_trip_in_pieces():
    frames = [p.encode_frame(100 + i, bytes(range(i * 7 % 256)) * (i + 1)) for i in range(20)]
    data = b''.join(frames)
    parser = p.FrameParser()
    out = []
    for i in range(0, len(data), 3):
        out += parser.feed(data[i:i + 3])
    assert [(e.topic_id, e.payload) for e in out] == [
        (100 + i, bytes(range(i * 7 % 256)) * (i + 1)) for i in range(20)]
    assert parser.garbage == 0


def test_garbage_between_frames_is_skipped_and_no_frame_lost():
    a, b = p.encode_frame(125, b'abc'), p.encode_frame(126, b'def')
    parser = p.FrameParser()
    events = parser.feed(b'\x00\x13hello\xfe' + a + b'noise' + b)
    frames = [e for e in events if e.kind == 'frame']
    assert [(f.topic_id, f.payload) for f in frames] == [(125, b'abc'), (126, b'def')]
    assert parser.garbage == len(b'\x00\x13hello\xfe') + len(b'noise')


def test_bad_version_reports_and_resyncs():
    parser = p.FrameParser()
    frame = p.encode_frame(125, b'x')
    events = parser.feed(b'\xff\x01' + b'\xff' + frame)   # FF FF FE...: 2nd 0xFF starts a frame
    kinds = [e.kind for e in events]
    assert kinds == ['bad_version', 'bad_version', 'frame']
    assert events[0].describe().startswith('unrecognized')
    assert events[1].describe() == 'Rev 0 (rosserial 0.4 and earlier)'


def test_bad_length_checksum():
    frame = bytearray(p.encode_frame(125, b'abcdef'))
    frame[4] ^= 0x55
    parser = p.FrameParser()
    events = parser.feed(bytes(frame) + p.encode_frame(130, b'ok'))
    assert events[0].kind == 'bad_length_checksum' and events[0].length == 6
    assert (events[-1].kind, events[-1].topic_id, events[-1].payload) == ('frame', 130, b'ok')


def test_bad_data_checksum_and_truncated_frame_do_not_eat_the_next():
    bad = bytearray(p.encode_frame(125, b'abcdef'))
    bad[-1] ^= 1
    truncated = p.encode_frame(127, b'0123456789')[:9]
    parser = p.FrameParser()
    good = p.encode_frame(128, b'good')
    events = parser.feed(bytes(bad) + truncated)
    assert [e.kind for e in events] == ['bad_data_checksum']
    assert parser.in_frame and parser.partial_step() == 'data'
    parser.reset()                       # the read timeout drops the truncated frame
    events = parser.feed(good)
    assert [(e.kind, e.topic_id) for e in events] == [('frame', 128)]


def test_truncated_frame_followed_by_a_frame_is_found_by_the_checksum():
    truncated = p.encode_frame(127, b'0123456789')[:9]
    good = p.encode_frame(128, b'good')
    events = p.FrameParser().feed(truncated + good + good)
    assert ('frame', 128) in [(e.kind, getattr(e, 'topic_id', None)) for e in events]


def test_payload_too_large():
    with pytest.raises(ValueError):
        p.encode_frame(100, bytes(40000))


def test_system_messages_match_rospy():
    from rosserial_msgs.msg import Log, TopicInfo
    from rosserial_msgs.srv import RequestParamRequest, RequestParamResponse
    from std_msgs.msg import Time
    import io
    import rospy

    def ser(m):
        b = io.BytesIO()
        m.serialize(b)
        return b.getvalue()

    ti = TopicInfo(125, 'chatter', 'std_msgs/String', '992ce8a1687cec8c8bd883ec73ca41d1', 512)
    assert p.TopicInfo(125, 'chatter', 'std_msgs/String',
                       '992ce8a1687cec8c8bd883ec73ca41d1', 512).encode() == ser(ti)
    back = p.TopicInfo.decode(ser(ti))
    assert (back.topic_id, back.topic_name, back.message_type, back.md5sum,
            back.buffer_size) == (125, 'chatter', 'std_msgs/String',
                                  '992ce8a1687cec8c8bd883ec73ca41d1', 512)
    assert p.decode_log(ser(Log(level=Log.WARN, msg='careful'))) == (2, 'careful')
    assert p.encode_log(3, 'bad') == ser(Log(level=3, msg='bad'))
    assert p.decode_param_request(ser(RequestParamRequest(name='~gain'))) == '~gain'
    resp = RequestParamResponse(ints=[1, -2], floats=[0.5], strings=['a', 'bc'])
    assert p.encode_param_response([1, -2], [0.5], ['a', 'bc']) == ser(resp)
    assert p.encode_time(12, 345) == ser(Time(rospy.Time(12, 345)))


@pytest.mark.parametrize('value,expected', [
    (3, ([3], [], [])), (True, ([1], [], [])), ([1, 2, 3], ([1, 2, 3], [], [])),
    (2.5, ([], [2.5], [])), ([0.1, 0.2], ([], [0.1, 0.2], [])), ('x', ([], [], ['x'])),
    (['a', 'b'], ([], [], ['a', 'b'])), ([], ([], [], []))])
def test_param_to_response(value, expected):
    assert p.param_to_response('n', value) == expected


def test_param_rejects_dicts_and_mixed_lists():
    with pytest.raises(p.ParamError, match='dictionary'):
        p.param_to_response('gains', {'p': 1})
    with pytest.raises(p.ParamError, match='same type'):
        p.param_to_response('mix', [1, 'a'])


def test_reader_reports_truncation():
    with pytest.raises(ValueError, match='truncated'):
        p.TopicInfo.decode(struct.pack('<H', 5))
