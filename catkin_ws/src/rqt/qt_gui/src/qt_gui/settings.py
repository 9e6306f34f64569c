"""qt_gui.settings.Settings: a group of a QSettings store, as handed to plugins."""


class Settings(object):
    """Keys relative to `group` of one QSettings object (INI: bools/numbers come back as strings)."""

    def __init__(self, qsettings, group=''):
        self._qs = qsettings
        self._group = group.strip('/')

    def _full(self, key):
        return '%s/%s' % (self._group, key) if self._group else key

    def value(self, key, default=None):
        v = self._qs.value(self._full(key))
        return default if v is None else v

    def set_value(self, key, value):
        self._qs.setValue(self._full(key), value)

    def contains(self, key):
        return self._qs.contains(self._full(key))

    def remove(self, key):
        self._qs.remove(self._full(key))

    def _in_group(self, fn):
        if self._group:
            self._qs.beginGroup(self._group)
        try:
            return [str(k) for k in fn()]
        finally:
            if self._group:
                self._qs.endGroup()

    def all_keys(self):
        return self._in_group(self._qs.allKeys)

    def child_keys(self):
        return self._in_group(self._qs.childKeys)

    def child_groups(self):
        return self._in_group(self._qs.childGroups)

    def get_settings(self, group):
        return Settings(self._qs, self._full(group))

    def group(self):
        return self._group
