#!/usr/bin/python3
"""rostest checker of lab 2: observe the student's launch file, write a per-criterion report."""
from grading import lab2
from grading.checker import run_checker
from grading.observe import Lab2Observer


def observe(isu, pkg_dir, workdir):
    return Lab2Observer(isu, pkg_dir, workdir).run()


if __name__ == '__main__':
    run_checker(lab2, lab2, observe)
