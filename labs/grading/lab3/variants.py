"""Lab 3's variant (table 11.1): links, manipulator joints, wheels and body of the ISU's last digit."""
from grading.common import variant


def spec(isu):
    v = variant('lab3', isu)
    return {'links': int(v['links']), 'arm': str(v['arm']), 'wheels': str(v['wheels']),
            'body': [float(x) for x in v['body']]}
