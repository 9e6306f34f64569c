"""The ~topics_glob / ~services_glob / ~params_glob parameters of rosbridge_websocket and
rosapi: '[*]', "['/turtle1/*', '/rosout']" or a list."""


class GlobError(ValueError):
    pass


def parse_glob(value, name):
    """'[*]' / "['/turtle1/*', '/rosout']" / a list -> list of glob strings ([] = all)."""
    if value is None or value == '':
        return []
    if isinstance(value, (list, tuple)):
        items = value
    elif isinstance(value, str):
        text = value.strip()
        if text.startswith('[') and text.endswith(']'):
            text = text[1:-1]
        items = text.split(',')
    else:
        raise GlobError('~%s: expected a list of globs like "[/turtle1/*, /rosout]", got '
                        '%r' % (name, value))
    globs = [str(i).strip().strip('\'"').strip() for i in items]
    return [g for g in globs if g]
