#!/usr/bin/env python3
"""rosrun rosserial_arduino make_libraries.py DIR

Deletes DIR/ros_lib and builds it anew: the client library (rosserial_client's core and this
package's ros.h, ArduinoHardware.h, examples) and one header per message and service of every
package visible to rospack (Debian's and the sourced workspaces'), float64 as AVR float."""
import os
import sys

from rosserial_client.make_library import PRIMITIVES_ARDUINO, main


def arduino_dir():
    here = os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', 'src', 'ros_lib')
    if os.path.isdir(here):
        return os.path.normpath(here)
    import rospkg
    return os.path.join(rospkg.RosPack().get_path('rosserial_arduino'), 'src', 'ros_lib')


if __name__ == '__main__':
    sys.exit(main(sys.argv[1:], PRIMITIVES_ARDUINO, [arduino_dir()], prog='make_libraries.py'))
