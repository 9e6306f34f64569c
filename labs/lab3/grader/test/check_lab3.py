#!/usr/bin/python3
"""rostest checker of lab 3: expand and check the model, observe lab3_setup.launch, report."""
from grading import lab3
from grading.checker import run_checker
from grading.lab3 import observer, rules

if __name__ == '__main__':
    run_checker(lab3, rules, observer.observe)
