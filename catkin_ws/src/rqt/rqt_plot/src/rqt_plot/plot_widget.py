"""The Qt side of rqt_plot: a pyqtgraph plot of ROSData curves against time, with a legend,
an auto-scrolling time window, y autoscaling, a field entry and a status line."""

import numpy as np
import pyqtgraph as pg
from PyQt5 import QtCore, QtWidgets

from rqt_plot.rosplot import PlotFieldError, ROSData, resolve_spec

COLORS = ['#1f77b4', '#d62728', '#2ca02c', '#ff7f0e', '#9467bd', '#8c564b', '#e377c2', '#17becf']


class Curve:
    def __init__(self, data, item, keep):
        self.data = data
        self.item = item
        self.keep = keep          # seconds of history kept
        self.x = np.empty(0)
        self.y = np.empty(0)

    def update(self):
        xs, ys = self.data.next()          # may raise the callback's error
        if not xs:
            return False
        self.x = np.concatenate([self.x, xs])
        self.y = np.concatenate([self.y, ys])
        cut = np.searchsorted(self.x, self.x[-1] - self.keep)
        if cut:
            self.x, self.y = self.x[cut:], self.y[cut:]
        self.item.setData(self.x, self.y)
        return True


class PlotWidget(QtWidgets.QWidget):
    """Plots specs; the ones whose topic is not published yet are retried every 0.5 s.

    topics_fn() -> {topic: type}; report(line, error) gets every status line (printed by the app).
    """

    def __init__(self, topics_fn, start_time, window=10.0, report=lambda line, error: None,
                 paused=False,
                 subscribe=True, parent=None):
        super().__init__(parent)
        self.topics_fn = topics_fn
        self.start_time = start_time
        self.window = window
        self.report = report
        self.subscribe = subscribe
        self.curves = {}          # spec -> Curve
        self.pending = []         # specs waiting for their topic
        self.failed = []          # specs that cannot be plotted
        self.requested = 0
        self._status = ''

        # segmented line drawing fails with Debian's PyQt5 5.15 (QPainter.drawLines overload), so
        # curves are drawn as one path
        pg.setConfigOptions(antialias=False, background='w', foreground='k', segmentedLineMode='off')
        self.plot = pg.PlotWidget()
        self.plot.showGrid(x=True, y=True, alpha=0.3)
        self.plot.setLabel('bottom', 'time', units='s')
        legend = self.plot.addLegend(offset=(10, 10), brush=pg.mkBrush(255, 255, 255, 220), pen='k')
        legend.setZValue(1000)       # above the curves
        self.plot.getPlotItem().setAutoVisible(y=True)
        self.plot.enableAutoRange(axis='y')

        self.entry = QtWidgets.QLineEdit()
        self.entry.setPlaceholderText('topic field, e.g. /turtle1/pose/x')
        self.entry.returnPressed.connect(self._add_from_entry)
        add = QtWidgets.QPushButton('Add')
        add.clicked.connect(self._add_from_entry)
        self.pause = QtWidgets.QPushButton('Pause')
        self.pause.setCheckable(True)
        self.pause.setChecked(paused)
        self.autoscroll = QtWidgets.QCheckBox('autoscroll')
        self.autoscroll.setChecked(True)
        clear = QtWidgets.QPushButton('Clear')
        clear.clicked.connect(self.clear)
        bar = QtWidgets.QHBoxLayout()
        bar.addWidget(QtWidgets.QLabel('Topic'))
        bar.addWidget(self.entry, 1)
        for w in (add, self.pause, self.autoscroll, clear):
            bar.addWidget(w)
        self.status = QtWidgets.QLabel()
        self.status.setWordWrap(True)
        layout = QtWidgets.QVBoxLayout(self)
        layout.addLayout(bar)
        layout.addWidget(self.plot, 1)
        layout.addWidget(self.status)

        self._redraw = QtCore.QTimer(self)
        self._redraw.timeout.connect(self.update_plot)
        self._redraw.start(40)
        self._retry = QtCore.QTimer(self)
        self._retry.timeout.connect(self.resolve_pending)
        self._retry.start(500)

    # ---- fields ---------------------------------------------------------------------------
    def add_specs(self, specs):
        for spec in specs:
            if spec not in self.curves and spec not in self.pending:
                self.requested += 1
                self.pending.append(spec)
        self.resolve_pending()

    def _add_from_entry(self):
        from rqt_plot.rosplot import expand_specs, parse_field_path
        text = self.entry.text().strip()
        if not text:
            return
        try:
            import rosgraph.names
            specs = [rosgraph.names.script_resolve_name('rqt_plot', s) for s in expand_specs([text])]
            for spec in specs:
                parse_field_path(spec)
        except PlotFieldError as e:
            self._error(str(e))
            return
        self.entry.clear()
        self.add_specs(specs)

    def resolve_pending(self):
        if not self.pending:
            return
        try:
            topics = self.topics_fn()
        except Exception as e:
            self._set_status('cannot get the topic list from the master: %s' % e)
            return
        still = []
        for spec in self.pending:
            try:
                found = resolve_spec(spec, topics)
            except PlotFieldError as e:
                self.failed.append(spec)
                self._error(str(e))
                continue
            if found is None:
                still.append(spec)
                continue
            for sub_spec, topic, msg_class, path in found:
                if sub_spec not in self.curves:
                    self._add_curve(sub_spec, topic, msg_class, path)
        self.pending = still
        self._show_state()

    def _add_curve(self, spec, topic, msg_class, path):
        color = COLORS[len(self.curves) % len(COLORS)]
        item = self.plot.plot([], [], name=spec, pen=pg.mkPen(color, width=2))
        data = ROSData(spec, topic, msg_class, path, self.start_time, subscribe=self.subscribe)
        self.curves[spec] = Curve(data, item, keep=max(60.0, 5 * self.window))
        self.report('plotting %s (%s on %s)' % (spec, msg_class._type, topic), False)

    def clear(self):
        for c in self.curves.values():
            c.x, c.y = np.empty(0), np.empty(0)
            c.item.setData([], [])

    # ---- drawing --------------------------------------------------------------------------
    def update_plot(self):
        if self.pause.isChecked():
            for c in self.curves.values():   # keep draining, so a resume starts from now
                try:
                    c.data.next()
                except PlotFieldError:
                    pass
            return
        latest = None
        for c in self.curves.values():
            try:
                c.update()
            except PlotFieldError as e:
                self._error(str(e), once=True)
            if len(c.x):
                latest = c.x[-1] if latest is None else max(latest, c.x[-1])
        if latest is not None and self.autoscroll.isChecked():
            self.plot.setXRange(max(0.0, latest - self.window) if latest > self.window else 0.0,
                                max(latest, self.window), padding=0)

    # ---- status ---------------------------------------------------------------------------
    def _show_state(self):
        parts = []
        if self.curves:
            parts.append('plotting %s' % ', '.join(self.curves))
        if self.pending:
            parts.append('waiting for topic(s) of %s to be published' % ', '.join(self.pending))
        if not parts and not self.failed:
            parts.append('nothing to plot: type a field (e.g. /turtle1/pose/x) and press Add')
        if parts:
            self._set_status('; '.join(parts))

    def _set_status(self, text):
        if text != self._status:
            self._status = text
            self.status.setText(text)
            self.report(text, False)

    def _error(self, text, once=False):
        line = 'ERROR: ' + text
        if once and line == self._status:
            return
        self._status = line
        self.status.setText(line)
        self.report(text, True)

    def nothing_plottable(self):
        """True when every requested field was resolved and none of them can be plotted."""
        return self.requested > 0 and not self.curves and not self.pending

    def shutdown(self):
        self._redraw.stop()
        self._retry.stop()
        for c in self.curves.values():
            c.data.close()


class PlotWindow(QtWidgets.QMainWindow):
    def __init__(self, widget, title='rqt_plot'):
        super().__init__()
        self.setWindowTitle(title)
        self.setCentralWidget(widget)
        self.resize(900, 600)
