#!/usr/bin/python3
"""Scripted `rqt_reconfigure /reconf_test`: sets int_ to 7 and bool_ through the editors, tries a
bad value, and prints the server's configuration as the plugin's client sees it."""
import sys
import time

from course_testing.rqt_driver import emit, run, running_instance

st = {}


def add_arguments(parser):
    group = parser.add_argument_group('Options for rqt_reconfigure plugin')
    group.add_argument('node_name', nargs='*', default=[])


def scenario(main, step):
    p = running_instance(main, 'rqt_reconfigure/Reconfigure')
    ed = p.node_editors.get('/reconf_test')
    if ed is None:
        return False
    if 'set' not in st:
        _, w = ed.editors['int_']
        w.setText('7')
        w.editingFinished.emit()
        ed.editors['bool_'][1].setChecked(True)
        _, d = ed.editors['double_']
        d.setText('99')                      # out of [-2, 10]
        d.editingFinished.emit()
        st['set'] = time.time()
        emit(kind='editors', names=sorted(ed.editors), status=p._widget.status.text(),
             servers=[p._widget.node_list.item(i).text() for i in range(p._widget.node_list.count())])
        return False
    if time.time() - st['set'] < 2.0:
        return False
    cfg = p._clients['/reconf_test'].get_configuration(timeout=5.0)
    emit(kind='config', int_=cfg['int_'], bool_=cfg['bool_'], double_=cfg['double_'])
    return True


sys.exit(run(['rqt_reconfigure', '/reconf_test'], scenario, standalone='rqt_reconfigure.param_plugin.ParamPlugin',
             plugin_argument_provider=add_arguments))
