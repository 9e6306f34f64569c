"""ros_mac_authentication: the `authenticate` service from ~secret_file_location."""
import sys

import rospy

from rosauth.mac import Authenticator, SecretError, SecretFile


def main():
    rospy.init_node('ros_mac_authentication')
    from rosauth.srv import Authentication, AuthenticationResponse
    if not rospy.has_param('~secret_file_location'):
        rospy.logerr("Parameter 'secret_file_location' not found.")
        sys.exit(-1)     # the original's MISSING_PARAMETER: exit status 255
    path = rospy.get_param('~secret_file_location')
    delta = float(rospy.get_param('~allowed_time_delta', 5))
    secret = SecretFile(path)
    try:
        secret.get()
    except SecretError as e:
        # course_web_server writes the file when it starts: the service answers `false`
        # until it is there
        rospy.logwarn('rosauth: %s; every request is refused until the file is valid' % e)
    auth = Authenticator(secret.get, delta)

    def handle(req):
        ok, reason = auth.authenticate(req.mac, req.client, req.dest, req.rand,
                                       req.t.to_sec(), req.level, req.end.to_sec())
        if not ok:
            rospy.logwarn('rosauth: refused %s -> %s: %s' % (req.client, req.dest, reason))
        return AuthenticationResponse(ok)

    rospy.Service('authenticate', Authentication, handle)
    rospy.loginfo('ROS Authentication Server Started')
    rospy.spin()
