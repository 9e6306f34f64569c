#!/usr/bin/env python3
"""A stand-in for the simulator's ROS API, for spawn_model's tests.

    fake_gazebo.py RECORD_FILE NAMESPACE [NAMESPACE ...]

Serves spawn_urdf_model, spawn_sdf_model, set_model_configuration, delete_model and
unpause_physics under each namespace, publishes <ns>/model_states (10 Hz) with the models spawned
so far, and appends one JSON line per request to RECORD_FILE. A model whose name starts with
"bad" is refused (success false, status "fake: refusing model NAME").
"""
import json
import threading

import rospy
from gazebo_msgs.msg import ModelStates
from gazebo_msgs.srv import (DeleteModel, DeleteModelResponse, SetModelConfiguration,
                             SetModelConfigurationResponse, SpawnModel, SpawnModelResponse)
from geometry_msgs.msg import Pose, Twist
from std_srvs.srv import Empty, EmptyResponse


class Fake:
    def __init__(self, record, namespaces):
        self.lock = threading.Lock()
        self.record_file = open(record, 'a', buffering=1)
        self.models = {ns: [] for ns in namespaces}
        self.pubs = {}
        self.services = []
        for ns in namespaces:
            for kind in ('urdf', 'sdf'):
                self.services.append(rospy.Service(
                    ns + '/spawn_%s_model' % kind, SpawnModel,
                    lambda req, ns=ns, kind=kind: self.spawn(ns, kind, req)))
            self.services.append(rospy.Service(ns + '/set_model_configuration',
                                               SetModelConfiguration,
                                               lambda req, ns=ns: self.configure(ns, req)))
            self.services.append(rospy.Service(ns + '/delete_model', DeleteModel,
                                               lambda req, ns=ns: self.delete(ns, req)))
            self.services.append(rospy.Service(ns + '/unpause_physics', Empty,
                                               lambda req, ns=ns: self.unpause(ns)))
            self.pubs[ns] = rospy.Publisher(ns + '/model_states', ModelStates, queue_size=1)

    def record(self, **entry):
        with self.lock:
            self.record_file.write(json.dumps(entry) + '\n')

    def spawn(self, ns, kind, req):
        p, q = req.initial_pose.position, req.initial_pose.orientation
        self.record(service=ns + '/spawn_%s_model' % kind, model_name=req.model_name,
                    model_xml=req.model_xml, robot_namespace=req.robot_namespace,
                    pose=[p.x, p.y, p.z, q.x, q.y, q.z, q.w],
                    reference_frame=req.reference_frame)
        if req.model_name.startswith('bad'):
            return SpawnModelResponse(False, 'fake: refusing model %s' % req.model_name)
        with self.lock:
            self.models[ns].append(req.model_name)
        return SpawnModelResponse(True, 'fake: spawned %s' % req.model_name)

    def configure(self, ns, req):
        self.record(service=ns + '/set_model_configuration', model_name=req.model_name,
                    urdf_param_name=req.urdf_param_name, joint_names=list(req.joint_names),
                    joint_positions=list(req.joint_positions))
        return SetModelConfigurationResponse(True, 'fake: configured')

    def delete(self, ns, req):
        self.record(service=ns + '/delete_model', model_name=req.model_name)
        with self.lock:
            if req.model_name in self.models[ns]:
                self.models[ns].remove(req.model_name)
        return DeleteModelResponse(True, 'fake: deleted')

    def unpause(self, ns):
        self.record(service=ns + '/unpause_physics')
        return EmptyResponse()

    def publish(self):
        for ns, pub in self.pubs.items():
            with self.lock:
                names = list(self.models[ns])
            pub.publish(ModelStates(names, [Pose() for _ in names], [Twist() for _ in names]))


def main():
    argv = rospy.myargv()
    rospy.init_node('fake_gazebo')
    fake = Fake(argv[1], argv[2:])
    fake.record(service='ready')
    rate = rospy.Rate(10)
    while not rospy.is_shutdown():
        fake.publish()
        try:
            rate.sleep()
        except rospy.ROSInterruptException:
            break


if __name__ == '__main__':
    main()
