"""rosapi_node: the /rosapi/* services, answered from the master (rosgraph) and the message
classes. Globs from ~topics_glob, ~services_glob, ~params_glob ('[*]' = everything)."""
import rosgraph
import rospy
import rosservice

from rosapi import graph, objectutils
from rosbridge_library.internal.globs import parse_glob
from rosbridge_library.internal.tcpros_backlog import deepen_tcpros_backlog
from rosapi import srv as S
from rosapi.msg import TypeDef


def _parse_glob(name):
    try:
        return parse_glob(rospy.get_param('~' + name, '[*]'), name)
    except ValueError as e:
        rospy.logfatal('rosapi: %s' % e)
        raise SystemExit(1)


class RosApi(object):
    def __init__(self):
        self.topics_glob = _parse_glob('topics_glob')
        self.services_glob = _parse_glob('services_glob')
        self.params_glob = _parse_glob('params_glob')
        self.protect_node_params = bool(rospy.get_param('~protect_node_params', False))

    # rospy answers service requests on concurrent threads, and an xmlrpc ServerProxy (one
    # HTTP connection) breaks when two threads use it at once (CannotSendRequest,
    # ResponseNotReady): every call gets its own master proxy.
    @staticmethod
    def master():
        return rosgraph.Master('/rosapi')

    def state(self):
        return self.master().getSystemState()

    def topic_types(self):
        return self.master().getTopicTypes()

    def _check_writable(self, name, op):
        """~protect_node_params (ours, web.launch sets it): set_param / delete_param of a
        running node's private parameter (/node/...) is refused."""
        if not self.protect_node_params:
            return
        owner = graph.private_param_owner(name, graph.nodes(self.state()))
        if owner:
            raise rospy.ServiceException(
                '%s %s: a private parameter of node %s; this launch keeps other nodes\' '
                'parameters read-only (protect_node_params:=false opens them)'
                % (op, name, owner))

    # ------------------------------------------------------------------------ handlers
    def topics(self, req):
        return graph.topics_and_types(self.topic_types(), self.topics_glob)

    def topics_for_type(self, req):
        return [graph.topics_for_type(self.topic_types(), req.type, self.topics_glob)]

    def topics_and_raw_types(self, req):
        topics, types = graph.topics_and_types(self.topic_types(), self.topics_glob)
        texts = []
        for t in types:
            try:
                texts.append(objectutils.full_text(t))
            except Exception:   # a type whose package is not on this machine
                texts.append('')
        return topics, types, texts

    def services(self, req):
        return [graph.services(self.state(), self.services_glob)]

    def services_for_type(self, req):
        out = []
        for s in graph.services(self.state(), self.services_glob):
            try:
                if rosservice.get_service_type(s) == req.type:
                    out.append(s)
            except Exception:   # a service that went away meanwhile
                pass
        return [out]

    def nodes(self, req):
        return [graph.nodes(self.state())]

    def node_details(self, req):
        return graph.node_details(self.state(), req.node, self.topics_glob, self.services_glob)

    def action_servers(self, req):
        return [graph.action_servers(self.topic_types(), self.topics_glob)]

    def topic_type(self, req):
        return [graph.topic_type(self.topic_types(), req.topic, self.topics_glob)]

    def service_type(self, req):
        if not graph.allowed(req.service, self.services_glob):
            return ['']
        try:
            return [rosservice.get_service_type(req.service) or '']
        except Exception:
            return ['']

    def publishers(self, req):
        return [graph.publishers(self.state(), req.topic, self.topics_glob)]

    def subscribers(self, req):
        return [graph.subscribers(self.state(), req.topic, self.topics_glob)]

    def service_providers(self, req):
        return [graph.service_providers(self.state(), req.service, self.services_glob)]

    def service_node(self, req):
        if not graph.allowed(req.service, self.services_glob):
            return ['']
        try:
            return [rosservice.get_service_node(req.service) or '']
        except Exception:
            return ['']

    def service_host(self, req):
        if not graph.allowed(req.service, self.services_glob):
            return ['']
        try:
            return [graph.host_of_uri(rosservice.get_service_uri(req.service))]
        except Exception:
            return ['']

    def _typedefs(self, make, name):
        try:
            return [[TypeDef(**d) for d in make(name)]]
        except Exception as e:
            raise rospy.ServiceException('unknown type %s: %s' % (name, e))

    def message_details(self, req):
        return self._typedefs(objectutils.message_typedefs, req.type)

    def service_request_details(self, req):
        return self._typedefs(objectutils.service_request_typedefs, req.type)

    def service_response_details(self, req):
        return self._typedefs(objectutils.service_response_typedefs, req.type)

    def set_param(self, req):
        if graph.allowed(req.name, self.params_glob):
            self._check_writable(req.name, 'set_param')
            try:
                value = graph.json_to_param(req.value)
            except ValueError as e:
                raise rospy.ServiceException(str(e))
            rospy.set_param(req.name, value)
        return []

    def get_param(self, req):
        default = graph.default_param(req.default)
        if graph.allowed(req.name, self.params_glob):
            return [graph.param_to_json(rospy.get_param(req.name, default))]
        return [graph.param_to_json(default)]

    def has_param(self, req):
        return [graph.allowed(req.name, self.params_glob) and rospy.has_param(req.name)]

    def search_param(self, req):
        if not graph.allowed(req.name, self.params_glob):
            return ['']
        return [rospy.search_param(req.name) or '']

    def delete_param(self, req):
        if graph.allowed(req.name, self.params_glob) and rospy.has_param(req.name):
            self._check_writable(req.name, 'delete_param')
            rospy.delete_param(req.name)
        return []

    def get_param_names(self, req):
        return [graph.param_names(rospy.get_param_names(), self.params_glob)]

    def get_time(self, req):
        return [rospy.get_rostime()]


SERVICES = [
    ('topics', S.Topics), ('topics_for_type', S.TopicsForType),
    ('topics_and_raw_types', S.TopicsAndRawTypes), ('services', S.Services),
    ('services_for_type', S.ServicesForType), ('nodes', S.Nodes),
    ('node_details', S.NodeDetails), ('action_servers', S.GetActionServers),
    ('topic_type', S.TopicType), ('service_type', S.ServiceType),
    ('publishers', S.Publishers), ('subscribers', S.Subscribers),
    ('service_providers', S.ServiceProviders), ('service_node', S.ServiceNode),
    ('service_host', S.ServiceHost), ('message_details', S.MessageDetails),
    ('service_request_details', S.ServiceRequestDetails),
    ('service_response_details', S.ServiceResponseDetails),
    ('set_param', S.SetParam), ('get_param', S.GetParam), ('has_param', S.HasParam),
    ('search_param', S.SearchParam), ('delete_param', S.DeleteParam),
    ('get_param_names', S.GetParamNames), ('get_time', S.GetTime),
]


def main():
    rospy.init_node('rosapi')
    api = RosApi()
    services = [rospy.Service('/rosapi/' + name, cls, getattr(api, name))
                for name, cls in SERVICES]
    if not deepen_tcpros_backlog():
        rospy.logwarn('rosapi: could not raise the TCPROS listen backlog: many calls at once '
                      'may time out')
    rospy.loginfo('Rosapi started')
    rospy.spin()
    del services
