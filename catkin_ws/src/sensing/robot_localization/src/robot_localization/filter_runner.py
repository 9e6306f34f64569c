"""The part of robot_localization's RosFilter that needs no ROS: the measurement queue,
per-topic stamp checks, the sensor timeout and set_pose. Warnings are collected as
(key, text) for the node to log (throttled)."""
import heapq
import itertools

import numpy as np

from .ekf import Ekf, STATE_SIZE, NAN_ERROR

SET_POSE_BASE_VARIANCE = 1e-6


def timestamp_before_previous(topic):
    return ('The %s message has a timestamp before that of the previous message received, this '
            'message will be ignored. This may indicate a bad clock.' % topic)


def timestamp_before_reset(topic):
    return ('The %s message has a timestamp equal to or before the last filter reset, this message '
            'will be ignored. This may indicate an empty or bad timestamp.' % topic)


class FilterRunner:
    def __init__(self, ekf=None, sensor_timeout=1.0 / 30.0):
        self.ekf = ekf or Ekf()
        self.sensor_timeout = sensor_timeout
        self.queue = []
        self._seq = itertools.count()
        self.last_stamp = {}
        self.last_reset = None
        self.warnings = []
        self.enabled = True

    def _warn(self, key, text):
        self.warnings.append((key, text))

    def accept_stamp(self, topic, stamp):
        """The original's per-topic checks; False (with a warning) if the message is ignored."""
        if self.last_reset is not None and stamp <= self.last_reset:
            self._warn(topic + '_timestamp', timestamp_before_reset(topic))
            return False
        last = self.last_stamp.get(topic)
        if last is not None and stamp < last:
            self._warn(topic + '_timestamp', timestamp_before_previous(topic))
            return False
        self.last_stamp[topic] = stamp
        return True

    def enqueue(self, measurement):
        if measurement is not None and self.enabled:
            heapq.heappush(self.queue, (measurement.time, next(self._seq), measurement))

    def integrate(self, now):
        """Fuse queued measurements in time order; predict-only after sensor_timeout.
        Returns True when there is a state to publish."""
        ekf = self.ekf
        while self.queue:
            _, _, m = heapq.heappop(self.queue)
            ekf.process(m)
        if ekf.initialized and ekf.last_time is not None and \
                now - ekf.last_time >= self.sensor_timeout:
            ekf.predict(now)
        if ekf.nan_detected:
            self._warn('nan', NAN_ERROR)
            ekf.nan_detected = False
        return ekf.initialized

    def set_pose(self, time, pose, covariance):
        """Reset the state to pose (x y z roll pitch yaw), zero twist/accel, as the original."""
        ekf = self.ekf
        state = np.zeros(STATE_SIZE)
        state[0:6] = pose
        ekf.reset(state)
        P = np.eye(STATE_SIZE) * SET_POSE_BASE_VARIANCE
        P[0:6, 0:6] = ekf.sanitize_covariance(covariance)
        ekf.P = P
        ekf.initialized = True
        ekf.last_time = time
        self.queue = []
        self.last_reset = time
        self.last_stamp = {}
