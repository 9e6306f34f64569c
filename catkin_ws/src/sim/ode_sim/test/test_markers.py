"""The scene as RViz markers: one Marker per visual, right type/size/pose/colour; geometry kept
between builds (a mesh's triangle list is built once), removed shapes forgotten."""
import numpy as np
import pytest
import rospy
from visualization_msgs.msg import Marker

from ode_sim.ros.markers import SceneMarkers
from ode_sim.description.model import Geometry
from ode_sim.engine.scene import ShapeInstance
from ode_sim.description.transforms import Pose

MESH = Geometry('mesh', vertices=np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0]], float),
                faces=np.array([[0, 1, 2]]))


def shapes(moving_pose):
    def inst(name, geom, pose, color=(1, 0, 0, 1), link_pose=None):
        return ShapeInstance('m::%s::v' % name, name, 'l', geom, color=color, static_pose=pose,
                             link_pose=link_pose)
    return [inst('box', Geometry('box', size=(1, 2, 3)), Pose((1, 0, 0))),
            inst('cyl', Geometry('cylinder', radius=0.5, length=2), Pose((0, 1, 0))),
            inst('ball', Geometry('sphere', radius=0.25), Pose()),
            inst('ground', Geometry('plane', plane_size=(10, 20)), Pose(), (0.8, 0.8, 0.8, 1)),
            inst('tri', MESH, Pose(), link_pose=lambda: moving_pose[0])]


def by_ns(arr):
    return {m.ns.split('/')[-1]: m for m in arr.markers[1:]}


def test_markers_for_every_geometry():
    moving = [Pose((0, 0, 1))]
    arr = SceneMarkers('odom').build(shapes(moving), rospy.Time(5))
    assert arr.markers[0].action == Marker.DELETEALL
    m = by_ns(arr)
    assert m['box'].type == Marker.CUBE and (m['box'].scale.x, m['box'].scale.y,
                                             m['box'].scale.z) == (1, 2, 3)
    assert m['box'].pose.position.x == 1 and m['box'].header.frame_id == 'odom'
    assert m['box'].header.stamp == rospy.Time(5) and m['box'].color.r == 1
    assert m['cyl'].type == Marker.CYLINDER and m['cyl'].scale.x == 1 and m['cyl'].scale.z == 2
    assert m['ball'].type == Marker.SPHERE and m['ball'].scale.z == 0.5
    assert m['ground'].type == Marker.CUBE and (m['ground'].scale.x, m['ground'].scale.y) == (10, 20)
    assert m['ground'].pose.position.z == pytest.approx(-0.0015)      # just below the grid
    assert m['tri'].type == Marker.TRIANGLE_LIST and len(m['tri'].points) == 3
    assert m['tri'].pose.position.z == 1
    assert len({mk.id for mk in arr.markers[1:]}) == 5


def test_geometry_is_built_once_and_poses_follow():
    moving = [Pose((0, 0, 1))]
    scene = SceneMarkers('world')
    s = shapes(moving)
    first = by_ns(scene.build(s, rospy.Time(1)))['tri']
    points = first.points
    moving[0] = Pose((2, 0, 0))
    second = by_ns(scene.build(s, rospy.Time(2)))['tri']
    assert second.points is points                     # the triangle list was not rebuilt
    assert second.pose.position.x == 2 and second.header.stamp == rospy.Time(2)
    arr = scene.build(s[:1], rospy.Time(3), include=lambda sh: sh.model != 'cyl')
    assert list(by_ns(arr)) == ['box'] and len(scene._cache) == 1
