"""Lab 1's variant (table 9.1): the computing node and the operation of the ISU's last digit."""
from grading.common import VariantTable

FIELDS = ('operation', 'compute')
OPERATIONS = ('+', '-', '*', '/')
NODES = ('node1', 'node2', 'node3')


def check_row(row):
    """None if a row of lab1's table is well-formed, else what is wrong (a few words)."""
    ops = row['operation'] if isinstance(row['operation'], list) else [row['operation']]
    if not ops or any(o not in OPERATIONS for o in ops) or len(set(ops)) != len(ops):
        return 'operation %r is not one of %s (or a list of them)' % (row['operation'], ' '.join(OPERATIONS))
    if row['compute'] not in ('node1', 'node2', 'node3'):
        return 'compute %r is not node1, node2 or node3' % (row['compute'],)
    return None


TABLE = VariantTable('lab1', FIELDS, check_row)


def operations(isu):
    """The operations that pass for the ISU's variant, the printed one first: a row whose scan
    can be read two ways lists both (digit 5: printed "+", read "*" by the rows around it)."""
    op = TABLE.row(isu)['operation']
    return tuple(op) if isinstance(op, list) else (op,)


def roles(isu):
    """(computing node, (first sender, second sender), printed operation) for the ISU's variant."""
    v = TABLE.row(isu)
    comp = v['compute']
    senders = tuple(n for n in NODES if n != comp)
    return comp, senders, operations(isu)[0]
