"""Lab 1's package, grader, time limit and criteria texts (ru, en)."""
PACKAGE = 'my_robot_controller'
GRADER_PKG = 'lab1_grader'
DEFAULT_TIMEOUT = 200.0

CRITERIA = [
    ('1', 'Ровно три узла node1, node2, node3', 'Exactly three nodes node1, node2, node3'),
    ('2', 'Вычисляющий узел варианта публикует result_<ISU> и слушает два других',
     'The variant\'s computing node publishes result_<ISU> and subscribes to the other two'),
    ('3', 'Результат равен операции варианта над двумя числами',
     'The result equals the variant\'s operation on the two numbers'),
    ('4', 'Результат публикуется регулярно', 'The result is published repeatedly'),
]
