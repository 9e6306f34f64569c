"""Lab 1: three nodes, the variant's computing node, operation and result topic.

criteria.py  the lab's package, grader and criteria texts
variants.py  the variant's roles and operation (labs/lab1/variants.yaml)
rules.py     pure logic: an observation -> the four criteria (no rospy)
observer.py  the rospy side: start node1..3, watch the graph and the numbers
"""
from grading.lab1.criteria import CRITERIA, DEFAULT_TIMEOUT, GRADER_PKG, PACKAGE

__all__ = ['CRITERIA', 'DEFAULT_TIMEOUT', 'GRADER_PKG', 'PACKAGE']
