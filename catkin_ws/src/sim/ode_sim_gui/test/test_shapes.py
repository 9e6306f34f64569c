"""What the window inserts (no ROS, no Qt): Gazebo's unit shapes and lights as SDF the
simulator's parser reads, model names as Gazebo picks them, the wall tool's preview boxes."""
import math
import xml.etree.ElementTree as ET

import pytest

from ode_sim.description import walls
from ode_sim.description.sdf import parse_sdf_model
from ode_sim_gui import shapes


def test_unique_name():
    assert shapes.unique_name('unit_box', []) == 'unit_box'
    assert shapes.unique_name('unit_box', ['unit_box']) == 'unit_box_0'
    assert shapes.unique_name('unit_box', ['unit_box', 'unit_box_0', 'unit_box_2']) == 'unit_box_1'


@pytest.mark.parametrize('kind,geom,izz', [('box', 'box', 0.166667), ('sphere', 'sphere', 0.1),
                                           ('cylinder', 'cylinder', 0.125)])
def test_unit_shapes(kind, geom, izz):
    m = parse_sdf_model(shapes.shape_sdf(kind, 'unit_' + kind), '<test>')
    assert m.name == 'unit_' + kind and not m.static
    (link,) = m.links
    assert link.inertial.mass == 1.0 and link.inertial.izz == pytest.approx(izz)
    assert link.collisions[0].geometry.kind == geom == link.visuals[0].geometry.kind
    g = link.visuals[0].geometry
    if kind == 'box':
        assert tuple(g.size) == (1, 1, 1)
    else:
        assert g.radius == 0.5
    with pytest.raises(ValueError):
        shapes.shape_sdf('cone', 'x')


@pytest.mark.parametrize('kind', shapes.LIGHTS)
def test_lights(kind):
    root = ET.fromstring(shapes.light_sdf(kind, 'user_%s_light' % kind))
    (light,) = root
    assert light.tag == 'light' and light.get('type') == kind
    assert light.get('name') == 'user_%s_light' % kind
    assert (light.find('direction') is not None) == (kind != 'point')
    with pytest.raises(ValueError):
        shapes.light_sdf('laser', 'x')


def test_include():
    root = ET.fromstring(shapes.include_sdf('model://barrel'))
    assert root.find('include/uri').text == 'model://barrel'


def test_wall_boxes_match_the_walls_model():
    segs = [(0.0, 0.0, 4.0, 0.0), (4.0, 0.0, 4.0, 3.0)]
    boxes = shapes.wall_boxes(segs, 2.5, 0.15)
    assert boxes[0][0] == pytest.approx((4.15, 0.15, 2.5))
    assert boxes[0][1] == pytest.approx((2.0, 0.0, 1.25))
    assert boxes[0][2] == pytest.approx(0.0)
    assert boxes[1][0] == pytest.approx((3.15, 0.15, 2.5))
    assert boxes[1][1] == pytest.approx((4.0, 1.5, 1.25))
    assert boxes[1][2] == pytest.approx(math.pi / 2)
    m = parse_sdf_model(walls.walls_model('walls', segs, 2.5, 0.15), '<test>')
    assert m.static
    vis = [v for link in m.links for v in link.visuals]
    assert len(vis) == 2
    for v, (size, c, yaw) in zip(vis, boxes):
        assert tuple(v.geometry.size) == pytest.approx(size)
        assert v.pose.p == pytest.approx(c)
        assert v.pose.rpy()[2] == pytest.approx(yaw)
