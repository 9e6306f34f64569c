"""Lab 3's variant (table 11.1): links, manipulator joints, wheels and body of the ISU's last digit."""
from grading.common import VariantTable, check_body

FIELDS = ('links', 'arm', 'wheels', 'body')


def check_row(row):
    """None if a row of lab3's table is well-formed, else what is wrong (a few words)."""
    if not isinstance(row['links'], int) or isinstance(row['links'], bool) or row['links'] < 1:
        return 'links %r is not a positive whole number' % (row['links'],)
    if not isinstance(row['arm'], str) or not row['arm'] or set(row['arm']) - set('RPC'):
        return 'arm %r is not a string of R, P, C' % (row['arm'],)
    if not isinstance(row['wheels'], str) or not row['wheels'] or set(row['wheels']) - set('CS'):
        return 'wheels %r is not a string of C, S' % (row['wheels'],)
    return check_body(row)


TABLE = VariantTable('lab3', FIELDS, check_row)


def spec(isu):
    v = TABLE.row(isu)
    return {'links': int(v['links']), 'arm': str(v['arm']), 'wheels': str(v['wheels']),
            'body': [float(x) for x in v['body']]}
