"""qt_gui: the plugin framework behind rqt (re-implementation, see README.md)."""
