"""Lab 1's variant (table 9.1): the computing node and the operation of the ISU's last digit."""
from grading.common import variant

NODES = ('node1', 'node2', 'node3')


def operations(isu):
    """The operations that pass for the ISU's variant, the printed one first: a row whose scan
    can be read two ways lists both (digit 5: printed "+", read "*" by the rows around it)."""
    op = variant('lab1', isu)['operation']
    return tuple(op) if isinstance(op, list) else (op,)


def roles(isu):
    """(computing node, (first sender, second sender), printed operation) for the ISU's variant."""
    v = variant('lab1', isu)
    comp = v['compute']
    senders = tuple(n for n in NODES if n != comp)
    return comp, senders, operations(isu)[0]
