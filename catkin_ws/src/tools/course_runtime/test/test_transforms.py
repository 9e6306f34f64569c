"""course_runtime.transforms without a master."""
import numpy as np
import rospy

from course_runtime.transforms import transform_stamped


def test_transform_stamped_fields_are_floats():
    t = transform_stamped(rospy.Time(2), 'odom', 'base_link', np.array([1, 2, 3]),
                          (0, 0, np.float32(0.5), 0.75))
    assert (t.header.stamp, t.header.frame_id, t.child_frame_id) == (rospy.Time(2), 'odom', 'base_link')
    tr, r = t.transform.translation, t.transform.rotation
    assert (tr.x, tr.y, tr.z) == (1.0, 2.0, 3.0) and (r.x, r.y, r.z, r.w) == (0.0, 0.0, 0.5, 0.75)
    assert all(type(v) is float for v in (tr.x, tr.y, tr.z, r.x, r.y, r.z, r.w))
