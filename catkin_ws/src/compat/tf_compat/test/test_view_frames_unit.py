"""tf_compat.view_frames without ROS: dot's version check and the files it writes."""
import types

import pytest

from tf_compat.view_frames import dot_version, generate


@pytest.mark.parametrize('text, version', [
    ('dot - graphviz version 2.43.0 (0)\n', (2, 43)),
    (b'dot - graphviz version 2.42.2 (20200307.0000)\n', (2, 42)),
    ('dot - graphviz version 12.2.1 (0)\n', (12, 2)),
    ('dot - Graphviz version 2 (x)', (2, 0)),
    ('something else', None),
    ('', None),
])
def test_dot_version(text, version):
    assert dot_version(text) == version


class FakeDot:
    def __init__(self, version_text, fail=False, missing=False):
        self.version_text, self.fail, self.missing, self.calls = version_text, fail, missing, []

    def __call__(self, cmd, **kwargs):
        self.calls.append(cmd)
        if self.missing:
            raise FileNotFoundError(cmd[0])
        if cmd[1] == '-V':
            return types.SimpleNamespace(returncode=0, stderr=self.version_text.encode())
        return types.SimpleNamespace(returncode=1 if self.fail else 0)


def test_generate_writes_gv_and_asks_for_pdf(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    dot, lines = FakeDot('dot - graphviz version 2.43.0 (0)\n'), []
    assert generate('digraph G { "a" -> "b" }', run=dot, out=lines.append) == 0
    assert (tmp_path / 'frames.gv').read_text() == 'digraph G { "a" -> "b" }'
    assert dot.calls[-1] == ['dot', '-Tpdf', 'frames.gv', '-o', 'frames.pdf']
    assert lines == ['dot - graphviz version 2.43.0 (0)', 'Detected dot version 2.43',
                     'frames.pdf generated']


def test_old_dot_writes_postscript(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    dot = FakeDot('dot version 2.8 (Tue Jan  1 2008)')
    assert generate('digraph G {}', run=dot, out=lambda *_: None) == 0
    assert dot.calls[-1] == ['dot', '-Tps2', 'frames.gv', '-o', 'frames.ps']


def test_unknown_version_assumes_2_16(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    dot, lines = FakeDot('weird'), []
    assert generate('digraph G {}', run=dot, out=lines.append) == 0
    assert 'Warning: failed to determine your version of dot.  Assuming v2.16' in lines
    assert dot.calls[-1][1] == '-Tpdf'


def test_missing_dot_is_one_clear_line(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    lines = []
    assert generate('digraph G {}', run=FakeDot('', missing=True), out=lines.append) == 255
    assert lines == ['Warning: Could not execute `dot -V`.  Is graphviz installed?']


def test_failing_dot(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    errs = []
    assert generate('digraph G {', run=FakeDot('dot - graphviz version 2.43.0', fail=True),
                    out=lambda *_: None, err=errs.append) == 1
    assert errs == ['failed to generate frames.pdf']


def test_real_dot_renders_a_pdf(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    assert generate('digraph G { "base_link" -> "laser" }', out=lambda *_: None) == 0
    assert (tmp_path / 'frames.pdf').read_bytes()[:5] == b'%PDF-'
