"""Automatic grading of the course labs (labs/grade): overlay build, rostest run, report.

One package per lab (grading.lab1 ... grading.lab4: criteria texts, variants, rules, observer)
over a shared core: common (criteria, variant tables), report, workspace (the overlay build),
sandbox, launch (the rospy side every observer uses: the student's processes, the master, a
launch), urdf and package (what labs 3 and 4 both read), checker (the rostest node), labs (the
registry by name), cli (labs/grade) and classgrade/slurm (labs/grade-class). Rules and the core
apart from launch and checker import no rospy and are unit-tested without a master.
RULES.md: what every grader does so that a correct solution never fails on a slow machine.
"""
