"""Dynamic Reconfigure editors' logic (no Qt, no ROS): editor kinds, enums, parsing and bounds."""
import ast
import math


class ParamValueError(Exception):
    pass


def editor_kind(param):
    """'enum', 'bool', 'str', 'int' or 'double' for a parameter description dict."""
    if param.get('edit_method'):
        return 'enum'
    return {'bool': 'bool', 'str': 'str', 'int': 'int', 'double': 'double'}.get(param.get('type'), 'str')


def enum_items(param):
    """[(name, value, description)] of an enum parameter's edit_method."""
    try:
        method = ast.literal_eval(param['edit_method'])
    except (ValueError, SyntaxError):
        raise ParamValueError('parameter "%s": edit_method is not a Python literal' % param.get('name'))
    return [(c['name'], c['value'], c.get('description', '')) for c in method.get('enum', [])]


def bound_text(value):
    if isinstance(value, float) and math.isinf(value):
        return 'inf' if value > 0 else '-inf'
    return str(value)


def slider_enabled(param):
    """Numeric sliders only with finite bounds."""
    return not any(isinstance(param.get(k), float) and math.isinf(param[k]) for k in ('min', 'max'))


def parse_value(param, text):
    """The value of a line-edit text for a parameter, checked against its bounds."""
    kind = param.get('type')
    name = param.get('name')
    if kind == 'str':
        return text
    if kind == 'bool':
        if text.strip().lower() in ('true', '1'):
            return True
        if text.strip().lower() in ('false', '0'):
            return False
        raise ParamValueError('value "%s" of "%s" is not a bool' % (text, name))
    try:
        value = int(text) if kind == 'int' else float(text)
    except ValueError:
        raise ParamValueError('value "%s" of "%s" is not %s' % (text, name, 'an int' if kind == 'int' else 'a double'))
    lo, hi = param.get('min'), param.get('max')
    if (lo is not None and value < lo) or (hi is not None and value > hi):
        raise ParamValueError('value %s of "%s" is out of range [%s, %s]'
                              % (text, name, bound_text(lo), bound_text(hi)))
    return value


def slider_to_value(param, position, steps=1000):
    lo, hi = param['min'], param['max']
    v = lo + (hi - lo) * position / float(steps)
    return int(round(v)) if param.get('type') == 'int' else v


def value_to_slider(param, value, steps=1000):
    lo, hi = param['min'], param['max']
    if hi == lo:
        return 0
    return int(round((value - lo) * steps / float(hi - lo)))


def flatten_groups(group, path=()):
    """[(group path, param dict)] of a config description's groups, depth first."""
    out = []
    here = path + (group.get('name', ''),)
    for p in group.get('parameters', []):
        out.append((here, p))
    groups = group.get('groups', [])
    if isinstance(groups, dict):          # the client's decoded descriptions: {name: group}
        groups = [dict(g, name=g.get('name', k)) for k, g in groups.items()]
    for g in groups:
        out.extend(flatten_groups(g, here))
    return out


def filter_servers(names, text):
    """Server names containing every whitespace-separated word of the filter (case-insensitive)."""
    words = text.lower().split()
    return [n for n in names if all(w in n.lower() for w in words)]
