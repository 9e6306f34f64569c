"""costmap_2d core without a master: cost values, layers, raytracing, footprints, parameters."""
import math
import os

import numpy as np
import pytest
import yaml

from costmap_2d.costmap import (FREE_SPACE, INSCRIBED_INFLATED_OBSTACLE, LETHAL_OBSTACLE,
                                NO_INFORMATION, Costmap2D, FootprintError,
                                calculate_min_and_max_distances, cost_translation_table,
                                make_footprint_from_radius, pad_footprint, parse_footprint)
from costmap_2d.layers import (InflationLayer, LayeredCostmap, Observation, ObstacleLayer,
                               StaticLayer, inflation_cost)
from costmap_2d.params import CostmapParamError, layer_specs, observation_sources

DIPLOMA = os.path.join(os.path.dirname(__file__), '../../move_base/test/config/diploma')


def test_inflation_cost_formula():
    res, r_in, k = 0.05, 0.1, 10.0
    assert inflation_cost(0, res, r_in, k) == LETHAL_OBSTACLE
    assert inflation_cost(1, res, r_in, k) == INSCRIBED_INFLATED_OBSTACLE   # 0.05 m
    assert inflation_cost(2, res, r_in, k) == INSCRIBED_INFLATED_OBSTACLE   # 0.10 m
    for d in (3, 5, 8, 11):
        expected = int(252 * math.exp(-k * (d * res - r_in)))
        assert inflation_cost(d, res, r_in, k) == expected
    arr = inflation_cost(np.array([0.0, 1.0, 3.0]), res, r_in, k)
    assert list(arr) == [254, 253, int(252 * math.exp(-0.5))]


def make_layered(values, res=0.1, inflation_radius=0.5, footprint=None):
    ny, nx = values.shape
    lc = LayeredCostmap('map', False, False)
    st, ob, inf = StaticLayer(), ObstacleLayer(), InflationLayer(inflation_radius=inflation_radius)
    for layer in (st, ob, inf):
        lc.add_plugin(layer)
    lc.set_footprint(footprint or [(-0.05, -0.05), (-0.05, 0.05), (0.05, 0.05), (0.05, -0.05)])
    st.set_map(nx, ny, res, 0.0, 0.0, values.ravel())
    return lc, st, ob, inf


def test_static_and_inflation_cells():
    v = np.zeros((10, 10), dtype=int)
    v[5, 5] = 100
    v[0, 0] = -1
    lc, *_ = make_layered(v)
    assert (lc.costmap.size_x, lc.costmap.size_y) == (10, 10)   # resized to the map
    lc.update_map(0.85, 0.85, 0.0)
    d = lc.costmap.data
    assert d[5, 5] == LETHAL_OBSTACLE
    # inscribed radius 0.05 < one cell: the neighbours get 252 * exp(-10 * (0.1 - 0.05))
    assert d[5, 6] == int(252 * math.exp(-10 * 0.05))
    assert d[6, 6] == int(252 * math.exp(-10 * (math.sqrt(2) * 0.1 - 0.05)))
    assert d[5, 0] == int(252 * math.exp(-10 * 0.45))   # 0.5 m: the inflation radius's edge
    assert d[9, 1] == FREE_SPACE                         # beyond it
    # unknown in the map, but the obstacle layer (track_unknown_space false) says free and
    # wins by updateWithMax, as in the original
    assert d[0, 0] == FREE_SPACE
    lc2, st2, ob2, _ = make_layered(v)
    ob2.track_unknown_space = True
    ob2.match_size()
    lc2.update_map(0.85, 0.85, 0.0)
    assert lc2.costmap.data[0, 0] == NO_INFORMATION
    assert d[9, 9] == FREE_SPACE


def test_static_layer_interpretation():
    st = StaticLayer(track_unknown_space=False, trinary_costmap=False, lethal_cost_threshold=50)
    out = st.interpret([-1, 0, 25, 50, 100])
    assert list(out) == [FREE_SPACE, 0, int(25 / 50 * 254), LETHAL_OBSTACLE, LETHAL_OBSTACLE]


def test_marking_respects_obstacle_range_and_clearing_raytraces():
    v = np.zeros((40, 40), dtype=int)
    lc, st, ob, inf = make_layered(v, res=0.1, inflation_radius=0.0)
    origin = (0.55, 2.05, 0.2)
    near = [3.05, 2.05, 0.2]      # 2.5 m away: outside obstacle_range 2.5 (strict <)
    closer = [2.95, 2.05, 0.2]
    ob.set_observations([Observation(origin, [near, closer], 2.5, 3.0)], [])
    lc.update_map(0.55, 2.05, 0.0)
    assert ob.grid.data[20, 29] == LETHAL_OBSTACLE
    assert ob.grid.data[20, 30] == FREE_SPACE
    # a later scan sees through the obstacle: the ray clears it and marks the far point
    ob.set_observations([Observation(origin, [[3.45, 2.05, 0.2]], 3.0, 3.0)],
                        [Observation(origin, [[3.45, 2.05, 0.2]], 3.0, 3.0)])
    lc.update_map(0.55, 2.05, 0.0)
    assert ob.grid.data[20, 29] == FREE_SPACE
    assert ob.grid.data[20, 34] == LETHAL_OBSTACLE
    assert lc.costmap.data[20, 34] == LETHAL_OBSTACLE


