"""The CI templates parse as YAML and run labs/grade in the course image with a JUnit report."""
import os

import yaml

HERE = os.path.dirname(os.path.abspath(__file__))


def load(name):
    with open(os.path.join(HERE, name)) as f:
        return yaml.safe_load(f)


def test_gitlab_template():
    ci = load('.gitlab-ci.yml')
    assert ci['variables']['COURSE_IMAGE'] == 'ros-course:bookworm'
    job = ci['grade']
    assert job['image'] == '$COURSE_IMAGE'
    assert job['script'] == ['/course/labs/grade $LAB --isu $ISU --repo $CI_PROJECT_DIR --junit report.xml']
    assert job['artifacts']['reports']['junit'] == 'report.xml' and job['artifacts']['when'] == 'always'


def test_github_template():
    wf = load('github-workflow.yml')
    job = wf['jobs']['grade']
    assert 'ros-course:bookworm' in job['container']['image']
    runs = [s['run'] for s in job['steps'] if 'run' in s]
    assert runs == ['/course/labs/grade "$LAB" --isu "$ISU" --repo "$GITHUB_WORKSPACE" --junit report.xml']
    assert any(s.get('with', {}).get('path') == 'report.xml' for s in job['steps'])
    assert wf[True] == ['push', 'workflow_dispatch']      # YAML 1.1 reads the key `on` as True


def test_grade_entry_point_exists():
    grade = os.path.join(os.path.dirname(HERE), 'grade')
    assert os.access(grade, os.X_OK)
    with open(grade) as f:
        assert f.readline().strip() == '#!/usr/bin/python3'
