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
        # 10 Hz as the talker keeps it (rospy.Rate(10)), from the send times in the text: the
        # typical period is 0.1 s, and the talker never runs ahead of its schedule. (Receipt
        # times, as `rostopic hz` sees them, also carry the machine's load; not judged here.)
        periods = sorted(b - a for a, b in zip(stamps, stamps[1:]))
        self.assertAlmostEqual(periods[len(periods) // 2], 0.1, delta=0.02)
        self.assertGreaterEqual((stamps[-1] - stamps[0]) / (len(stamps) - 1), 0.095)
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
