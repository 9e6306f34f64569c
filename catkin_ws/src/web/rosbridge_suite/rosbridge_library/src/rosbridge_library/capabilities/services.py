"""call_service (the client calls a ROS service), advertise_service / unadvertise_service /
service_response (a ROS node calls a service the client provides)."""
import itertools
import threading

from rosbridge_library.capabilities.base import Capability, InvalidArgumentException
from rosbridge_library.internal import message_conversion, ros_loader


def args_to_request(args, request):
    """Service args as a list in field order or as a dict -> the filled request."""
    if isinstance(args, list):
        names = request.__slots__
        if len(args) > len(names):
            raise InvalidArgumentException('%s takes %d args, got %d'
                                           % (request._type, len(names), len(args)))
        args = dict(zip(names, args))
    elif args is None:
        args = {}
    message_conversion.populate_instance(args, request)
    return request


class CallService(Capability):
    def __init__(self, protocol):
        Capability.__init__(self, protocol)
        protocol.register_operation('call_service', self.call_service)

    def call_service(self, msg):
        service = self.arg(msg, 'service', str)
        args = self.arg(msg, 'args', (list, dict), False, [])
        fragment_size = self.arg(msg, 'fragment_size', int, False, None)
        compression = self.arg(msg, 'compression', str, False, 'none')
        timeout = self.arg(msg, 'timeout', (int, float), False,
                           self.protocol.settings.get('service_call_timeout'))
        cid = msg.get('id')
        if not self.allowed(service, 'services_glob'):
            self.protocol.log('warning', 'No permission to call service: %s' % service, cid)
            self._respond(service, cid, False, 'No permission to call service %s' % service,
                          fragment_size, compression)
            return
        threading.Thread(target=self._call, daemon=True, name='call_service %s' % service,
                         args=(service, args, cid, fragment_size, compression, timeout)).start()

    def _call(self, service, args, cid, fragment_size, compression, timeout):
        try:
            srv_type = self.backend.service_type(service)
            if srv_type is None:
                raise Exception('Service %s does not exist' % service)
            request = args_to_request(args, ros_loader.get_service_request_instance(srv_type))
            response = self._call_with_timeout(service, srv_type, request, timeout)
            values = message_conversion.extract_values(response)
        except Exception as e:   # a failing service answers this call only
            self.protocol.log('error', 'call_service %s: %s' % (service, e), cid)
            self._respond(service, cid, False, str(e), fragment_size, compression)
            return
        self._respond(service, cid, True, values, fragment_size, compression)

    def _call_with_timeout(self, service, srv_type, request, timeout):
        if not timeout:
            return self.backend.call_service(service, srv_type, request, None)
        box = {}

        def call():
            try:
                box['response'] = self.backend.call_service(service, srv_type, request, timeout)
            except Exception as e:   # handed to the waiting thread
                box['error'] = e
        t = threading.Thread(target=call, daemon=True, name='call %s' % service)
        t.start()
        t.join(timeout)
        if t.is_alive():
            raise Exception('Service call to %s timed out after %s s' % (service, timeout))
        if 'error' in box:
            raise box['error']
        return box['response']

    def _respond(self, service, cid, result, values, fragment_size, compression):
        out = {'op': 'service_response', 'service': service, 'values': values, 'result': result}
        if cid is not None:
            out['id'] = cid
        self.protocol.send(out, 'png' if compression == 'png' else 'none', fragment_size)


class _Pending(object):
    def __init__(self):
        self.event = threading.Event()
        self.values = None
        self.result = None


class AdvertiseService(Capability):
    """Services this client provides: a ROS call becomes a `call_service` to the client, and
    the client's `service_response` (same id) answers it."""
    _ids = itertools.count()

    def __init__(self, protocol):
        Capability.__init__(self, protocol)
        self.services = {}      # service -> type
        self.pending = {}       # request id -> _Pending
        self.lock = threading.Lock()
        protocol.register_operation('advertise_service', self.advertise_service)
        protocol.register_operation('unadvertise_service', self.unadvertise_service)
        protocol.register_operation('service_response', self.service_response)

    def advertise_service(self, msg):
        service = self.arg(msg, 'service', str)
        srv_type = self.arg(msg, 'type', str)
        if not self.allowed(service, 'services_glob'):
            self.protocol.log('warning', 'No permission to advertise service: %s' % service,
                              msg.get('id'))
            return
        cls = ros_loader.get_service_class(srv_type)
        if service in self.services:     # the original replaces an existing advertisement
            self.backend.unadvertise_service(self.protocol.client_id, service)
        self.backend.advertise_service(self.protocol.client_id, service, srv_type,
                                       lambda req: self._handle(service, cls, req))
        self.services[service] = srv_type
        self.protocol.log('info', 'Advertised service %s.' % service, msg.get('id'))

    def unadvertise_service(self, msg):
        service = self.arg(msg, 'service', str)
        if service not in self.services:
            self.protocol.log('warning', 'Service %s has not been advertised via rosbridge.'
                              % service, msg.get('id'))
            return
        del self.services[service]
        self.backend.unadvertise_service(self.protocol.client_id, service)
        self._fail_pending(service)
        self.protocol.log('info', 'Unadvertised service %s.' % service, msg.get('id'))

    def _handle(self, service, cls, request):
        """Runs on the ROS service thread: forward to the client, wait for its answer."""
        rid = 'service_request:%s:%d' % (service, next(self._ids))
        pending = _Pending()
        with self.lock:
            self.pending[rid] = (service, pending)
        try:
            self.protocol.send({'op': 'call_service', 'id': rid, 'service': service,
                                'args': message_conversion.extract_values(request)})
            while not pending.event.wait(0.1):
                if self.protocol.finished or service not in self.services:
                    raise Exception('service %s: the rosbridge client that provided it is gone'
                                    % service)
        finally:
            with self.lock:
                self.pending.pop(rid, None)
        if pending.result is None:
            raise Exception('service %s: the rosbridge client that provided it is gone'
                            % service)
        if not pending.result:
            raise Exception('service %s failed in the rosbridge client: %s'
                            % (service, pending.values))
        response = cls._response_class()
        message_conversion.populate_instance(pending.values or {}, response)
        return response

    def service_response(self, msg):
        rid = self.arg(msg, 'id', str)
        with self.lock:
            entry = self.pending.get(rid)
        if entry is None:
            raise Exception('no pending request with id %s' % rid)
        pending = entry[1]
        pending.values = msg.get('values')
        pending.result = bool(msg.get('result', True))
        pending.event.set()

    def _fail_pending(self, service=None):
        with self.lock:
            for s, p in self.pending.values():
                if service is None or s == service:
                    p.event.set()

    def finish(self):
        for service in list(self.services):
            self.backend.unadvertise_service(self.protocol.client_id, service)
        self.services.clear()
        self._fail_pending()
