"""Lab 2's variant (table 10.1): the points of the ISU's last digit; the ISU's namespaces."""
from grading.common import VariantTable, numbers

FIELDS = ('points',)
TURTLE_WORLD = 11.088889   # m, the side of turtlesim's field


def check_row(row):
    """None if a row of lab2's table is well-formed, else what is wrong (a few words)."""
    pts = row['points']
    if not isinstance(pts, list) or not pts or not all(numbers(p, 2) for p in pts):
        return 'points %r is not a list of [x, y] pairs' % (pts,)
    out = [p for p in pts if not all(0 < c < TURTLE_WORLD for c in p)]
    if out:
        return 'point %r lies outside turtlesim\'s field (0..%.2f m)' % (out[0], TURTLE_WORLD)
    return None


TABLE = VariantTable('lab2', FIELDS, check_row)


def printed_points(isu):
    """The variant's row as the table prints it, repeated cells included."""
    return [tuple(float(c) for c in p) for p in TABLE.row(isu)['points']]


def points(isu):
    """The distinct points of the variant's row, in printed order: each must be visited."""
    out = []
    for q in printed_points(isu):
        if q not in out:
            out.append(q)
    return out


def namespaces(isu):
    return '/ns1_%s' % isu, '/ns2_%s' % isu
