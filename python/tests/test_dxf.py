"""DXF read back with ezdxf, the reference Python DXF library: the file audits clean, has one
LWPOLYLINE per curve with the right closed flags, declares its units, and its coordinates are
the drawing's, in mm or inches, y pointing up."""

from __future__ import annotations

import io
import logging
import subprocess

import ezdxf
import numpy as np
import pytest

import crawltrace

from conftest import PEN_RADIUS, distance_to_rectangle


def read_dxf(text: str, caplog) -> "ezdxf.document.Drawing":
    """Reads and audits a DXF text; ezdxf must neither warn nor find errors."""
    with caplog.at_level(logging.WARNING, logger="ezdxf"):
        document = ezdxf.read(io.StringIO(text))
        auditor = document.audit()
    assert not auditor.has_errors, [str(error) for error in auditor.errors]
    assert not auditor.has_fixes, [str(fix) for fix in auditor.fixes]
    assert [r.getMessage() for r in caplog.records if r.levelno >= logging.WARNING] == []
    assert document.dxfversion == "AC1015"
    return document


def test_the_polylines_are_the_drawn_rectangle_in_millimetres(rectangle_image, caplog):
    drawing = crawltrace.trace(rectangle_image, dpi=300)
    document = read_dxf(drawing.to_dxf(), caplog)
    assert document.header["$INSUNITS"] == 4  # millimetres
    entities = list(document.modelspace())
    assert [entity.dxftype() for entity in entities] == ["LWPOLYLINE"] * len(drawing.curves)
    assert [bool(entity.closed) for entity in entities] == [c.closed for c in drawing.curves]
    mm_per_pixel = 25.4 / 300
    for entity, curve in zip(entities, drawing.curves):
        vertices = np.array([(x, y) for x, y, *_ in entity.get_points()])
        # The same vertices as Drawing.curves, in mm with y up, to the 4 decimals written.
        expected = np.column_stack([curve.points[:, 0], 400 - curve.points[:, 1]]) * mm_per_pixel
        np.testing.assert_allclose(vertices, expected, atol=1e-4)
        # And on the rectangle that was drawn, within the pen's radius and a pixel of fitting.
        in_pixels = np.column_stack([vertices[:, 0], 400 * mm_per_pixel - vertices[:, 1]])
        worst = distance_to_rectangle(in_pixels / mm_per_pixel).max()
        assert worst <= PEN_RADIUS + 1.0, worst


def test_inches_are_declared_and_the_extents_are_the_page(rectangle_image, caplog):
    drawing = crawltrace.trace(rectangle_image, size="6in", units="in")
    document = read_dxf(drawing.to_dxf(), caplog)
    assert document.header["$INSUNITS"] == 1  # inches
    assert document.header["$EXTMAX"][:2] == pytest.approx((6.0, 4.0))
    (entity,) = document.modelspace()
    xs = [x for x, *_ in entity.get_points()]
    assert 0.9 < min(xs) < 1.1 and 4.9 < max(xs) < 5.1  # the rectangle spans 100..500 of 600 px


def test_curves_are_flattened_within_the_simplify_tolerance(samples, caplog):
    """A smooth drawing: the DXF vertices stay within `simplify` of the SVG's Bézier paths, so
    a finer tolerance gives more vertices."""
    coarse = crawltrace.trace(samples / "spiral-waves-thin.png", simplify=2.0)
    fine = crawltrace.trace(samples / "spiral-waves-thin.png", simplify=0.25)
    count = lambda drawing: sum(  # noqa: E731
        len(entity) for entity in read_dxf(drawing.to_dxf(), caplog).modelspace()
    )
    assert count(fine) > count(coarse)
    assert count(coarse) == sum(len(curve) for curve in coarse.curves)


def test_the_command_writes_the_same_dxf(samples, binary, tmp_path, caplog):
    sample = samples / "silhouettes-scan.jpg"
    output = tmp_path / "silhouettes.dxf"
    subprocess.run([str(binary), "trace", str(sample), "-o", str(output), "-q"], check=True)
    document = read_dxf(output.read_text(), caplog)
    drawing = crawltrace.trace(sample)
    entities = list(document.modelspace())
    assert len(entities) == len(drawing.curves) > 1
    assert [bool(entity.closed) for entity in entities] == [c.closed for c in drawing.curves]
    # A batch honours the format too.
    subprocess.run(
        [str(binary), "trace", str(sample), str(samples / "face-scan.jpg"), "-o", str(tmp_path / "out"),
         "--format", "dxf", "-q"],
        check=True,
    )
    assert sorted(p.name for p in (tmp_path / "out").iterdir()) == ["face-scan.dxf", "silhouettes-scan.dxf"]
    read_dxf((tmp_path / "out" / "face-scan.dxf").read_text(), caplog)
