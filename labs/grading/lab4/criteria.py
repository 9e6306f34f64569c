"""Lab 4's package, launch file, grader, time limit and criteria texts (ru, en)."""
PACKAGE = 'my_robot_simulation_control'
GRADER_PKG = 'lab4_grader'
LAUNCH = 'lab4.launch'
DEFAULT_TIMEOUT = 480.0

CRITERIA = [
    ('1', 'Сцена: свет, земля, гравитация и не менее 3 разных непримитивных объектов',
     'Scene: light, ground, gravity and at least 3 different non-primitive objects'),
    ('2', 'Габариты корпуса по варианту (±5 мм)', 'Body size matches the variant (±5 mm)'),
    ('3', 'Дальность лидара (min/max) по варианту', 'Lidar range (min/max) matches the variant'),
    ('4', 'Разрешение камеры по варианту', 'Camera resolution matches the variant'),
    ('5', 'Контроллеры загружены через controller_manager и запущены, колёса — по скорости',
     'Controllers loaded through controller_manager and running, wheels by velocity'),
    ('6', 'Нет плагина diff-drive / skid-steer в описании робота',
     'No diff-drive / skid-steer plugin in the robot description'),
    ('7', 'Робот проезжает заметное расстояние за отведённое время',
     'The robot covers distance within the time limit'),
    ('8', 'Движение целенаправленное: без вращения на месте и колебаний',
     'Purposeful motion: no spinning in place, no oscillation'),
    ('9', 'Нет столкновений с объектами сцены', 'No collision with the scene'),
]
