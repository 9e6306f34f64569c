"""Byte transports for a DeviceLink: a serial port (pyserial) and an accepted TCP socket."""
import socket

POLL = 0.02   # seconds a read waits for the first byte


class SerialPort(object):
    """pyserial port; open errors are serial.SerialException."""

    def __init__(self, path, baud, fix_pyserial_for_test=False):
        import serial
        kw = dict(rtscts=True, dsrdtr=True) if fix_pyserial_for_test else {}
        self.serial = serial.Serial(path, baud, timeout=POLL, write_timeout=10, **kw)
        self.path = path

    def read_some(self):
        waiting = self.serial.in_waiting
        data = self.serial.read(max(1, waiting))
        return data

    def write(self, data):
        self.serial.write(data)

    def flush_input(self):
        self.serial.reset_input_buffer()

    def close(self):
        self.serial.close()


class SocketPort(object):
    """An accepted TCP connection (rosserial's tcp mode); a closed peer raises OSError."""

    def __init__(self, sock):
        self.sock = sock
        self.sock.settimeout(POLL)

    def read_some(self):
        try:
            data = self.sock.recv(4096)
        except socket.timeout:
            return b''
        if not data:
            raise OSError('the TCP client closed the connection')
        return data

    def write(self, data):
        self.sock.sendall(data)

    def flush_input(self):
        pass

    def close(self):
        self.sock.close()