def test_raytrace_stops_at_raytrace_range_and_map_edge():
    lc = LayeredCostmap('odom', False, True)
    lc.resize_map(50, 10, 0.1, 0.0, 0.0)
    ob = ObstacleLayer(track_unknown_space=True)
    lc.add_plugin(ob)
    ob.raytrace_freespace(Observation((0.05, 0.55, 0.0), [[100.0, 0.55, 0.0]], 2.5, 1.0))
    row = ob.grid.data[5]
    assert (row[:10] == FREE_SPACE).all()
    assert (row[11:] == NO_INFORMATION).all()
    ob.raytrace_freespace(Observation((0.05, 0.55, 0.0), [[100.0, 0.55, 0.0]], 2.5, 30.0))
    assert (ob.grid.data[5] == FREE_SPACE).all()   # clipped at the edge, no error


def test_footprint_clearing():
    v = np.zeros((20, 20), dtype=int)
    lc, st, ob, inf = make_layered(v, res=0.1, inflation_radius=0.0,
                                   footprint=[(-0.2, -0.2), (-0.2, 0.2), (0.2, 0.2), (0.2, -0.2)])
    ob.set_observations([Observation((1.0, 1.0, 0), [[1.05, 1.05, 0]], 2.5, 3.0)], [])
    lc.update_map(1.0, 1.0, 0.0)
    assert ob.grid.data[10, 10] == FREE_SPACE     # under the robot: cleared


def test_rolling_window_keeps_overlap():
    c = Costmap2D(10, 10, 1.0, 0.0, 0.0)
    c.data[5, 5] = 7
    c.update_origin(2.0, 1.0)
    assert (c.origin_x, c.origin_y) == (2.0, 1.0)
    assert c.data[4, 3] == 7
    assert c.data[:, 8:].max() == 0


def test_footprints():
    diploma = parse_footprint('[[-0.08,-0.12], [-0.08,0.12], [0.08,0.12], [0.08,-0.12]]')
    assert diploma[0] == (-0.08, -0.12)
    padded = pad_footprint(diploma, 0.01)
    assert padded[0] == pytest.approx((-0.09, -0.13))
    r_in, r_out = calculate_min_and_max_distances(padded)
    assert r_in == pytest.approx(0.09)
    assert r_out == pytest.approx(math.hypot(0.09, 0.13))
    circle = make_footprint_from_radius(0.46)
    assert len(circle) == 16
    assert calculate_min_and_max_distances(circle)[1] == pytest.approx(0.46)
    with pytest.raises(FootprintError, match='at least three points'):
        parse_footprint([[0, 0], [1, 1]])
    with pytest.raises(FootprintError, match='footprint'):
        parse_footprint('[[0, 0], [1')
    with pytest.raises(FootprintError, match='numbers'):
        parse_footprint([[0, 'a'], [1, 1], [2, 2]])


def test_cost_translation_table():
    t = cost_translation_table()
    assert (t[0], t[253], t[254], t[255]) == (0, 99, 100, -1)
    assert t[1] == 1 and t[252] == 98


def load_diploma(name):
    with open(os.path.join(DIPLOMA, name)) as f:
        return yaml.safe_load(f)


def test_diploma_common_params_plugins_form():
    common = load_diploma('costmap_common_params.yaml')
    glob = dict(common)
    glob.update(load_diploma('global_costmap_params.yaml')['global_costmap'])
    specs, warning = layer_specs(glob, '/move_base/global_costmap')
    assert warning is None
    assert [(n, k) for n, k, _ in specs] == [('static', 'static'), ('inflation_g', 'inflation')]


def test_pre_hydro_form_and_observation_sources():
    common = load_diploma('costmap_common_params.yaml')
    common.pop('plugins')
    common['static_map'] = True
    specs, warning = layer_specs(common, '/move_base/global_costmap')
    assert 'pre-hydro' in warning
    assert [k for _, k, _ in specs] == ['static', 'obstacle', 'inflation']
    srcs = observation_sources(specs[1][2], '/move_base/global_costmap/obstacle_layer')
    s = srcs['laser_scan_sensor']
    assert (s['topic'], s['data_type'], s['sensor_frame']) == ('scan', 'LaserScan', 'laser')
    assert (s['marking'], s['clearing']) == (True, True)
    assert (s['obstacle_range'], s['raytrace_range']) == (2.5, 3.0)
    assert s['expected_update_rate'] == 0.0


def test_bad_costmap_params_name_the_parameter():
    with pytest.raises(CostmapParamError, match='costmap_2d::Nope layer x ./c/plugins'):
        layer_specs({'plugins': [{'name': 'x', 'type': 'costmap_2d::Nope'}]}, '/c')
    with pytest.raises(CostmapParamError, match='/c/src/data_type'):
        observation_sources({'observation_sources': 'src', 'src': {'data_type': 'Sonar'}}, '/c')
    with pytest.raises(CostmapParamError, match='/c/missing is not set'):
        observation_sources({'observation_sources': 'missing'}, '/c')


def test_convex_polygon_cells_cover_the_outline_as_the_original():
    from costmap_2d.costmap import Costmap2D
    cm = Costmap2D(40, 40, 0.05, 0.0, 0.0)
    cm.data[:] = 254
    # a footprint whose right edge x = 1.09 lies in column 21 (cell centre 1.075 is outside)
    poly = [(0.91, 0.87), (0.91, 1.13), (1.09, 1.13), (1.09, 0.87)]
    assert cm.set_convex_polygon_cost(poly, 0)
    assert cm.data[20, 21] == 0 and cm.data[17, 18] == 0 and cm.data[22, 21] == 0
    assert cm.data[20, 22] == 254 and cm.data[16, 20] == 254
