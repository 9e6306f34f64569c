"""Perspective files: the JSON export of a settings group, as qt_gui writes them."""
import json
import re

from python_qt_binding import QtCore

_BINDING_PREFIX = re.compile(r'\b(PyQt5|PySide2)\.QtCore\b')


def _encode(value):
    if isinstance(value, QtCore.QByteArray):
        hexed = bytes(value.toHex())
        pretty = ''.join(chr(c) if 32 <= c < 127 else '.' for c in bytes(value))
        return {'type': 'repr(QByteArray.hex)',
                'repr(QByteArray.hex)': 'QtCore.QByteArray(%r)' % hexed,
                'pretty-print': pretty}
    text = _BINDING_PREFIX.sub('QtCore', repr(value))
    try:
        back = eval(text, {'QtCore': QtCore})
    except Exception:
        back = object()
    if back != value:
        raise ValueError('value %s does not round-trip through repr()' % text)
    return {'type': 'repr', 'repr': text}


def _decode(entry):
    kind = entry.get('type')
    if kind == 'repr':
        return eval(entry['repr'], {'QtCore': QtCore})
    if kind == 'repr(QByteArray.hex)':
        hexed = eval(entry['repr(QByteArray.hex)'], {'QtCore': QtCore})
        return QtCore.QByteArray.fromHex(hexed)
    raise ValueError('unknown serialization type "%s"' % kind)


def export_group(qsettings, group):
    """{"keys": {...}, "groups": {...}} of `group` (recursively)."""
    qsettings.beginGroup(group)
    try:
        return _export(qsettings)
    finally:
        qsettings.endGroup()


def _export(qs):
    data = {'keys': {}, 'groups': {}}
    for key in qs.childKeys():
        data['keys'][key] = _encode(qs.value(key))
    for sub in qs.childGroups():
        qs.beginGroup(sub)
        try:
            data['groups'][sub] = _export(qs)
        finally:
            qs.endGroup()
    return data


def import_group(qsettings, group, data):
    """Replace `group` with the content of an exported dictionary."""
    qsettings.remove(group)
    qsettings.beginGroup(group)
    try:
        _import(qsettings, data)
    finally:
        qsettings.endGroup()


def _import(qs, data):
    for key, entry in data.get('keys', {}).items():
        qs.setValue(key, _decode(entry))
    for sub, child in data.get('groups', {}).items():
        qs.beginGroup(sub)
        try:
            _import(qs, child)
        finally:
            qs.endGroup()


def write_file(path, data):
    with open(path, 'w') as f:
        json.dump(data, f, indent=2, sort_keys=True)
        f.write('\n')


def read_file(path):
    with open(path) as f:
        return json.load(f)
