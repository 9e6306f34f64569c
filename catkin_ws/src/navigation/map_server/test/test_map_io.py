"""map_server core without a master: YAML parsing and its errors, pixel -> cell conversion in every
mode, map_saver's files and the round trip saver -> loader."""
import os

import numpy as np
import pytest

from map_server.grid import Grid
from map_server.map_io import MapError, load_map, parse_map_yaml, pixels_to_cells
from map_server.node import MAP_SAVER_USAGE, parse_saver_args
from map_server.saver import SaverError, pgm_bytes, save_map, yaml_text

YAML = ('image: {image}\nresolution: 0.05\norigin: [-1.0, -2.0, 0.5]\nnegate: 0\n'
        'occupied_thresh: 0.65\nfree_thresh: 0.196\n')


def write_pgm(path, img):
    h, w = img.shape
    with open(path, 'wb') as f:
        f.write(b'P5\n%d %d\n255\n' % (w, h) + img.astype(np.uint8).tobytes())


def gray(values):
    return np.asarray(values, dtype=np.uint8)[:, :, None]


def test_trinary_thresholds_and_row_flip():
    # top image row: occupied, free; bottom row: unknown (205), free (254)
    cells = pixels_to_cells(gray([[0, 254], [205, 254]]), False, False, 0.65, 0.196, 'trinary')
    assert cells.tolist() == [[-1, 0], [100, 0]]     # row 0 = bottom of the image


def test_negate_swaps_black_and_white():
    cells = pixels_to_cells(gray([[0, 255]]), False, True, 0.65, 0.196, 'trinary')
    assert cells.tolist() == [[0, 100]]


def test_scale_mode_and_alpha():
    px = np.zeros((1, 3, 2), dtype=np.uint8)
    px[0, :, 0] = [128, 128, 0]
    px[0, :, 1] = [255, 0, 255]     # alpha 0 -> unknown in scale mode
    cells = pixels_to_cells(px, True, False, 0.65, 0.196, 'scale')
    p = (255 - 128) / 255.0
    assert cells.tolist() == [[int(1 + 98 * (p - 0.196) / (0.65 - 0.196)), -1, 100]]


def test_raw_mode_copies_values():
    cells = pixels_to_cells(gray([[0, 37, 100, 255]]), False, False, 0.65, 0.196, 'raw')
    assert cells.tolist() == [[0, 37, 100, -1]]


def test_rgb_mean_of_channels():
    px = np.array([[[0, 0, 0], [255, 255, 240]]], dtype=np.uint8)
    assert pixels_to_cells(px, False, False, 0.65, 0.196, 'trinary').tolist() == [[100, 0]]


def test_load_map_relative_image_and_origin(tmp_path):
    write_pgm(tmp_path / 'm.pgm', np.array([[0, 254, 205]]))
    (tmp_path / 'm.yaml').write_text(YAML.format(image='m.pgm'))
    grid = load_map(str(tmp_path / 'm.yaml'))
    assert (grid.width, grid.height, grid.resolution) == (3, 1, 0.05)
    assert grid.origin == (-1.0, -2.0, 0.5)
    assert grid.data.tolist() == [[100, 0, -1]]


def test_png_loads(tmp_path):
    from PIL import Image
    Image.fromarray(np.array([[0, 254]], dtype=np.uint8), 'L').save(str(tmp_path / 'm.png'))
    (tmp_path / 'm.yaml').write_text(YAML.format(image='m.png'))
    assert load_map(str(tmp_path / 'm.yaml')).data.tolist() == [[100, 0]]


@pytest.mark.parametrize('text, message', [
    (YAML.replace('resolution: 0.05\n', ''), 'The map does not contain a resolution tag or it is invalid.'),
    (YAML.replace('resolution: 0.05', 'resolution: abc'),
     'The map does not contain a resolution tag or it is invalid.'),
    (YAML.replace('resolution: 0.05', 'resolution: -1'), 'resolution must be > 0'),
    (YAML.replace('negate: 0\n', ''), 'The map does not contain a negate tag or it is invalid.'),
    (YAML.replace('occupied_thresh: 0.65\n', ''), 'The map does not contain an occupied_thresh tag or it is invalid.'),
    (YAML.replace('free_thresh: 0.196', 'free_thresh: 0.9'), 'invalid thresholds'),
    (YAML.replace('occupied_thresh: 0.65', 'occupied_thresh: 1.5'), 'invalid thresholds'),
    (YAML.replace('origin: [-1.0, -2.0, 0.5]', 'origin: [1, 2]'),
     'The map does not contain an origin tag or it is invalid.'),
    (YAML.replace('image: {image}\n', ''), 'The map does not contain an image tag or it is invalid.'),
    (YAML.replace('image: {image}', 'image: ""'), 'The image tag cannot be an empty string.'),
    (YAML + 'mode: fancy\n', 'Invalid mode tag "fancy".'),
    ('image: [unclosed\n', 'not valid YAML'),
])
def test_bad_yaml_gives_the_one_line_error(tmp_path, text, message):
    (tmp_path / 'm.yaml').write_text(text.format(image='m.pgm'))
    with pytest.raises(MapError) as e:
        parse_map_yaml(str(tmp_path / 'm.yaml'))
    assert message in str(e.value) and '\n' not in str(e.value)


