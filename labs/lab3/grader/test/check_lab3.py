#!/usr/bin/python3
"""rostest checker of lab 3: expand and check the model, observe lab3_setup.launch, report."""
from grading import lab3
from grading.checker import run_checker
from grading.observe import Lab3Observer


def observe(isu, pkg_dir, workdir):
    return Lab3Observer(isu, pkg_dir, workdir).run()


if __name__ == '__main__':
    run_checker(lab3, lab3, observe)
