"""qt_gui.recursive_plugin_provider without a display or a master: plugin providers discovered
as plugins, each one's plugins offered and loaded through it."""
import pytest

from qt_gui.plugin_provider import PluginLoadError, PluginProvider
from qt_gui.recursive_plugin_provider import RecursivePluginProvider


def descriptor(plugin_id):
    return {'plugin_id': plugin_id, 'full_name': plugin_id}


class Widget(object):
    def __init__(self, context):
        self.context = context


class Inner(PluginProvider):
    """A provider found as a plugin; built with the recursive provider's context."""
    built = []
    reload_import = False

    def __init__(self, context):
        super(Inner, self).__init__()
        self.context = context
        self.errors = ['Inner: one bad plugin.xml']
        self.unloaded = []
        Inner.built.append(self)

    def discover(self):
        return [descriptor('pkg/Widget')]

    def load_class(self, d):
        assert d['plugin_id'] == 'pkg/Widget'
        return Widget

    def unload(self, instance):
        self.unloaded.append(instance)


class Providers(PluginProvider):
    """Discovers two provider plugins: Inner and one whose class cannot be loaded."""

    def __init__(self):
        super(Providers, self).__init__()
        self.errors = ['Inner: one bad plugin.xml']   # the same manifests crawled twice

    def discover(self):
        return [descriptor('pkg/Inner'), descriptor('pkg/Broken')]

    def load_class(self, d):
        if d['plugin_id'] == 'pkg/Broken':
            raise PluginLoadError('could not import module "broken"')
        return Inner


def test_plugins_of_discovered_providers_load_through_them():
    Inner.built = []
    rp = RecursivePluginProvider(Providers(), context='rospack')
    rp.reload_import = True
    assert [d['plugin_id'] for d in rp.discover()] == ['pkg/Widget']
    inner, = Inner.built
    assert inner.context == 'rospack' and inner.reload_import is True
    assert rp.errors == ['Inner: one bad plugin.xml',
                         'RecursivePluginProvider: could not load plugin provider "pkg/Broken": '
                         'PluginLoadError: could not import module "broken"']
    cls = rp.load_class(descriptor('pkg/Widget'))
    widget = rp.instantiate(cls, 'plugin context')
    assert isinstance(widget, Widget) and widget.context == 'plugin context'
    rp.unload(widget)
    assert inner.unloaded == [widget]


def test_unknown_plugin_is_one_error():
    rp = RecursivePluginProvider(Providers())
    rp.discover()
    with pytest.raises(PluginLoadError, match='no plugin provider discovered "pkg/Other"'):
        rp.load_class(descriptor('pkg/Other'))
