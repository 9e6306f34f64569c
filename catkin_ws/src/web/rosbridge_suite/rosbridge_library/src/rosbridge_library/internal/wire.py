"""Wire encodings of outgoing protocol messages: JSON text, CBOR, PNG and fragments.

A frame is ``(data, binary)``: UTF-8 ``bytes`` of JSON for a WebSocket text frame
(binary False) or CBOR bytes (binary True); encoded once, however many clients get it.
"""
import base64
import io
import json
import math


def to_json(message):
    """Compact JSON; NaN / inf left anywhere (e.g. in a parameter) become null."""
    try:
        return json.dumps(message, separators=(',', ':'), allow_nan=False)
    except ValueError:
        return json.dumps(_nan_to_none(message), separators=(',', ':'), allow_nan=False)


def _nan_to_none(v):
    if isinstance(v, float):
        return v if math.isfinite(v) else None
    if isinstance(v, dict):
        return {k: _nan_to_none(x) for k, x in v.items()}
    if isinstance(v, (list, tuple)):
        return [_nan_to_none(x) for x in v]
    return v


def to_cbor(message):
    import cbor2
    return cbor2.dumps(message)


def png_encode(text):
    """As rosbridge's pngcompression: the bytes of `text` as the pixels of a near-square RGB
    image padded with newlines; returns the base64 text of the PNG file."""
    from PIL import Image
    data = text.encode('utf-8')
    length = len(data)
    width = max(1, int(math.floor(math.sqrt(length / 3.0))))
    height = max(1, int(math.ceil((length / 3.0) / width)))
    data += b'\n' * (width * height * 3 - length)
    buf = io.BytesIO()
    Image.frombytes('RGB', (width, height), data).save(buf, 'png')
    return base64.b64encode(buf.getvalue()).decode('ascii')


def png_decode(b64):
    """Inverse of png_encode (trailing newline padding stripped)."""
    from PIL import Image
    img = Image.open(io.BytesIO(base64.b64decode(b64)))
    return img.convert('RGB').tobytes().rstrip(b'\n').decode('utf-8')


def split(text, size):
    return [text[i:i + size] for i in range(0, len(text), size)] or ['']


def fragments(text, mid, size, op='fragment'):
    """The fragment (or png) messages of one serialized message."""
    parts = split(text, size)
    return [{'op': op, 'id': mid, 'data': p, 'num': i, 'total': len(parts)}
            for i, p in enumerate(parts)]


def frames(message, compression='none', fragment_size=None, mid=None):
    """The frames that carry `message` (a dict) with this compression and fragment size."""
    if compression in ('cbor', 'cbor-raw'):
        return [(to_cbor(message), True)]
    return [(_utf8(data), binary) for data, binary in _text_frames(message, compression,
                                                                   fragment_size, mid)]


def _utf8(text):
    return text.encode('utf-8')


def _text_frames(message, compression, fragment_size, mid):
    text = to_json(message)
    if compression == 'png':
        data = png_encode(text)
        if fragment_size and len(data) > fragment_size:
            return [(to_json(f), False) for f in fragments(data, mid or _auto_id(), fragment_size,
                                                           op='png')]
        return [(to_json({'op': 'png', 'data': data}), False)]
    if fragment_size and len(text) > fragment_size:
        return [(to_json(f), False) for f in fragments(text, mid or _auto_id(), fragment_size)]
    return [(text, False)]


_counter = [0]


def _auto_id():
    _counter[0] += 1
    return 'fragment_%d' % _counter[0]
