"""Lab 3's package, model and launch files, grader, time limit and criteria texts (ru, en)."""
PACKAGE = 'my_firts_robot_model'
GRADER_PKG = 'lab3_grader'
MODEL = 'urdf/my_robots_super_model.xacro'
LAUNCH = 'lab3_setup.launch'
DEFAULT_TIMEOUT = 360.0

CRITERIA = [
    ('1', 'urdf/my_robots_super_model.xacro раскрывается xacro и проходит check_urdf',
     'urdf/my_robots_super_model.xacro expands with xacro and passes check_urdf'),
    ('2', 'Число звеньев по варианту (все звенья URDF или без колёс)',
     'Number of links matches the variant (every URDF link, or wheels aside)'),
    ('3', 'Типы шарниров манипулятора по варианту', 'Manipulator joint types match the variant'),
    ('4', 'Колёсные шарниры (число и тип) по варианту', 'Wheel joints (number and type) match the variant'),
    ('5', 'Габариты корпуса по варианту (±5 мм)', 'Body size matches the variant (±5 mm)'),
    ('6', 'У каждого звена есть collision и inertial с массой > 0',
     'Every link has collision and inertial with mass > 0'),
    ('7', 'lab3_setup.launch: robot_description, robot_state_publisher, joint_state_publisher, '
          'RViz с RobotModel и TF; TF всех звеньев',
     'lab3_setup.launch: robot_description, robot_state_publisher, joint_state_publisher, '
     'RViz with RobotModel and TF; TF of every link'),
]
