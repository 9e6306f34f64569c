"""Robot Steering maths (no Qt, no ROS): integer sliders (x1000) -> velocity commands."""

FACTOR = 1000.0


class Steering(object):
    """The command sent every 100 ms; a zero command only once until a non-zero one follows."""

    def __init__(self):
        self.linear = 0       # slider value
        self.angular = 0
        self._zero_sent = False

    def command(self):
        return self.linear / FACTOR, self.angular / FACTOR

    def next_to_send(self):
        """(vx, wz) to publish now, or None."""
        vx, wz = self.command()
        if vx == 0 and wz == 0:
            if self._zero_sent:
                return None
            self._zero_sent = True
        else:
            self._zero_sent = False
        return vx, wz

    def stop(self):
        """Both to 0; the zero command is sent (again, if it already was)."""
        self._zero_sent = False
        self.linear = self.angular = 0


def slider_limit(value):
    return int(round(value * FACTOR))


def label(value, unit):
    return '%0.2f %s' % (value, unit)
