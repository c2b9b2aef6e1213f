"""The Python API: trace from a path, bytes or a numpy array; curves as (N, 2) arrays with a
closed flag; reconstruct; physical size; errors as CrawltraceError with the command line's
one-line messages; the GIL released while tracing."""

from __future__ import annotations

import subprocess
import threading
import time

import numpy as np
import pytest

import crawltrace
from crawltrace import CrawltraceError

from conftest import DASH, PEN_RADIUS, distance_to_rectangle


def test_the_error_is_a_value_error():
    assert issubclass(CrawltraceError, ValueError)


def test_a_path_bytes_and_a_path_like_give_the_same_drawing(samples):
    path = samples / "face-scan.jpg"
    from_path = crawltrace.trace(str(path))
    from_bytes = crawltrace.trace(path.read_bytes())
    from_pathlike = crawltrace.trace(path)
    from_bytearray = crawltrace.trace(bytearray(path.read_bytes()))
    from_view = crawltrace.trace(memoryview(path.read_bytes()))
    svg = from_path.to_svg()
    for other in (from_bytes, from_pathlike, from_bytearray, from_view):
        assert other.to_svg() == svg
    assert len(from_path.curves) == svg.count("<path ") > 0
    assert [c.closed for c in from_path.curves] == [
        line.endswith('Z"/>') for line in svg.splitlines() if line.startswith("<path")
    ]
    for curve in from_path.curves:
        assert curve.points.dtype == np.float64
        assert curve.points.ndim == 2 and curve.points.shape[1] == 2
        assert len(curve) == curve.points.shape[0] >= 2
        assert curve.indices is None
        assert curve.closed in (True, False)


def test_the_svg_is_what_the_command_writes(samples, binary):
    path = samples / "letters-scan.jpg"
    command = subprocess.run(
        [str(binary), "trace", str(path), "-o", "-", "-q", "--dpi", "300"],
        check=True,
        capture_output=True,
    )
    assert crawltrace.trace(path, dpi=300).to_svg() == command.stdout.decode()
    command = subprocess.run(
        [str(binary), "trace", str(path), "-o", "-", "-q", "--format", "dxf", "--size", "8in"],
        check=True,
        capture_output=True,
    )
    assert crawltrace.trace(path, size="8in").to_dxf() == command.stdout.decode()


def test_a_numpy_array_traces_to_the_shape_drawn(rectangle_image):
    drawing = crawltrace.trace(rectangle_image)
    assert (drawing.width, drawing.height) == (600, 400)
    assert len(drawing.curves) == 1
    (curve,) = drawing.curves
    assert curve.closed
    # Every vertex lies on the centre line of the drawn outline, within the pen's radius and
    # the fitting tolerance.
    worst = distance_to_rectangle(curve.points).max()
    assert worst <= PEN_RADIUS + 1.0, worst
    # The four corners are there: vertices near each.
    for corner in [(100, 80), (500, 80), (500, 320), (100, 320)]:
        nearest = np.hypot(*(curve.points - corner).T).min()
        assert nearest < DASH / 2, (corner, nearest)


def test_every_accepted_array_layout_gives_the_same_curves(rectangle_image):
    reference = crawltrace.trace(rectangle_image).to_svg()
    gray = rectangle_image
    variants = {
        "(h, w, 1)": gray[:, :, None],
        "rgb": np.dstack([gray] * 3),
        "rgba": np.dstack([gray] * 3 + [np.full_like(gray, 255)]),
        "gray + alpha": np.dstack([gray, np.full_like(gray, 255)]),
        "uint16": gray.astype(np.uint16) * 257,
        "fortran order": np.asfortranarray(gray),
        "a strided view": np.repeat(gray, 2, axis=1)[:, ::2],
    }
    for name, array in variants.items():
        assert crawltrace.trace(array).to_svg() == reference, name


@pytest.mark.parametrize(
    "array, message",
    [
        (np.zeros((10, 10, 5), np.uint8), "got shape [10, 10, 5]"),
        (np.zeros(100, np.uint8), "got shape [100]"),
        (np.zeros((2, 10, 10, 3), np.uint8), "got shape [2, 10, 10, 3]"),
        (np.zeros((10, 10)), "got dtype float64"),
        (np.zeros((10, 10), np.int32), "got dtype int32"),
        (np.zeros((10, 10), bool), "got dtype bool"),
        (np.zeros((0, 10), np.uint8), "empty image (10×0 pixels)"),
        (np.full((50, 50), 255, np.uint8), "no drawing found"),
    ],
)
def test_a_wrong_array_is_a_clear_error(array, message):
    with pytest.raises(CrawltraceError) as raised:
        crawltrace.trace(array)
    text = str(raised.value)
    assert message in text, text
    assert "\n" not in text


def test_bad_files_and_data_are_one_line_errors(tmp_path):
    cases = [
        (tmp_path / "missing.png", "missing.png: no such file"),
        (b"hello, not an image", "not an image, or not a format crawltrace reads"),
        (b"", "empty file (0 bytes)"),
        (tmp_path, "not a regular file (a folder)"),
    ]
    for source, message in cases:
        with pytest.raises(CrawltraceError) as raised:
            crawltrace.trace(source)
        assert message in str(raised.value)
        assert "\n" not in str(raised.value)
    with pytest.raises(TypeError, match="takes a path, bytes or a numpy array, not int"):
        crawltrace.trace(42)


