"""A provider of providers, as the original's RecursivePluginProvider: the descriptors its inner
provider discovers are plugin providers (e.g. base class `rqt_gui_py::PluginProvider`); each is
loaded and instantiated through the plugin framework and the plugins it discovers are offered."""
from qt_gui.plugin_provider import PluginLoadError, PluginProvider


class RecursivePluginProvider(PluginProvider):

    def __init__(self, plugin_provider, context=None):
        """plugin_provider: discovers the providers; context: what each provider is built with
        (PluginProvider.instantiate: no argument when its __init__ takes none)."""
        super(RecursivePluginProvider, self).__init__()
        self._plugin_provider = plugin_provider
        self._context = context
        self._providers = []
        self._owner = {}          # plugin id -> provider that discovered it
        self._class_owner = {}    # plugin class -> provider that loaded it
        self.reload_import = False

    def discover(self):
        self._providers, self._owner = [], {}
        errors = []
        descriptors = []
        for d in self._plugin_provider.discover():
            try:
                cls = self._plugin_provider.load_class(d)
                provider = self._plugin_provider.instantiate(cls, self._context)
            except Exception as e:
                errors.append('RecursivePluginProvider: could not load plugin provider "%s": %s: %s'
                              % (d['plugin_id'], type(e).__name__, e))
                continue
            if hasattr(provider, 'reload_import'):
                provider.reload_import = self.reload_import
            self._providers.append(provider)
            for plugin in provider.discover():
                self._owner.setdefault(plugin['plugin_id'], provider)
                descriptors.append(plugin)
            errors += provider.errors
        # the inner provider and the providers it found may crawl the same manifests: each line once
        self.errors = list(dict.fromkeys(self._plugin_provider.errors + errors))
        return descriptors

    def load_class(self, descriptor):
        provider = self._owner.get(descriptor['plugin_id'])
        if provider is None:
            raise PluginLoadError('no plugin provider discovered "%s"' % descriptor['plugin_id'])
        cls = provider.load_class(descriptor)
        self._class_owner[cls] = provider
        return cls

    def instantiate(self, cls, context):
        return self._class_owner[cls].instantiate(cls, context)

    def unload(self, instance):
        provider = self._class_owner.get(type(instance))
        if provider is not None:
            provider.unload(instance)
