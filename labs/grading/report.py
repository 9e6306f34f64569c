"""Console report and JUnit XML of a grading run."""
import re
import xml.etree.ElementTree as ET

OK = '\u2714'
FAIL = '\u2718'


def format_report(lab, isu, criteria, note=None):
    lines = ['%s, ISU %s (variant %s):' % (lab, isu, isu[-1])]
    if note:
        lines.append('(%s)' % note)
    for c in criteria:
        mark = OK if c.passed else FAIL
        lines.append('%s %s. %s / %s' % (mark, c.id, c.title_ru, c.title_en))
        r = c.reason
        if r.get('ru') or r.get('en'):
            if r.get('ru') == r.get('en'):
                lines.append('    %s' % r['en'])
            else:
                lines.append('    %s' % r.get('ru', ''))
                lines.append('    %s' % r.get('en', ''))
    n = sum(1 for c in criteria if c.passed)
    lines.append('%d/%d criteria passed: %s' % (n, len(criteria), 'PASS' if n == len(criteria) else 'FAIL'))
    return '\n'.join(lines)


def xml_text(text):
    """Text XML 1.0 can carry: no terminal colour codes or control characters."""
    text = re.sub(r'\x1b\[[0-9;]*[A-Za-z]|\x1b\][^\x07]*\x07', '', text or '')
    return ''.join(ch for ch in text if ch >= ' ' or ch in '\t\n')


def write_junit(path, lab, isu, criteria, elapsed=0.0, note=None, variants=None):
    """`note`: a self-check run (no sandbox); `variants`: the variant table file, when it is
    not the textbook's."""
    failures = sum(1 for c in criteria if not c.passed)
    suite = ET.Element('testsuite', name='%s-%s%s' % (lab, isu, '-self-check' if note else ''),
                       tests=str(len(criteria)), failures=str(failures), errors='0', time='%.1f' % elapsed)
    if note or variants:
        props = ET.SubElement(suite, 'properties')
        if note:
            ET.SubElement(props, 'property', name='self-check', value=note)
        if variants:
            ET.SubElement(props, 'property', name='variants', value=variants)
    for c in criteria:
        case = ET.SubElement(suite, 'testcase', classname='%s.variant%s' % (lab, isu[-1]),
                             name='%s_%s' % (c.id, re.sub(r'[^a-z0-9]+', '_', c.title_en.lower()).strip('_')[:60]))
        text = xml_text('%s / %s' % (c.reason.get('en', ''), c.reason.get('ru', '')))
        if not c.passed:
            f = ET.SubElement(case, 'failure', message=xml_text(c.reason.get('en', '')))
            f.text = text
        else:
            ET.SubElement(case, 'system-out').text = text
    root = ET.Element('testsuites', tests=str(len(criteria)), failures=str(failures))
    root.append(suite)
    ET.ElementTree(root).write(path, encoding='utf-8', xml_declaration=True)
