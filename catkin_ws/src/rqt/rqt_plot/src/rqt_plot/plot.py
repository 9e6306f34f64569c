"""rqt_plot plugin `Plot`: the same PlotWidget as the standalone rqt_plot, docked in rqt_gui."""
import argparse
import sys

from rqt_gui_py.plugin import Plugin

from rqt_plot.rosplot import PlotFieldError, expand_specs, parse_field_path


class Plot(Plugin):

    def __init__(self, context):
        super(Plot, self).__init__(context)
        self.setObjectName('Plot')
        import rospy
        from rqt_plot.plot_widget import PlotWidget
        args = self._parse_args(context.argv())
        self._args = args
        self._widget = PlotWidget(lambda: dict(rospy.get_published_topics()), rospy.get_time(),
                                  report=self._report, paused=args.pause)
        self._widget.setObjectName('PlotWidgetUi')
        self._widget.setWindowTitle('Plot')
        if context.serial_number() > 1:
            self._widget.setWindowTitle(self._widget.windowTitle() + (' (%d)' % context.serial_number()))
        context.add_widget(self._widget)
        self._initial = self._specs(args.topics)

    @staticmethod
    def _parse_args(argv):
        parser = argparse.ArgumentParser(prog='rqt_plot', add_help=False)
        Plot.add_arguments(parser)
        return parser.parse_args(argv)

    @staticmethod
    def add_arguments(parser):
        group = parser.add_argument_group('Options for rqt_plot plugin')
        group.add_argument('-P', '--pause', action='store_true', help='Start in paused state')
        group.add_argument('-e', '--empty', action='store_true', help='Do not restore topics')
        group.add_argument('topics', nargs='*', default=[], help='Topics to plot')

    def _specs(self, topics):
        try:
            import rosgraph.names
            specs = [rosgraph.names.script_resolve_name('rqt_plot', s) for s in expand_specs(topics)]
            for spec in specs:
                parse_field_path(spec)
            return specs
        except PlotFieldError as e:
            self._report(str(e), True)
            return []

    def _report(self, line, error=False):
        print('rqt_plot: %s%s' % ('ERROR: ' if error else '', line),
              file=sys.stderr if error else sys.stdout, flush=True)

    def save_settings(self, plugin_settings, instance_settings):
        instance_settings.set_value('topics', repr(list(self._widget.curves) + list(self._widget.pending)))
        instance_settings.set_value('paused', self._widget.pause.isChecked())

    def restore_settings(self, plugin_settings, instance_settings):
        specs = list(self._initial)
        if not specs and not self._args.empty:
            saved = instance_settings.value('topics')
            if saved:
                try:
                    specs = [str(s) for s in eval(str(saved))]
                except Exception:
                    specs = []
        if instance_settings.value('paused') in [True, 'true']:
            self._widget.pause.setChecked(True)
        self._widget.add_specs(specs)

    def shutdown_plugin(self):
        self._widget.shutdown()
