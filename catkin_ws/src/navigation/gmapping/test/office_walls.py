"""Ground truth of the space scanner's office for map checks: the wall boxes of ode_sim's
models/office/model.sdf (read as a file) and the furniture poses of office.world."""
import os
import xml.etree.ElementTree as ET

import numpy as np


def wall_boxes(sdf_path):
    """-> [(cx, cy, sx, sy)] of the office model's collision boxes (model at the world origin)."""
    boxes = []
    for col in ET.parse(sdf_path).getroot().iter('collision'):
        pose = [float(v) for v in col.find('pose').text.split()]
        size = [float(v) for v in col.find('geometry/box/size').text.split()]
        boxes.append((pose[0], pose[1], size[0], size[1]))
    return boxes


def furniture(world_path):
    """-> [(x, y)] of the included models other than the office, sun and ground plane."""
    out = []
    for inc in ET.parse(world_path).getroot().iter('include'):
        uri = inc.find('uri').text
        if uri.strip() in ('model://office', 'model://sun', 'model://ground_plane') or inc.find('pose') is None:
            continue
        pose = [float(v) for v in inc.find('pose').text.split()]
        out.append((pose[0], pose[1]))
    return out


def distance_to_walls(points, boxes):
    """Distance [m] from each (x, y) point to the nearest wall box (0 inside)."""
    pts = np.asarray(points, dtype=float).reshape(-1, 2)
    best = np.full(len(pts), np.inf)
    for cx, cy, sx, sy in boxes:
        dx = np.maximum(np.abs(pts[:, 0] - cx) - sx / 2.0, 0.0)
        dy = np.maximum(np.abs(pts[:, 1] - cy) - sy / 2.0, 0.0)
        best = np.minimum(best, np.hypot(dx, dy))
    return best


def wall_surface_points(boxes, step=0.05):
    """Points sampled along every face of every wall box."""
    pts = []
    for cx, cy, sx, sy in boxes:
        x0, x1, y0, y1 = cx - sx / 2, cx + sx / 2, cy - sy / 2, cy + sy / 2
        for x in np.arange(x0, x1 + 1e-9, step):
            pts += [(x, y0), (x, y1)]
        for y in np.arange(y0, y1 + 1e-9, step):
            pts += [(x0, y), (x1, y)]
    return np.array(pts)


def grid_points(data, origin, resolution, value):
    """Centres (x, y) of the cells of an (h, w) grid equal to value."""
    rows, cols = np.nonzero(data == value)
    return np.stack([origin[0] + (cols + 0.5) * resolution, origin[1] + (rows + 0.5) * resolution], axis=1)


def map_quality(data, origin, resolution, boxes, furniture_xy, furniture_radius=1.2, visible=None):
    """(wall cells marked within one cell [fraction of the observed wall surface],
    false occupied [fraction of occupied cells farther than one cell from any wall and any furniture]).
    visible: wall surface points to count (default: those next to a known (free) cell)."""
    occ = grid_points(data, origin, resolution, 100)
    d = distance_to_walls(occ, boxes)
    if furniture_xy:
        f = np.asarray(furniture_xy)
        near_f = np.min(np.hypot(occ[:, None, 0] - f[None, :, 0], occ[:, None, 1] - f[None, :, 1]), axis=1) \
            < furniture_radius
    else:
        near_f = np.zeros(len(occ), dtype=bool)
    tol = 1.5 * resolution
    false_occ = float(np.mean((d > tol) & ~near_f)) if len(occ) else 1.0
    surface = wall_surface_points(boxes) if visible is None else visible
    h, w = data.shape
    cols = np.floor((surface[:, 0] - origin[0]) / resolution).astype(int)
    rows = np.floor((surface[:, 1] - origin[1]) / resolution).astype(int)
    ok = (cols >= 1) & (rows >= 1) & (cols < w - 1) & (rows < h - 1)
    surface, rows, cols = surface[ok], rows[ok], cols[ok]
    # observed: a known-free cell within 2 cells (the face was seen from the free side)
    seen = np.zeros(len(surface), dtype=bool)
    marked = np.zeros(len(surface), dtype=bool)
    for dr in range(-2, 3):
        for dc in range(-2, 3):
            r, c = np.clip(rows + dr, 0, h - 1), np.clip(cols + dc, 0, w - 1)
            seen |= data[r, c] == 0
            if abs(dr) <= 1 and abs(dc) <= 1:
                marked |= data[r, c] == 100
    walls_found = float(np.mean(marked[seen])) if seen.any() else 0.0
    return walls_found, false_occ, int(seen.sum())


def office_paths():
    """(office model.sdf, office.world) found through ROS_PACKAGE_PATH-free relative lookup or rospkg."""
    import rospkg
    rp = rospkg.RosPack()
    sdf = os.path.join(rp.get_path('ode_sim'), 'models', 'office', 'model.sdf')
    world = os.path.join(rp.get_path('space_scanner_simulation'), 'worlds', 'office.world')
    return sdf, world
