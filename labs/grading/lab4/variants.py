"""Lab 4's variant (chapter 12's table): lidar range, camera resolution, body of the ISU's last digit."""
from grading.common import VariantTable, check_body, numbers

FIELDS = ('lidar', 'camera', 'body')


def check_row(row):
    """None if a row of lab4's table is well-formed, else what is wrong (a few words)."""
    if check_body(row):
        return check_body(row)
    if not numbers(row['lidar'], 2) or not 0 <= row['lidar'][0] < row['lidar'][1]:
        return 'lidar %r is not [range_min, range_max] in m with 0 <= min < max' % (row['lidar'],)
    cam = row['camera']
    if not (isinstance(cam, list) and len(cam) == 2 and all(isinstance(x, int) and not isinstance(x, bool)
                                                            and x > 0 for x in cam)):
        return 'camera %r is not [width, height] in pixels' % (cam,)
    return None


TABLE = VariantTable('lab4', FIELDS, check_row)


def spec(isu):
    v = TABLE.row(isu)
    return {'lidar': [float(x) for x in v['lidar']], 'camera': [int(x) for x in v['camera']],
            'body': [float(x) for x in v['body']]}
