"""Automatic grading of the course labs (labs/grade): overlay build, rostest run, report.

Pure logic (variants, criteria, path and name checks, report, JUnit) imports no rospy and is
unit-tested without a master; `observe` holds the rospy side used by the rostest checkers.
RULES.md: what every grader does so that a correct solution never fails on a slow machine.
"""
