"""The labs the graders know, by name: each lab's package (grading.labN: PACKAGE, GRADER_PKG,
DEFAULT_TIMEOUT, CRITERIA) and its variant table (grading.labN.variants)."""
from grading import lab1, lab2, lab3, lab4
from grading.common import GradeError
from grading.lab1 import variants as lab1_variants
from grading.lab2 import variants as lab2_variants
from grading.lab3 import variants as lab3_variants
from grading.lab4 import variants as lab4_variants

LABS = {'lab1': lab1, 'lab2': lab2, 'lab3': lab3, 'lab4': lab4}
TABLES = {'lab1': lab1_variants.TABLE, 'lab2': lab2_variants.TABLE, 'lab3': lab3_variants.TABLE,
          'lab4': lab4_variants.TABLE}


def load_variants(lab, path=None):
    """{digit: row} of a lab's variant table: `path`, else $GRADING_VARIANTS, else the
    textbook's (labs/<lab>/variants.yaml). GradeError (one line) on a bad file."""
    if lab not in TABLES:
        raise GradeError('no variant table for %r' % lab)
    return TABLES[lab].load(path)
