"""Generate a host ros_lib under OUT/rosserial the way the original rosserial_test's CMake does:
through rosserial_client.make_library's module API, then every quoted include rewritten to
"rosserial/..." so the client headers cannot be confused with roscpp's."""
import os
import re
import sys

import rospkg

from rosserial_client.make_library import *  # noqa: F401,F403  (the original's usage)
from rosserial_client.make_library import (MessageDataType, PrimitiveDataType, StringDataType,
                                           TimeDataType, rosserial_client_copy_files,
                                           rosserial_generate)

MAPPING = {
    'bool': ('bool', 1, PrimitiveDataType, []),
    'byte': ('int8_t', 1, PrimitiveDataType, []),
    'int8': ('int8_t', 1, PrimitiveDataType, []),
    'char': ('uint8_t', 1, PrimitiveDataType, []),
    'uint8': ('uint8_t', 1, PrimitiveDataType, []),
    'int16': ('int16_t', 2, PrimitiveDataType, []),
    'uint16': ('uint16_t', 2, PrimitiveDataType, []),
    'int32': ('int32_t', 4, PrimitiveDataType, []),
    'uint32': ('uint32_t', 4, PrimitiveDataType, []),
    'int64': ('int64_t', 8, PrimitiveDataType, []),
    'uint64': ('uint64_t', 8, PrimitiveDataType, []),
    'float32': ('float', 4, PrimitiveDataType, []),
    'float64': ('double', 8, PrimitiveDataType, []),
    'time': ('ros::Time', 8, TimeDataType, ['ros/time']),
    'duration': ('ros::Duration', 8, TimeDataType, ['ros/duration']),
    'string': ('char*', 0, StringDataType, []),
    'Header': ('std_msgs::Header', 0, MessageDataType, ['std_msgs/Header']),
}

out = os.path.join(sys.argv[1], 'rosserial')
rospack = rospkg.RosPack()
rosserial_client_copy_files(rospack, out + os.sep)
failed = rosserial_generate(rospack, out, MAPPING)
for d, _, files in os.walk(out):
    for fn in files:
        p = os.path.join(d, fn)
        with open(p) as f:
            text = f.read()
        with open(p, 'w') as f:
            f.write(re.sub(r'^#include "([^"]+)"', r'#include "rosserial/\1"', text, flags=re.M))
sys.exit(1 if failed else 0)
