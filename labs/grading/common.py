"""Criteria, bilingual reasons and variant tables shared by the CLI and the checkers."""
import json
import os

import yaml

LABS_DIR = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


class GradeError(Exception):
    """A bad command line or environment problem: one line, non-zero exit."""


def reason(ru, en):
    """A one-line reason in both course languages."""
    return {'ru': ru, 'en': en}


class Criterion:
    """One graded criterion: id, titles (ru/en), verdict and a one-line reason."""

    def __init__(self, cid, title_ru, title_en, passed=False, why=None, details=None):
        self.id = cid
        self.title_ru = title_ru
        self.title_en = title_en
        self.passed = passed
        self.reason = why or reason('', '')
        self.details = details or {}

    def set(self, passed, why, **details):
        self.passed = bool(passed)
        self.reason = why
        self.details.update(details)
        return self

    def to_dict(self):
        return {'id': self.id, 'title_ru': self.title_ru, 'title_en': self.title_en,
                'passed': self.passed, 'reason': self.reason, 'details': self.details}

    @classmethod
    def from_dict(cls, d):
        return cls(d['id'], d['title_ru'], d['title_en'], bool(d['passed']),
                   d.get('reason') or reason('', ''), d.get('details') or {})


def criteria_by_id(table):
    """{id: a fresh, not yet judged Criterion} of a lab's CRITERIA [(id, title ru, title en)]."""
    return {cid: Criterion(cid, ru, en) for cid, ru, en in table}


def write_report(path, criteria):
    tmp = path + '.tmp'
    with open(tmp, 'w') as f:
        json.dump([c.to_dict() for c in criteria], f, ensure_ascii=False, indent=1)
    os.replace(tmp, path)


def read_report(path):
    with open(path) as f:
        return [Criterion.from_dict(d) for d in json.load(f)]


def parse_isu(text):
    """The ISU id as a string of digits; GradeError otherwise."""
    s = str(text).strip()
    if not s.isdigit():
        raise GradeError('ISU id must be digits only, got %r' % text)
    return s


def variant_digit(isu):
    return int(parse_isu(isu)[-1])


VARIANTS_ENV = 'GRADING_VARIANTS'   # a variant table given by `labs/grade --variants FILE`


def default_variants_file(lab):
    """The lab's table as the textbook prints it: labs/<lab>/variants.yaml."""
    return os.path.join(LABS_DIR, lab, 'variants.yaml')


def is_number(v):
    return isinstance(v, (int, float)) and not isinstance(v, bool)


def numbers(v, n):
    """True when v is a list of n numbers."""
    return isinstance(v, list) and len(v) == n and all(is_number(x) for x in v)


def check_body(row):
    """None if the row's body is [L, W, H] in mm, else what is wrong (labs 3 and 4)."""
    if not numbers(row['body'], 3) or not all(x > 0 for x in row['body']):
        return 'body %r is not [L, W, H] in mm (3 positive numbers)' % (row['body'],)
    return None


def _check_fields(row, fields):
    """None if a variant row is a mapping of exactly `fields`, else what is wrong."""
    if not isinstance(row, dict):
        return 'is not a mapping of %s' % ', '.join(fields)
    unknown = sorted(str(k) for k in row if k not in fields)
    if unknown:
        return 'unknown field %r (fields: %s)' % (unknown[0], ', '.join(fields))
    missing = [f for f in fields if f not in row]
    if missing:
        return 'field %r missing' % missing[0]
    return None


def _read_yaml(path, where):
    try:
        with open(path) as f:
            return yaml.safe_load(f)
    except OSError as e:
        raise GradeError('%s: cannot read it (%s)' % (where, e.strerror or e))
    except yaml.YAMLError as e:
        mark = getattr(e, 'problem_mark', None)
        at = ' at line %d' % (mark.line + 1) if mark is not None else ''
        raise GradeError('%s: not YAML%s (%s)' % (where, at, getattr(e, 'problem', None) or str(e).splitlines()[0]))


def load_table(lab, fields, check_row, path=None):
    """{digit: row} of a lab's variant table: `path`, else the file named by $GRADING_VARIANTS
    (labs/grade --variants), else the textbook's table; every row a mapping of `fields` that
    `check_row(row)` (None or what is wrong) accepts. GradeError (one line) on a bad file."""
    path = path or os.environ.get(VARIANTS_ENV) or default_variants_file(lab)
    where = 'variants file %s' % path
    data = _read_yaml(path, where)
    if not isinstance(data, dict) or not isinstance(data.get('variants'), dict):
        raise GradeError('%s: no "variants:" mapping of digits 0-9 at the top level' % where)
    table = {}
    for k, row in data['variants'].items():
        if isinstance(k, bool) or not isinstance(k, int) or not 0 <= k <= 9:
            raise GradeError('%s: key %r is not a digit 0-9' % (where, k))
        why = _check_fields(row, fields) or check_row(row)
        if why:
            raise GradeError('%s: digit %d: %s' % (where, k, why))
        table[k] = row
    missing = [d for d in range(10) if d not in table]
    if missing:
        raise GradeError('%s: no row for digit%s %s (a %s table needs all ten)' % (
            where, 's' if len(missing) > 1 else '', ', '.join(map(str, missing)), lab))
    return table


class VariantTable:
    """A lab's variant table: its rows are mappings of `fields` that `check_row(row)` (None or
    what is wrong) accepts."""

    def __init__(self, lab, fields, check_row):
        self.lab, self.fields, self.check_row = lab, fields, check_row

    def load(self, path=None):
        """{digit: row}: `path`, else $GRADING_VARIANTS, else the textbook's (load_table)."""
        return load_table(self.lab, self.fields, self.check_row, path)

    def row(self, isu):
        """The row of the ISU's variant (its last digit)."""
        return self.load()[variant_digit(isu)]
