"""The look-ups behind message_info_service.py (what the C++ rosserial_server asks for the types
it cannot know at compile time): a message type's md5 sum and full definition, a service type's
md5 sums. Unknown types give empty strings (as the original), with one warning naming the type."""
import roslib.message


class MessageInfo(object):
    def __init__(self, log_warn=None):
        self.log_warn = log_warn or (lambda text: None)
        self.messages = {}
        self.services = {}

    def message(self, type_name):
        """'pkg/Type' -> (md5, full definition) or ('', '')."""
        if type_name not in self.messages:
            cls = None
            try:
                cls = roslib.message.get_message_class(type_name)
            except (ValueError, ImportError, AttributeError):
                cls = None
            if cls is None:
                self.log_warn('message_info: unknown message type %r (is its package built and '
                              'the workspace sourced?)' % type_name)
                return '', ''
            self.messages[type_name] = (cls._md5sum, cls._full_text)
        return self.messages[type_name]

    def service(self, type_name):
        """'pkg/Srv' -> (service md5, request md5, response md5) or ('', '', '')."""
        if type_name not in self.services:
            cls = None
            try:
                cls = roslib.message.get_service_class(type_name)
            except (ValueError, ImportError, AttributeError):
                cls = None
            if cls is None:
                self.log_warn('service_info: unknown service type %r (is its package built and '
                              'the workspace sourced?)' % type_name)
                return '', '', ''
            self.services[type_name] = (cls._md5sum, cls._request_class._md5sum,
                                        cls._response_class._md5sum)
        return self.services[type_name]
