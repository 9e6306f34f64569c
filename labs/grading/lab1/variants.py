"""Lab 1's variant (table 9.1): the computing node and the operation of the ISU's last digit."""
from grading.common import load_table, variant_digit

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


def load(path=None):
    """{digit: row} of lab1's variant table (grading.common.load_table)."""
    return load_table('lab1', FIELDS, check_row, path)


def row_of(isu):
    """The table's row of the ISU's variant (its last digit)."""
    return load()[variant_digit(isu)]



def operations(isu):
    """The operations that pass for the ISU's variant, the printed one first: a row whose scan
    can be read two ways lists both (digit 5: printed "+", read "*" by the rows around it)."""
    op = row_of(isu)['operation']
    return tuple(op) if isinstance(op, list) else (op,)


def roles(isu):
    """(computing node, (first sender, second sender), printed operation) for the ISU's variant."""
    v = row_of(isu)
    comp = v['compute']
    senders = tuple(n for n in NODES if n != comp)
    return comp, senders, operations(isu)[0]
