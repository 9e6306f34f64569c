"""The model library's rooms (scripts/make_models.py writes them): walls as axis-aligned centre
lines with doorway gaps, built into boxes WALL_T thick; the office's doorways and the maze's
layout are data the tests walk through."""
from model_objects import MAZE_WALL, WALL


WALL_T = 0.1


def wall_runs(x0, y0, x1, y1, gaps=()):
    """Axis-aligned wall centre line from (x0, y0) to (x1, y1) minus doorway gaps
    [(centre along the line, width)]: the list of remaining (x0, y0, x1, y1) pieces."""
    horizontal = y0 == y1
    a, b = (x0, x1) if horizontal else (y0, y1)
    a, b = min(a, b), max(a, b)
    pieces, start = [], a
    for c, w in sorted(gaps):
        pieces.append((start, c - w / 2))
        start = c + w / 2
    pieces.append((start, b))
    out = []
    for p, q in pieces:
        if q - p > 1e-9:
            out.append((p, y0, q, y0) if horizontal else (x0, p, x0, q))
    return out


class Room:
    def __init__(self, name, title, height, color, walls, doorways=()):
        self.name, self.title, self.height, self.color = name, title, height, color
        self.walls = walls          # centre lines (x0, y0, x1, y1)
        self.doorways = list(doorways)   # (name, (x, y), 'x'|'y' passage direction, width)

    def boxes(self):
        """(name, (sx, sy, sz), (cx, cy, cz)) for every wall, ends extended by half the
        thickness so that corners close."""
        out = []
        for i, (x0, y0, x1, y1) in enumerate(self.walls):
            length = abs(x1 - x0) + abs(y1 - y0) + WALL_T
            size = (length, WALL_T, self.height) if y0 == y1 else (WALL_T, length, self.height)
            out.append(('wall_%d' % i, size, ((x0 + x1) / 2, (y0 + y1) / 2, self.height / 2)))
        return out


def empty_room():
    h = 3.0
    walls = [(-h, -h, h, -h), (h, -h, h, h), (h, h, -h, h), (-h, h, -h, -h)]
    return Room('empty_room', 'Empty room 6 x 6 m inside, walls 1 m high', 1.0, WALL, walls)


OFFICE_DOORWAYS = [
    ('entrance', (-6.0, 3.0), 'x', 1.0),
    ('room_a', (-4.0, 2.0), 'y', 1.0),
    ('room_b', (0.0, 2.0), 'y', 1.0),
    ('room_c', (2.8, 2.0), 'y', 1.0),
    ('room_d', (3.5, 3.0), 'x', 1.0),
    ('a_b', (-2.0, -1.5), 'x', 1.0),
    ('b_c', (2.0, -1.5), 'x', 1.0),
]


def office():
    walls = []
    walls += wall_runs(-6, -4, 6, -4)
    walls += wall_runs(-6, 4, 6, 4)
    walls += wall_runs(-6, -4, -6, 4, gaps=[(3.0, 1.0)])
    walls += wall_runs(6, -4, 6, 4)
    walls += wall_runs(-6, 2, 6, 2, gaps=[(-4.0, 1.0), (0.0, 1.0), (2.8, 1.0)])
    walls += wall_runs(-2, -4, -2, 2, gaps=[(-1.5, 1.0)])
    walls += wall_runs(2, -4, 2, 2, gaps=[(-1.5, 1.0)])
    walls += wall_runs(3.5, 2, 3.5, 4, gaps=[(3.0, 1.0)])
    return Room('office', 'Office floor 12 x 8 m: rooms A, B (around the origin), C, a store '
                'room D and a corridor with an entrance; walls 1 m high', 1.0, WALL, walls,
                OFFICE_DOORWAYS)


# 5 x 5 cells of 1 m; north is the first line. Entrance on the west of the middle row (the
# maze frame's origin is the middle of that opening), exit on the east of the same row.
MAZE = [
    '###########',
    '#.....#...#',
    '#.###.#.#.#',
    '#.#...#.#.#',
    '#.#.###.#.#',
    '..#.....#..',
    '###.#####.#',
    '#...#...#.#',
    '#.###.#.#.#',
    '#.....#...#',
    '###########',
]


def maze_walls(grid=MAZE, cell=1.0):
    n = len(grid)

    def xy(i, j):
        return j / 2 * cell, (n // 2 - i) / 2 * cell

    walls = []
    for i in range(0, n, 2):            # east-west runs on even lines
        j = 0
        while j < n:
            if grid[i][j] == '#':
                k = j
                while k + 1 < n and grid[i][k + 1] == '#':
                    k += 1
                if k > j:
                    walls.append(xy(i, j) + xy(i, k))
                j = k + 1
            else:
                j += 1
    for j in range(0, n, 2):            # north-south runs on even columns
        i = 0
        while i < n:
            if grid[i][j] == '#':
                k = i
                while k + 1 < n and grid[k + 1][j] == '#':
                    k += 1
                if k > i:
                    walls.append(xy(i, j) + xy(k, j))
                i = k + 1
            else:
                i += 1
    return walls


def maze():
    return Room('maze', 'Maze of 5 x 5 cells of 1 m, entrance west and exit east of the middle '
                'row, walls 0.5 m high', 0.5, MAZE_WALL, maze_walls())


ROOMS = [empty_room, office, maze]


def rooms():
    return [f() for f in ROOMS]
