"""Lab 2: two turtlesims in ns1_<ISU>/ns2_<ISU>, the variant's points, the time, the follower.

criteria.py  the lab's package, launch file, grader and criteria texts
variants.py  the variant's points and the ISU's namespaces (labs/lab2/variants.yaml)
package.py   static checks of the student's package (launch files, scripts)
rules.py     pure logic: path geometry, an observation -> the six criteria (no rospy)
observer.py  the rospy side: roslaunch the student's launch file, watch both turtles
"""
from grading.lab2.criteria import CRITERIA, DEFAULT_TIMEOUT, GRADER_PKG, LAUNCH, PACKAGE

__all__ = ['CRITERIA', 'DEFAULT_TIMEOUT', 'GRADER_PKG', 'LAUNCH', 'PACKAGE']
