"""The one module between rospy and the ROS-free link core: message classes, md5 checks,
publishers, subscribers, services, parameters, logging, time and diagnostics."""
import io
import time

import roslib.message
import rospy
from diagnostic_msgs.msg import DiagnosticArray, DiagnosticStatus, KeyValue


def load_message(message_type):
    cls = roslib.message.get_message_class(message_type)
    if cls is None:
        raise ValueError('Cannot import message type %s: is its package built and the workspace '
                         'sourced?' % message_type)
    return cls


def load_service(service_type):
    cls = roslib.message.get_service_class(service_type)
    if cls is None:
        raise ValueError('Cannot import service type %s: is its package built and the workspace '
                         'sourced?' % service_type)
    return cls


def serialize(msg):
    buf = io.BytesIO()
    msg.serialize(buf)
    return buf.getvalue()


def _check(cls, md5):
    if cls._md5sum != md5:
        raise ValueError('Checksum does not match: %s,%s' % (cls._md5sum, md5))


class Publisher(object):
    def __init__(self, info):
        self.message_type = info.message_type
        self.cls = load_message(info.message_type)
        _check(self.cls, info.md5sum)
        # latched: a message the device sends once right after sync (a status, a calibration)
        # still reaches a subscriber whose connection is made after it was published
        self.pub = rospy.Publisher(info.topic_name, self.cls, queue_size=10, latch=True)

    def handle(self, payload):
        m = self.cls()
        m.deserialize(payload)
        self.pub.publish(m)


class Subscriber(object):
    def __init__(self, info, deliver):
        self.message_type = info.message_type
        self.cls = load_message(info.message_type)
        _check(self.cls, info.md5sum)
        self.deliver = deliver
        self.sub = rospy.Subscriber(info.topic_name, self.cls, self.callback)

    def callback(self, msg):
        self.deliver(serialize(msg))

    def unregister(self):
        self.sub.unregister()


class ServiceServer(object):
    """A ROS service whose calls are served by the device."""

    def __init__(self, info, call):
        self.srv = load_service(info.message_type)
        self.call = call
        self.service = rospy.Service(info.topic_name, self.srv, self.handle)

    def handle(self, req):
        try:
            payload = self.call(serialize(req))
        except Exception as e:
            raise rospy.ServiceException(str(e))
        res = self.srv._response_class()
        res.deserialize(payload)
        return res


class ServiceClient(object):
    """A ROS service the device calls."""

    def __init__(self, info, wait=10.0):
        self.srv = load_service(info.message_type)
        self.name = info.topic_name
        self.wait = wait
        self.proxy = rospy.ServiceProxy(info.topic_name, self.srv)

    def call(self, payload):
        req = self.srv._request_class()
        req.deserialize(payload)
        rospy.wait_for_service(self.name, self.wait)
        return serialize(self.proxy(req))


class RosBackend(object):
    def __init__(self):
        self.pub_diagnostics = rospy.Publisher('/diagnostics', DiagnosticArray, queue_size=10)

    def log(self, level, text):
        {'debug': rospy.logdebug, 'info': rospy.loginfo, 'warn': rospy.logwarn,
         'error': rospy.logerr, 'fatal': rospy.logfatal}[level](text)

    def now(self):
        t = rospy.Time.now()
        return t.secs, t.nsecs

    def get_param(self, name):
        if not rospy.has_param(name):
            raise KeyError(name)
        return rospy.get_param(name)

    def publisher(self, info):
        return Publisher(info)

    def subscriber(self, info, deliver):
        return Subscriber(info, deliver)

    def service_server(self, info, call):
        return ServiceServer(info, call)

    def service_client(self, info):
        return ServiceClient(info)

    def check_md5(self, info, part):
        if part == 'message':
            _check(load_message(info.message_type), info.md5sum)
            return
        srv = load_service(info.message_type)
        _check(srv._request_class if part == 'request' else srv._response_class, info.md5sum)

    def diagnostics(self, message, lastsync, lastsync_lost):
        status = DiagnosticStatus(name='rosserial_python', level=DiagnosticStatus.ERROR,
                                  message=message)
        status.values = [KeyValue('last sync', time.ctime(lastsync) if lastsync else 'never'),
                         KeyValue('last sync lost',
                                  time.ctime(lastsync_lost) if lastsync_lost else 'never')]
        arr = DiagnosticArray(status=[status])
        arr.header.stamp = rospy.Time.now()
        self.pub_diagnostics.publish(arr)
