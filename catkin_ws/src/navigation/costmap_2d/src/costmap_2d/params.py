"""Costmap parameter resolution (no ROS imports): the `plugins:` list form and the pre-Hydro
form (`static_map`, `map_type`, `observation_sources` at the costmap's top level), from a
plain dict of the costmap namespace's parameters."""

LAYER_TYPES = {
    'costmap_2d::StaticLayer': 'static',
    'costmap_2d::ObstacleLayer': 'obstacle',
    'costmap_2d::VoxelLayer': 'obstacle',     # 2D projection of the voxel layer
    'costmap_2d::InflationLayer': 'inflation',
}

COSTMAP_DEFAULTS = {
    'global_frame': 'map',
    'robot_base_frame': 'base_link',
    'transform_tolerance': 0.3,
    'update_frequency': 5.0,
    'publish_frequency': 0.0,
    'width': 10,
    'height': 10,
    'resolution': 0.05,
    'origin_x': 0.0,
    'origin_y': 0.0,
    'rolling_window': False,
    'track_unknown_space': False,
    'always_send_full_costmap': False,
    'robot_radius': 0.46,
    'footprint_padding': 0.01,
}

OBSERVATION_DEFAULTS = {
    'sensor_frame': '',
    'observation_persistence': 0.0,
    'expected_update_rate': 0.0,
    'data_type': 'PointCloud',
    'min_obstacle_height': 0.0,
    'max_obstacle_height': 2.0,
    'inf_is_valid': False,
    'clearing': False,
    'marking': True,
}


class CostmapParamError(ValueError):
    pass


def layer_specs(params, ns):
    """[(layer name, kind, layer params dict)] and a pre-Hydro warning text or None.

    params: the costmap namespace as a dict (rosparam get of `ns`)."""
    plugins = params.get('plugins')
    if plugins is not None:
        if not isinstance(plugins, list):
            raise CostmapParamError('%s/plugins must be a list of {name: ..., type: ...} '
                                    'entries, got %r' % (ns, plugins))
        specs = []
        for i, p in enumerate(plugins):
            if not isinstance(p, dict) or 'name' not in p or 'type' not in p:
                raise CostmapParamError('%s/plugins[%d] must have a name and a type, got %r'
                                        % (ns, i, p))
            kind = LAYER_TYPES.get(p['type'])
            if kind is None:
                raise CostmapParamError(
                    'Failed to create the %s layer %s (%s/plugins[%d]): unknown type; declared '
                    'types are %s' % (p['type'], p['name'], ns, i, ' '.join(sorted(LAYER_TYPES))))
            sub = params.get(p['name'], {})
            specs.append((p['name'], kind, sub if isinstance(sub, dict) else {}))
        return specs, None
    # pre-Hydro: translate the flat parameter set (costmap_2d_ros.cpp loadOldParameters)
    specs = []
    if params.get('static_map', True):
        specs.append(('static_layer', 'static', dict(params)))
    map_type = params.get('map_type', 'costmap')
    specs.append(('obstacle_layer', 'obstacle', dict(params)))
    specs.append(('inflation_layer', 'inflation', dict(params)))
    warning = ('Loading from pre-hydro parameter style (%s, map_type %s); layers: %s'
               % (ns, map_type, ', '.join(s[0] for s in specs)))
    return specs, warning


def observation_sources(layer_params, ns):
    """{source name: its params with defaults} of an obstacle layer."""
    names = str(layer_params.get('observation_sources', '')).split()
    out = {}
    for name in names:
        src = layer_params.get(name)
        if src is None:
            raise CostmapParamError(
                '%s: observation source %s is listed in observation_sources but %s/%s is not '
                'set' % (ns, name, ns, name))
        if not isinstance(src, dict):
            raise CostmapParamError('%s/%s must be a dictionary, got %r' % (ns, name, src))
        p = dict(OBSERVATION_DEFAULTS)
        p['topic'] = name
        p['obstacle_range'] = layer_params.get('obstacle_range', 2.5)
        p['raytrace_range'] = layer_params.get('raytrace_range', 3.0)
        p.update(src)
        if p['data_type'] not in ('PointCloud', 'PointCloud2', 'LaserScan'):
            raise CostmapParamError(
                'Only topics that use point clouds or laser scans are currently supported '
                '(%s/%s/data_type is %r)' % (ns, name, p['data_type']))
        out[name] = p
    return out
