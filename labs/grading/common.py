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


def load_variants(lab):
    path = os.path.join(LABS_DIR, lab, 'variants.yaml')
    with open(path) as f:
        data = yaml.safe_load(f)
    return {int(k): v for k, v in data['variants'].items()}


def variant(lab, isu):
    return load_variants(lab)[variant_digit(isu)]
