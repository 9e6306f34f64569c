#!/usr/bin/python3
"""Scripted `rqt_gui` for test_rqt_gui.py.

build <flag> <perspective>: through the Plugins menu, load the tutorial plugin, the broken
  plugins, Message Publisher and Plot; the publisher publishes std_msgs/Float64 `i * 0.5` on
  /rqt_test/value at 10 Hz and Plot plots /rqt_test/value/data; state is printed, then (after the
  test's screenshot, flag file) the perspective is exported.
reload: started with --perspective-file; prints what came back.
"""
import sys

from course_testing.rqt_driver import emit, file_exists, run, running_instance, widget_rect

mode = sys.argv.pop(1)
flag = perspective = None
if mode == 'build':
    flag = sys.argv.pop(1)
    perspective = sys.argv.pop(1)
st = {'phase': 0, 'wait': 0}


def menu_tree(menu, prefix=()):
    out = []
    for a in menu.actions():
        if a.menu():
            out.extend(menu_tree(a.menu(), prefix + (a.text(),)))
        elif a.objectName().startswith('plugin_action__'):
            out.append(list(prefix + (a.text(), a.objectName()[len('plugin_action__'):])))
    return out


def trigger(main, plugin_id):
    from python_qt_binding.QtWidgets import QAction
    for a in main.main_window.findChildren(QAction):
        if a.objectName() == 'plugin_action__' + plugin_id:
            a.trigger()
            return True
    raise AssertionError('no Plugins menu entry for ' + plugin_id)


def docks(main):
    from qt_gui.dock_widget import DockWidget
    out = {}
    for d in main.main_window.findChildren(DockWidget):
        if d.isVisible():
            out[d.objectName()] = {'title': d.windowTitle(), 'rect': widget_rect(d),
                                   'area': int(main.main_window.dockWidgetArea(d)),
                                   'floating': d.isFloating()}
    return out


def publisher_rows(pub):
    from python_qt_binding.QtCore import Qt
    tree = pub._widget.publisher_tree_widget
    rows = []
    for k in range(tree.topLevelItemCount()):
        top = tree.topLevelItem(k)
        rows.append([top.text(0), top.text(1), top.text(2), top.checkState(0) == Qt.Checked,
                     [[top.child(j).text(0), top.child(j).text(3)] for j in range(top.childCount())]])
    return rows


def build(main, step):
    pm = main.plugin_manager
    if st['phase'] == 0:
        emit(kind='menu', menu=menu_tree(main.main_window.plugins_menu), errors=list(pm.errors))
        trigger(main, 'rqt_mypkg/My Plugin')
        trigger(main, 'rqt_mypkg/My Plugin')
        errors_before = len(pm.errors)
        trigger(main, 'rqt_broken/Raises')
        trigger(main, 'rqt_broken/Missing')
        emit(kind='broken', errors=pm.errors[errors_before:], window_visible=main.main_window.isVisible(),
             status=main.main_window.statusBar().currentMessage(),
             running=sorted('%s#%d' % k for k in pm.running),
             tutorial_saved=[running_instance(main, 'rqt_mypkg/My Plugin').saved], docks=docks(main))
        for (pid, serial), h in list(pm.running.items()):
            if pid == 'rqt_mypkg/My Plugin':
                pm.unload_plugin(h)
        trigger(main, 'rqt_publisher/Publisher')
        trigger(main, 'rqt_plot/Plot')
        pub = running_instance(main, 'rqt_publisher/Publisher')
        pid = pub.add_publisher('/rqt_test/value', 'std_msgs/Float64', 10.0, False)
        bad = pub.add_publisher('/rqt_test/bad', 'no_such_pkg/NoSuchType', 1.0, False)
        pub.set_expression(pid, '/data', 'i * 0.5')
        pub.set_enabled(pid, True)
        running_instance(main, 'rqt_plot/Plot')._widget.add_specs(['/rqt_test/value/data'])
        emit(kind='publishing', bad_type_id=bad, status=pub._widget.status.text(),
             rows=publisher_rows(pub))
        st['phase'] = 1
        return False
    if st['phase'] == 1:
        plot = running_instance(main, 'rqt_plot/Plot')._widget
        curve = plot.curves.get('/rqt_test/value/data')
        if curve is None or len(curve.x) < 20:
            return False
        emit(kind='plotted', points=len(curve.x), last=float(curve.y[-1]), docks=docks(main),
             plot_rect=widget_rect(plot.plot))
        st['phase'] = 2
        return False
    if st['phase'] == 2:
        if not file_exists(flag):
            return False
        pub = running_instance(main, 'rqt_publisher/Publisher')
        pub._widget.publisher_tree_widget.topLevelItem(0).setText(2, '2')   # rate edited -> '2.00'
        main.export_perspective(perspective)
        emit(kind='exported', rows=publisher_rows(pub))
        return True


def reload(main, step):
    if step < 5:
        return False
    pub = running_instance(main, 'rqt_publisher/Publisher')
    plot = running_instance(main, 'rqt_plot/Plot')
    emit(kind='reloaded', running=sorted('%s#%d' % k for k in main.plugin_manager.running),
         perspective=main.perspective, docks=docks(main),
         rows=publisher_rows(pub) if pub else None,
         plot_specs=sorted(list(plot._widget.curves) + list(plot._widget.pending)) if plot else None)
    return True


sys.exit(run(['rqt_gui'] + sys.argv[1:], build if mode == 'build' else reload))
