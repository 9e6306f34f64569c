"""Lab 2's variant (table 10.1): the points of the ISU's last digit; the ISU's namespaces."""
from grading.common import variant


def printed_points(isu):
    """The variant's row as the table prints it, repeated cells included."""
    return [tuple(float(c) for c in p) for p in variant('lab2', isu)['points']]


def points(isu):
    """The distinct points of the variant's row, in printed order: each must be visited."""
    out = []
    for q in printed_points(isu):
        if q not in out:
            out.append(q)
    return out


def namespaces(isu):
    return '/ns1_%s' % isu, '/ns2_%s' % isu
