"""Plugin providers: discover descriptors and turn one into a plugin object."""
import importlib
import inspect
import os
import sys


class PluginLoadError(Exception):
    pass


class PluginProvider(object):
    """Base: `discover()` -> descriptors; `load_class(descriptor)` -> class; `instantiate`."""

    def __init__(self):
        self.errors = []     # one line per problem met while discovering

    def discover(self):
        return []

    def load_class(self, descriptor):
        raise PluginLoadError('provider cannot load "%s"' % descriptor['plugin_id'])

    def instantiate(self, cls, context):
        init = getattr(cls, '__init__', None)
        try:
            params = [p for p in inspect.signature(init).parameters.values()
                      if p.kind in (p.POSITIONAL_ONLY, p.POSITIONAL_OR_KEYWORD)]
        except (TypeError, ValueError):
            params = [None, None]
        if len(params) <= 1:
            return cls()
        return cls(context)

    def unload(self, instance):
        pass


class PythonPluginProvider(PluginProvider):
    """Loads Python plugins: `library path` goes on sys.path, `type` is module.Class."""

    reload_import = False

    def load_class(self, descriptor):
        if not descriptor.get('module_name'):
            raise PluginLoadError('plugin "%s" has type "%s", which is not a Python class '
                                  '(module.Class)' % (descriptor['plugin_id'], descriptor['class_type']))
        lib = descriptor['library_path']
        if lib and os.path.isdir(lib) and lib not in sys.path:
            sys.path.insert(0, lib)
        try:
            module = importlib.import_module(descriptor['module_name'])
            if self.reload_import:
                module = importlib.reload(module)
        except Exception as e:
            raise PluginLoadError('could not import module "%s" of plugin "%s": %s: %s' % (
                descriptor['module_name'], descriptor['plugin_id'], type(e).__name__, e))
        cls = getattr(module, descriptor['class_attr'], None)
        if cls is None:
            raise PluginLoadError('could not find class "%s" in module "%s"' % (
                descriptor['class_attr'], descriptor['module_name']))
        return cls