@pytest.mark.parametrize(
    "options, message",
    [
        ({"threshold": 256}, "threshold: must be a gray level from 0 to 255"),
        ({"threshold": -1}, "threshold: must be a gray level from 0 to 255"),
        ({"threshold": 100, "adaptive": True}, "threshold: cannot be used with adaptive=True"),
        ({"spacing": 0}, "spacing: must be a positive number"),
        ({"stroke_width": float("nan")}, "stroke_width: must be a positive number"),
        ({"simplify": -0.5}, "simplify: must be zero or a positive number"),
        ({"method": "crawl"}, 'method: must be "strokes", "points" or "paper"'),
        ({"color": 'red" onload="x'}, "color: must be an SVG colour"),
        ({"dpi": 0}, "dpi: must be a positive number"),
        ({"dpi": -300}, "dpi: must be a positive number"),
        ({"size": "banana"}, "size: must be a positive length with a unit, such as 210mm"),
        ({"size": "210"}, "size: must be a positive length with a unit"),
        ({"size": "8in", "dpi": 300}, "size: cannot be used with dpi"),
        ({"units": "cm"}, "units: must be mm or in"),
    ],
)
def test_bad_options_are_the_command_lines_errors(samples, options, message):
    with pytest.raises(CrawltraceError) as raised:
        crawltrace.trace(samples / "face-clean.png", **options)
    assert str(raised.value) == message or str(raised.value).startswith(message)


def test_physical_size_follows_dpi_size_and_units(rectangle_image):
    default = crawltrace.trace(rectangle_image)
    assert default.image_dpi is None
    assert (default.dpi, default.units) == (96.0, "mm")
    assert 'width="158.75mm" height="105.8333mm" viewBox="0 0 600 400"' in default.to_svg()
    scanned = crawltrace.trace(rectangle_image, dpi=300, units="in")
    assert (scanned.dpi, scanned.units) == (300.0, "in")
    assert 'width="2in" height="1.3333in"' in scanned.to_svg()
    sized = crawltrace.trace(rectangle_image, size="120mm")
    assert sized.dpi == pytest.approx(600 / (120 / 25.4))
    assert 'width="120mm" height="80mm"' in sized.to_svg()


def test_the_image_files_density_is_used(samples, tmp_path):
    # A JPEG with a JFIF density of 200 dpi, written by hand: SOI, APP0, then the sample's rest.
    jpeg = (samples / "face-scan.jpg").read_bytes()
    app0 = b"\xff\xe0\x00\x10JFIF\x00\x01\x02\x01\x00\xc8\x00\xc8\x00\x00"
    rest = jpeg[2:]
    if rest[:2] == b"\xff\xe0":  # drop the sample's own APP0
        rest = rest[2 + int.from_bytes(rest[2:4], "big"):]
    drawing = crawltrace.trace(b"\xff\xd8" + app0 + rest)
    assert drawing.image_dpi == 200.0
    assert drawing.dpi == 200.0
    assert crawltrace.trace(b"\xff\xd8" + app0 + rest, dpi=100).dpi == 100.0


def test_the_gil_is_released_while_tracing(samples):
    """While one thread traces a 12-megapixel page, another keeps running Python code."""
    page = (samples / "page-4000x3000.png").read_bytes()
    finished = []
    started = time.perf_counter()
    tracer = threading.Thread(target=lambda: finished.append(crawltrace.trace(page)))
    tracer.start()
    ticks = []
    while tracer.is_alive():
        ticks.append(time.perf_counter())
        time.sleep(0.001)
    tracer.join()
    duration = time.perf_counter() - started
    assert finished and finished[0].curves
    gaps = np.diff([started] + ticks + [time.perf_counter()])
    # Holding the GIL would stop this loop for the whole trace.
    assert gaps.max() < 0.5 * duration, (gaps.max(), duration)


def test_reconstruct_finds_closed_and_open_curves_and_outliers():
    # A circle, an open wave well away from it (the crawl lets an open curve's end take any
    # point within the curve's own extent), and a lone point.
    angles = np.linspace(0, 2 * np.pi, 40, endpoint=False)
    circle = np.column_stack([np.cos(angles), np.sin(angles)]) * 10
    wave_x = np.linspace(100, 130, 31)
    wave = np.column_stack([wave_x, np.sin(wave_x / 5) * 3])
    outlier = np.array([[50.0, 60.0]])
    points = np.vstack([circle, wave, outlier])
    curves, outliers = crawltrace.reconstruct(points)
    assert sorted(c.closed for c in curves) == [False, True]
    closed = next(c for c in curves if c.closed)
    assert sorted(closed.indices.tolist()) == list(range(40))
    np.testing.assert_array_equal(closed.points, points[closed.indices])
    open_curve = next(c for c in curves if not c.closed)
    assert sorted(open_curve.indices.tolist()) == list(range(40, 71))
    assert outliers.dtype == np.int64 and outliers.tolist() == [71]
    # Lists work too, and give the same result.
    again, _ = crawltrace.reconstruct(points.tolist())
    assert [c.indices.tolist() for c in again] == [c.indices.tolist() for c in curves]


@pytest.mark.parametrize(
    "points, message",
    [
        (np.zeros((5, 3)), "points: must be an (N, 2) array of x, y; got shape (5, 3)"),
        (np.zeros(4), "points: must be an (N, 2) array of x, y; got shape (4,)"),
        ([[0, 0], [1, "a"]], "points: not an (N, 2) array of numbers"),
        ([[0, 0], [1, 1], [2, float("nan")]], "point 2 has a coordinate that is not a finite number"),
        ([[0, 0], [1, 1e300]], "point 1 has a coordinate the triangulation cannot represent"),
    ],
)
def test_bad_point_sets_are_clear_errors(points, message):
    with pytest.raises(CrawltraceError) as raised:
        crawltrace.reconstruct(points)
    assert str(raised.value).startswith(message), str(raised.value)
