"""Lab 3: a mobile base with a manipulator in urdf/my_robots_super_model.xacro, shown in RViz.

criteria.py  the lab's package, model and launch files, grader and criteria texts
variants.py  the variant's links, arm, wheels and body (labs/lab3/variants.yaml)
model.py     the URDF read as the lab asks: body, wheels, manipulator chain, links
rviz.py      RViz's config and command line
rules.py     pure logic: an observation -> the seven criteria (no rospy)
observer.py  the rospy side: xacro and check_urdf the model, roslaunch lab3_setup.launch

Definitions (also in labs/lab3/README.md):
  body      the link named `base_link`, else the root link of the tree;
  rigid body group  the body and every link joined to it through fixed joints only;
  wheel     a joint whose parent is in the rigid body group, whose child subtree has no movable
            joint, and whose child link has a cylinder collision on a movable joint (a wheel) or
            a sphere collision on any joint (a caster, code S);
  arm       every other movable joint (mimic joints aside), which must form one serial chain;
            read from the body outwards;
  links     the table's "Кол-во звеньев" passes in either reading: every <link> of the URDF
            (the book's count: a URDF is links joined by joints, wheels and base included) or
            every link except wheel/caster links and their subtrees (the only reading in which
            variants 1, 3, 5 and 6 can be built).
"""
from grading.lab3.criteria import CRITERIA, DEFAULT_TIMEOUT, GRADER_PKG, LAUNCH, MODEL, PACKAGE

__all__ = ['CRITERIA', 'DEFAULT_TIMEOUT', 'GRADER_PKG', 'LAUNCH', 'MODEL', 'PACKAGE']
