"""rqt_reconfigure editor logic without a master (descriptions of dynamic_reconfigure's TestConfig)."""
import pytest
from dynamic_reconfigure.cfg import TestConfig

from rqt_reconfigure.param_model import (ParamValueError, bound_text, editor_kind, enum_items,
                                         filter_servers, flatten_groups, parse_value, slider_enabled,
                                         slider_to_value, value_to_slider)

PARAMS = {p['name']: p for _, p in flatten_groups(TestConfig.config_description)}


def test_kinds_and_groups():
    assert editor_kind(PARAMS['int_enum_']) == 'enum' and editor_kind(PARAMS['bool_']) == 'bool'
    assert editor_kind(PARAMS['str_']) == 'str' and editor_kind(PARAMS['int_']) == 'int'
    assert editor_kind(PARAMS['double_']) == 'double'
    paths = dict((p['name'], g) for g, p in flatten_groups(TestConfig.config_description))
    assert paths['deep_var_int'] == ('Default', 'Group_One', 'GROUP2', 'Group3')


def test_enum():
    assert [n for n, _, _ in enum_items(PARAMS['int_enum_'])] == ['Small', 'Medium', 'Large', 'ExtraLarge']
    assert enum_items(PARAMS['int_enum_'])[2][1] == 2


def test_parse_and_bounds():
    assert parse_value(PARAMS['int_'], '7') == 7
    assert parse_value(PARAMS['double_'], '2.5') == 2.5
    assert parse_value(PARAMS['bool_'], 'true') is True
    with pytest.raises(ParamValueError, match='value "x" of "int_" is not an int'):
        parse_value(PARAMS['int_'], 'x')
    with pytest.raises(ParamValueError, match=r'value 11 of "int_" is out of range \[-10, 10\]'):
        parse_value(PARAMS['int_'], '11')
    assert parse_value(PARAMS['double_no_minmax'], '1e9') == 1e9


def test_infinite_bounds_disable_the_slider():
    assert bound_text(PARAMS['double_no_max']['max']) == 'inf'
    assert bound_text(PARAMS['double_no_minmax']['min']) == '-inf'
    assert not slider_enabled(PARAMS['double_no_max']) and slider_enabled(PARAMS['double_'])


def test_slider_mapping():
    p = PARAMS['int_']
    assert slider_to_value(p, 0) == -10 and slider_to_value(p, 1000) == 10 and slider_to_value(p, 500) == 0
    assert value_to_slider(PARAMS['double_'], 4.0) == 500


def test_filter():
    assert filter_servers(['/a/cam', '/b/base'], 'CAM') == ['/a/cam']
    assert filter_servers(['/a/cam', '/b/base'], '') == ['/a/cam', '/b/base']
