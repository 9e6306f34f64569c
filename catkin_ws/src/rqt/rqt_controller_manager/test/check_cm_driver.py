#!/usr/bin/python3
"""Scripted `rqt_controller_manager` against the dummy robot: selects /controller_manager, sees
the configured controllers as uninitialized, runs the context menu's 'Load and Start', 'Stop',
'Stop and Unload' on velocity_j2, and reports the table after each."""
import sys

from course_testing.rqt_driver import emit, run, running_instance

st = {'phase': 0}
STEPS = [('Load and Start', ['load', 'start'], 'running'), ('Stop', ['stop'], 'stopped'),
         ('Start again', ['start'], 'running'), ('Stop and Unload', ['stop', 'unload'], 'uninitialized')]


def table(p):
    model = p._widget.table_view.model()
    if model is None:
        return {}
    return {model.data(model.index(r, 0), 0): model.data(model.index(r, 1), 0) for r in range(model.rowCount())}


def scenario(main, step):
    from rqt_controller_manager.model import menu_for
    p = running_instance(main, 'rqt_controller_manager/ControllerManager')
    if p is None:
        return False
    rows = table(p)
    ph = st['phase']
    if ph == 0:
        if p._widget.cm_combo.currentText() != '/controller_manager' or 'velocity_j2' not in rows:
            return False
        emit(kind='listed', cm=p._widget.cm_combo.currentText(), rows=rows)
        st['phase'] = 1
        return False
    label, ops, expect = STEPS[ph - 1]
    if not st.get('sent'):
        state = rows.get('velocity_j2')
        menu = dict(menu_for(state))
        emit(kind='menu', state=state, labels=[l for l, _ in menu_for(state)])
        p.run_operations('velocity_j2', menu[label])  # what choosing the entry does
        st['sent'] = True
        return False
    if rows.get('velocity_j2') != expect:
        return False
    emit(kind='after', label=label, rows=rows)
    st['sent'] = False
    st['phase'] += 1
    return st['phase'] > len(STEPS)


sys.exit(run(['rqt_controller_manager'], scenario,
             standalone='rqt_controller_manager.controller_manager.ControllerManager'))
