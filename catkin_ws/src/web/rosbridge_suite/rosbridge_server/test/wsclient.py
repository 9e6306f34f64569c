"""A minimal blocking WebSocket client for the tests (RFC 6455: handshake, masked frames out,
text/binary frames in): it lets a test be a client that never reads, or check every frame."""
import base64
import json
import os
import socket
import struct


class WsClient(object):
    def __init__(self, port, host='127.0.0.1', rcvbuf=None, timeout=30.0, source=None):
        self.sock = socket.socket()
        if source:      # another loopback address (127.0.0.2, ...): another client address
            self.sock.bind((source, 0))
        if rcvbuf:
            self.sock.setsockopt(socket.SOL_SOCKET, socket.SO_RCVBUF, rcvbuf)
        self.sock.settimeout(timeout)
        self.sock.connect((host, port))
        key = base64.b64encode(os.urandom(16)).decode()
        self.sock.sendall(('GET / HTTP/1.1\r\nHost: %s:%d\r\nUpgrade: websocket\r\n'
                           'Connection: Upgrade\r\nSec-WebSocket-Key: %s\r\n'
                           'Sec-WebSocket-Version: 13\r\n\r\n' % (host, port, key)).encode())
        self.buf = b''
        while b'\r\n\r\n' not in self.buf:
            chunk = self.sock.recv(4096)
            if not chunk:
                raise ConnectionError('server closed during the handshake')
            self.buf += chunk
        head, self.buf = self.buf.split(b'\r\n\r\n', 1)
        if b' 101 ' not in head.split(b'\r\n')[0]:
            raise ConnectionError('handshake refused: %r' % head[:200])

    def send_text(self, text):
        self._send(0x1, text.encode('utf-8'))

    def send(self, **msg):
        self.send_text(json.dumps(msg))

    def _send(self, opcode, payload):
        n = len(payload)
        if n < 126:
            header = struct.pack('!BB', 0x80 | opcode, 0x80 | n)
        elif n < 65536:
            header = struct.pack('!BBH', 0x80 | opcode, 0x80 | 126, n)
        else:
            header = struct.pack('!BBQ', 0x80 | opcode, 0x80 | 127, n)
        mask = os.urandom(4)
        # XOR with the mask through int arithmetic: fast enough for megabytes
        m = int.from_bytes((mask * (n // 4 + 1))[:n], 'big') if n else 0
        body = (int.from_bytes(payload, 'big') ^ m).to_bytes(n, 'big') if n else b''
        self.sock.sendall(header + mask + body)

    def _read(self, n):
        if len(self.buf) < n:
            chunks, have = [self.buf], len(self.buf)
            while have < n:
                chunk = self.sock.recv(max(262144, n - have))
                if not chunk:
                    raise ConnectionError('connection closed by the server')
                chunks.append(chunk)
                have += len(chunk)
            self.buf = b''.join(chunks)
        out, self.buf = self.buf[:n], self.buf[n:]
        return out

    def recv_frame(self):
        """(opcode, payload) of the next data frame (pings are answered, close raises)."""
        while True:
            b1, b2 = self._read(2)
            opcode, n = b1 & 0x0F, b2 & 0x7F
            if n == 126:
                n = struct.unpack('!H', self._read(2))[0]
            elif n == 127:
                n = struct.unpack('!Q', self._read(8))[0]
            payload = self._read(n)
            if opcode == 0x8:
                raise ConnectionError('server closed the connection: %r' % payload[:100])
            if opcode == 0x9:
                self._send(0xA, payload)
                continue
            if opcode in (0x1, 0x2):
                return opcode, payload

    def recv(self):
        """The next message as a dict (text frames)."""
        opcode, payload = self.recv_frame()
        return json.loads(payload.decode('utf-8')) if opcode == 0x1 else payload

    def recv_until(self, pred, limit=1000):
        for _ in range(limit):
            msg = self.recv()
            if isinstance(msg, dict) and pred(msg):
                return msg
        raise AssertionError('no matching message among %d received' % limit)

    def close(self):
        try:
            self._send(0x8, struct.pack('!H', 1000))
        except OSError:
            pass
        self.sock.close()
