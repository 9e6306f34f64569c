"""Lab 2's package, launch file, grader, time limit and criteria texts (ru, en)."""
PACKAGE = 'my_best_controller'
GRADER_PKG = 'lab2_grader'
LAUNCH = 'lab2_setup.launch'
DEFAULT_TIMEOUT = 420.0

CRITERIA = [
    ('1', 'В ns1_<ISU> и ns2_<ISU> запущены turtlesim с turtle1',
     'ns1_<ISU> and ns2_<ISU> each run a turtlesim with turtle1'),
    ('2', 'Черепаха 1 проходит все точки варианта', 'Turtle 1 visits every point of the variant'),
    ('3', 'Время до последней точки опубликовано в result_<ISU>',
     'The time to the last point is published on result_<ISU>'),
    ('4', 'Черепаха 2 повторяет путь черепахи 1 (по её pose, без remap)',
     'Turtle 2 repeats turtle 1\'s path (from its pose, no remap)'),
    ('5', 'Нет глобальных имён: всё внутри ns1_<ISU>/ns2_<ISU>',
     'No global names: everything under ns1_<ISU>/ns2_<ISU>'),
    ('6', 'Работа завершена за 5 минут, без ударов о стены',
     'The run finishes within 5 minutes, without hitting walls'),
]
