"""Map YAML + image -> Grid, as map_server's main.cpp and image_loader.cpp do it.

Errors raise MapError carrying the original map_server's one-line message."""
import math
import os
from dataclasses import dataclass

import numpy as np
import yaml

from map_server.grid import Grid

TRINARY, SCALE, RAW = 'trinary', 'scale', 'raw'
MODES = (TRINARY, SCALE, RAW)


class MapError(Exception):
    """A map YAML or image that cannot be loaded; str(e) is the one-line reason."""


@dataclass
class MapConfig:
    image: str          # absolute or relative to the cwd (already resolved against the YAML's directory)
    resolution: float
    origin: tuple
    negate: bool
    occupied_thresh: float
    free_thresh: float
    mode: str = TRINARY


def _no_tag(key):
    """The original's error for a missing or invalid number tag."""
    return MapError('The map does not contain %s %s tag or it is invalid.' % ('an' if key[0] in 'aeiou' else 'a', key))


def _number(doc, key, kind=float):
    if key not in doc:
        raise _no_tag(key)
    value = doc[key]
    if isinstance(value, bool) and kind is float:
        raise _no_tag(key)
    try:
        value = kind(value)
    except (TypeError, ValueError):
        raise _no_tag(key)
    if kind is float and not math.isfinite(value):
        raise _no_tag(key)
    return value


def parse_map_yaml(path):
    """Read a map YAML file -> MapConfig. Raises MapError with map_server's messages."""
    try:
        with open(path) as f:
            text = f.read()
    except OSError:
        raise MapError('Map_server could not open %s.' % path)
    try:
        doc = yaml.safe_load(text)
    except yaml.YAMLError as e:
        mark = getattr(e, 'problem_mark', None)
        where = ' (line %d)' % (mark.line + 1) if mark is not None else ''
        raise MapError('Map_server could not parse %s%s: not valid YAML.' % (path, where))
    if not isinstance(doc, dict):
        raise MapError('Map_server could not parse %s: expected a YAML mapping of map keys.' % path)
    res = _number(doc, 'resolution')
    if res <= 0.0:
        raise MapError('The map does not contain a resolution tag or it is invalid. '
                       '(resolution must be > 0, got %g)' % res)
    negate = doc.get('negate')
    if negate is None or isinstance(negate, str):
        raise MapError('The map does not contain a negate tag or it is invalid.')
    try:
        negate = bool(int(negate))
    except (TypeError, ValueError):
        raise MapError('The map does not contain a negate tag or it is invalid.')
    occ = _number(doc, 'occupied_thresh')
    free = _number(doc, 'free_thresh')
    if not (0.0 <= free <= 1.0 and 0.0 <= occ <= 1.0) or free > occ:
        raise MapError('The map has invalid thresholds: occupied_thresh %g and free_thresh %g must lie '
                       'in [0, 1] with free_thresh <= occupied_thresh.' % (occ, free))
    mode = doc.get('mode', TRINARY)
    if mode not in MODES:
        raise MapError('Invalid mode tag "%s".' % mode)
    origin = doc.get('origin')
    try:
        origin = tuple(float(v) for v in origin)
        if len(origin) != 3 or not all(math.isfinite(v) for v in origin):
            raise ValueError
    except (TypeError, ValueError):
        raise MapError('The map does not contain an origin tag or it is invalid.')
    image = doc.get('image')
    if image is None or not isinstance(image, (str, int, float)):
        raise MapError('The map does not contain an image tag or it is invalid.')
    image = str(image)
    if not image:
        raise MapError('The image tag cannot be an empty string.')
    if not os.path.isabs(image):
        image = os.path.join(os.path.dirname(path), image)
    return MapConfig(image, res, origin, negate, occ, free, mode)


def _read_pixels(image_path):
    """-> (pixels uint8 (h, w, channels), has_alpha). Raises MapError naming the file."""
    try:
        from PIL import Image
    except ImportError:     # a missing dependency: a clear error, never a silent fallback
        raise MapError('map_server needs python3-pil (Debian package) to read "%s"' % image_path)
    try:
        with Image.open(image_path) as img:
            img.load()
            mode = img.mode
            if mode == 'P':
                img = img.convert('RGBA' if 'transparency' in img.info else 'RGB')
            elif mode in ('1', 'I', 'I;16', 'I;16B', 'F'):
                if mode != '1':
                    arr = np.asarray(img, dtype=np.float64)
                    peak = 65535.0 if arr.max() > 255 else 255.0
                    img = Image.fromarray(np.clip(arr * 255.0 / peak, 0, 255).astype(np.uint8), 'L')
                else:
                    img = img.convert('L')
            elif mode == 'LA':          # as SDL_image reads it (the original): grey, grey, grey, alpha
                img = img.convert('RGBA')
            elif mode not in ('L', 'RGB', 'RGBA'):
                img = img.convert('RGBA' if 'A' in mode else 'RGB')
            pixels = np.asarray(img, dtype=np.uint8)
            has_alpha = img.mode in ('LA', 'RGBA')
    except FileNotFoundError:
        raise MapError('failed to open image file "%s": no such file' % image_path)
    except Exception as e:  # PIL raises several types for unreadable files
        raise MapError('failed to open image file "%s": %s' % (image_path, e))
    if pixels.ndim == 2:
        pixels = pixels[:, :, None]
    if pixels.shape[0] == 0 or pixels.shape[1] == 0:
        raise MapError('failed to open image file "%s": the image is empty' % image_path)
    return pixels, has_alpha


def pixels_to_cells(pixels, has_alpha, negate, occ_th, free_th, mode):
    """image_loader.cpp's conversion. pixels: uint8 (h, w, channels), row 0 = top of the image.
    -> int8 (h, w) with row 0 = bottom (the map's lowest y)."""
    n = pixels.shape[2]
    avg_channels = n if (mode == TRINARY or not has_alpha) else n - 1
    color_avg = pixels[:, :, :avg_channels].astype(np.int32).sum(axis=2) / float(avg_channels)
    # transparent (alpha 0) = unknown in scale mode; an image without alpha is opaque
    alpha = pixels[:, :, n - 1].astype(np.float64) if has_alpha else np.ones(color_avg.shape)
    if negate:
        color_avg = 255.0 - color_avg
    if mode == RAW:
        cells = color_avg.astype(np.int32).astype(np.uint8).view(np.int8)
    else:
        occ = (255.0 - color_avg) / 255.0
        cells = np.full(color_avg.shape, -1, dtype=np.int8)
        if mode == SCALE:
            span = occ_th - free_th
            ratio = (occ - free_th) / span if span > 0 else np.zeros_like(occ)
            scaled = (1.0 + 98.0 * ratio).astype(np.int32)
            middle = alpha >= 1.0
            cells[middle] = scaled[middle].astype(np.int8)
        cells[occ > occ_th] = 100
        cells[occ < free_th] = 0
    return np.ascontiguousarray(cells[::-1])


def load_image_grid(cfg):
    """MapConfig -> Grid."""
    pixels, has_alpha = _read_pixels(cfg.image)
    cells = pixels_to_cells(pixels, has_alpha, cfg.negate, cfg.occupied_thresh, cfg.free_thresh, cfg.mode)
    h, w = cells.shape
    return Grid(w, h, cfg.resolution, cfg.origin, cells)


def load_map(yaml_path):
    """Map YAML path -> Grid (raises MapError)."""
    return load_image_grid(parse_map_yaml(yaml_path))