def test_missing_yaml_and_missing_image(tmp_path):
    with pytest.raises(MapError, match='Map_server could not open'):
        parse_map_yaml(str(tmp_path / 'none.yaml'))
    (tmp_path / 'm.yaml').write_text(YAML.format(image='nothere.pgm'))
    with pytest.raises(MapError, match='failed to open image file ".*nothere.pgm"'):
        load_map(str(tmp_path / 'm.yaml'))


def test_saver_files_exactly_as_the_original(tmp_path):
    data = np.array([[-1, 0, 25], [26, 64, 65]], dtype=np.int8)   # row 0 = bottom
    grid = Grid(3, 2, 0.05, (-1.0, -2.0, 0.25), data)
    pgm = pgm_bytes(grid)
    header = b'P5\n# CREATOR: map_saver.cpp 0.050 m/pix\n3 2\n255\n'
    assert pgm[:len(header)] == header
    assert list(pgm[len(header):]) == [205, 205, 0, 205, 254, 254]     # top row first
    assert yaml_text('out/m.pgm', 0.05, (-1.0, -2.0, 0.25)) == (
        'image: out/m.pgm\nresolution: 0.050000\norigin: [-1.000000, -2.000000, 0.250000]\n'
        'negate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\n\n')


def test_save_then_load_round_trip(tmp_path):
    rng = np.random.default_rng(1)
    data = rng.choice(np.array([-1, 0, 100], dtype=np.int8), size=(40, 30))
    grid = Grid(30, 40, 0.05, (-0.75, -1.0, 0.0), data)
    lines = []
    cwd = os.getcwd()
    os.chdir(tmp_path)
    try:
        save_map(grid, 'saved', log=lines.append)
        back = load_map('saved.yaml')
    finally:
        os.chdir(cwd)
    assert lines == ['Writing map occupancy data to saved.pgm', 'Writing map occupancy data to saved.yaml']
    assert np.array_equal(back.data, grid.data)
    assert back.origin == grid.origin and back.resolution == pytest.approx(0.05)


def test_saver_arguments():
    assert parse_saver_args([]) == ('map', 65, 25)
    assert parse_saver_args(['-f', 'x/y', '--occ', '90', '--free', '10']) == ('x/y', 90, 10)
    assert parse_saver_args(['-h']) is None
    with pytest.raises(SaverError, match='threshold_free must be smaller than threshold_occupied'):
        parse_saver_args(['--occ', '20', '--free', '30'])
    with pytest.raises(SaverError, match='threshold_occupied must be between 1 and 100'):
        parse_saver_args(['--occ', '101'])
    with pytest.raises(SaverError) as e:
        parse_saver_args(['--bogus'])
    assert str(e.value) == MAP_SAVER_USAGE


@pytest.mark.parametrize('name, mode, negate', [('trinary', 'trinary', False), ('scale', 'scale', False),
                                                ('raw', 'raw', False), ('negate', 'trinary', True)])
def test_the_ramp_reads_as_the_cpp_loader_reads_it(name, mode, negate):
    """test/spectrum.png (RGBA: opaque, half and fully transparent greys, a coloured row) gives
    spectrum_<mode>.txt, which gtest_image_loader.cpp asks of map_server::loadMapFromFile too."""
    from map_server.map_io import _read_pixels
    here = os.path.dirname(os.path.abspath(__file__))
    pixels, has_alpha = _read_pixels(os.path.join(here, 'spectrum.png'))
    expected = np.loadtxt(os.path.join(here, 'spectrum_%s.txt' % name), dtype=int)
    assert pixels_to_cells(pixels, has_alpha, negate, 0.65, 0.196, mode).tolist() == expected.tolist()


def test_an_image_without_alpha_is_opaque_in_scale_mode():
    px = np.array([[[200, 100, 0]]], dtype=np.uint8)      # mean 100: between the thresholds
    p = (255 - 100) / 255.0
    assert pixels_to_cells(px, False, False, 0.65, 0.196, 'scale').tolist() == [
        [int(1 + 98 * (p - 0.196) / (0.65 - 0.196))]]


def test_grey_with_alpha_is_read_as_sdl_image_reads_it(tmp_path):
    """A grey + alpha PNG: grey, grey, grey, alpha (the original's SDL_image), so the trinary
    mean counts the grey three times."""
    from PIL import Image
    from map_server.map_io import _read_pixels
    la = np.zeros((1, 1, 2), dtype=np.uint8)
    la[0, 0] = (40, 200)
    Image.fromarray(la, 'LA').save(str(tmp_path / 'la.png'))
    pixels, has_alpha = _read_pixels(str(tmp_path / 'la.png'))
    assert has_alpha and pixels.tolist() == [[[40, 40, 40, 200]]]
