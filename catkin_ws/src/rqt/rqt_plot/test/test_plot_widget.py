"""PlotWidget without a master: curves fed through ROSData buffers, offscreen Qt."""
import math
import os

if not os.environ.get('DISPLAY'):
    os.environ.setdefault('QT_QPA_PLATFORM', 'offscreen')

import pytest                                   # noqa: E402

from rqt_plot.plot_widget import PlotWidget     # noqa: E402


@pytest.fixture
def app(qapp):
    """pytest-qt's application, which lives as long as the test process. One made by this
    module would be destroyed at its end while pyqtgraph still holds widgets of it, and the
    next in-process Qt test of the same pytest worker would make a second one."""
    return qapp


def feed(widget, spec, ts, fn):
    data = widget.curves[spec].data
    with data.lock:
        data.buff_x.extend(ts)
        data.buff_y.extend(fn(t) for t in ts)


def test_autoscroll_autoscale_and_waiting(app):
    topics = {}
    lines = []
    w = PlotWidget(lambda: dict(topics), 0.0, window=5.0, subscribe=False,
                   report=lambda line, error: lines.append((line, error)))
    w.add_specs(['/pt/x', '/pt/y'])
    assert w.pending == ['/pt/x', '/pt/y'] and not w.curves
    assert lines[-1] == ('waiting for topic(s) of /pt/x, /pt/y to be published', False)
    topics['/pt'] = 'geometry_msgs/Point'
    w.resolve_pending()
    assert list(w.curves) == ['/pt/x', '/pt/y'] and not w.pending
    assert ('plotting /pt/x (geometry_msgs/Point on /pt)', False) in lines

    ts = [i / 30.0 for i in range(30 * 20)]          # 20 s of data at 30 Hz
    feed(w, '/pt/x', ts, lambda t: 3.0 * math.sin(t))
    feed(w, '/pt/y', ts, lambda t: 3.0 * math.cos(t))
    w.update_plot()
    app.processEvents()
    (x0, x1), (y0, y1) = w.plot.getViewBox().viewRange()
    assert (x0, x1) == pytest.approx((ts[-1] - 5.0, ts[-1]))          # scrolled to the last 5 s
    assert -3.5 < y0 < -2.0 and 2.0 < y1 < 3.5                        # y fits the data

    w.pause.setChecked(True)                       # paused: new data is dropped, view stays
    feed(w, '/pt/x', [30.0], lambda t: 100.0)
    w.update_plot()
    assert w.plot.getViewBox().viewRange()[0] == pytest.approx((ts[-1] - 5.0, ts[-1]))
    w.shutdown()


def test_bad_field_added_later_is_reported(app):
    lines = []
    w = PlotWidget(lambda: {'/pt': 'geometry_msgs/Point'}, 0.0, subscribe=False,
                   report=lambda line, error: lines.append((line, error)))
    w.add_specs(['/pt/q'])
    assert lines[0] == ("/pt/q: geometry_msgs/Point has no field 'q' (its fields: x, y, z)", True)
    assert w.nothing_plottable()
    w.add_specs(['/pt'])                            # a message: all its numeric fields
    assert list(w.curves) == ['/pt/x', '/pt/y', '/pt/z']
    assert not w.nothing_plottable()
    w.shutdown()
