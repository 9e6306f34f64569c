"""message_info_service.py: message_info and service_info answer the md5 sums and definitions of
the types a device declares (what the C++ rosserial_server needs); unknown types give empty
strings and one warning naming the type."""
import subprocess
import sys

from course_testing import Proc, wait_for
from rosserial_python.message_info import MessageInfo


def test_lookups_without_a_master():
    warned = []
    info = MessageInfo(warned.append)
    md5, text = info.message('std_msgs/String')
    assert md5 == '992ce8a1687cec8c8bd883ec73ca41d1' and text.strip() == 'string data'
    assert info.message('geometry_msgs/PoseStamped')[1].count('MSG: ') == 4
    assert info.service('std_srvs/Trigger') == ('937c9679a518e3a18d831e57125ea522',
                                                'd41d8cd98f00b204e9800998ecf8427e',
                                                '937c9679a518e3a18d831e57125ea522')
    assert info.message('no_pkg/Nothing') == ('', '')
    assert info.service('no_pkg/Nothing') == ('', '', '')
    assert len(warned) == 2 and "'no_pkg/Nothing'" in warned[0]


def test_node_answers_both_services(roscore, tmp_path):
    node = Proc(['rosrun', 'rosserial_python', 'message_info_service.py'], env=roscore.env,
                log=str(tmp_path / 'node.log'))
    try:
        code = ('import rospy\n'
                'from rosserial_msgs.srv import RequestMessageInfo, RequestServiceInfo\n'
                'rospy.wait_for_service("message_info", 60)\n'
                'r = rospy.ServiceProxy("message_info", RequestMessageInfo)("std_msgs/Header")\n'
                'print(r.md5)\n'
                'print(rospy.ServiceProxy("service_info", RequestServiceInfo)("std_srvs/Empty"))\n')
        p = subprocess.run([sys.executable, '-c', code], env=roscore.env, capture_output=True,
                           text=True, timeout=90)
        assert p.returncode == 0, p.stderr
        assert '2176decaecbce78abc3b96ef049fabed' in p.stdout
        assert 'service_md5: "d41d8cd98f00b204e9800998ecf8427e"' in p.stdout, p.stdout
        wait_for(lambda: 'rosserial message_info_service node' in node.output(), 30,
                 what='the node\'s start line')
    finally:
        node.stop()
