#!/usr/bin/python3
"""rostest: talker_listener.launch publishes "hello world <time>" at 10 Hz and the listener logs it."""
import re
import threading
import time
import unittest

import rospy
import rostest
from rosgraph_msgs.msg import Log
from std_msgs.msg import String

HELLO = re.compile(r'^hello world (\d+\.\d+)$')


class TalkerListenerTest(unittest.TestCase):

    def setUp(self):
        self.lock = threading.Lock()
        self.chatter = []      # (receipt time, data)
        self.heard = []        # (node name, log text) of the listener's log lines
        rospy.Subscriber('chatter', String, self._chatter)
        rospy.Subscriber('/rosout', Log, self._rosout)

    def _chatter(self, msg):
        with self.lock:
            self.chatter.append((time.monotonic(), msg.data))

    def _rosout(self, msg):
        with self.lock:
            self.heard.append((msg.name, msg.msg))

    def _wait(self, cond, timeout, what):
        deadline = time.monotonic() + timeout
        while time.monotonic() < deadline and not rospy.is_shutdown():
            with self.lock:
                if cond():
                    return
            time.sleep(0.05)
        self.fail('timed out waiting for ' + what)

    def test_chatter_text_and_rate(self):
        self._wait(lambda: len(self.chatter) >= 31, 20.0, '31 chatter messages')
        with self.lock:
            msgs = list(self.chatter)
        for _, data in msgs:
            self.assertRegex(data, HELLO)
        stamps = [float(HELLO.match(d).group(1)) for _, d in msgs]
        self.assertEqual(stamps, sorted(stamps))
        # rate measured at the receiver over 30 periods, as `rostopic hz` does
        rate = 30.0 / (msgs[30][0] - msgs[0][0])
        self.assertAlmostEqual(rate, 10.0, delta=1.0)
        # the text carries rospy.get_time() of the talker: close to our clock
        self.assertLess(abs(stamps[-1] - rospy.get_time()), 5.0)

    def test_listener_logs_what_it_heard(self):
        pattern = re.compile(r'^/listener(_\d+_\d+)?I heard hello world \d+\.\d+$')
        self._wait(lambda: any(n == '/listener' and pattern.match(m) for n, m in self.heard),
                   20.0, 'the listener to log "I heard hello world ..."')
        # the talker logs each message it sends, too
        self._wait(lambda: any(n == '/talker' and HELLO.match(m) for n, m in self.heard),
                   20.0, 'the talker to log "hello world ..."')


if __name__ == '__main__':
    rospy.init_node('check_talker_listener')
    rostest.rosrun('rospy_tutorials', 'talker_listener', TalkerListenerTest)
