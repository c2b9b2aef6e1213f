"""The vpype plug-in, with vpype installed from PyPI: `vpype ctrace` is found through the entry
point, adds the traced curves as lines on a layer in CSS pixels (96 / dpi per image pixel), and
runs in the plotter pipeline of docs/cli.md."""

from __future__ import annotations

import subprocess
import sys
from importlib.metadata import entry_points
from pathlib import Path

import numpy as np
import pytest

vpype_cli = pytest.importorskip("vpype_cli")

import crawltrace  # noqa: E402


#: The vpype command installed beside this Python (a virtual environment's bin/ need not be on
#: PATH).
VPYPE = str(Path(sys.executable).parent / "vpype")


def vpype(*args: str, cwd: Path) -> subprocess.CompletedProcess:
    return subprocess.run([VPYPE, *args], cwd=cwd, capture_output=True, text=True)


def test_the_plugin_is_registered():
    names = [entry.name for entry in entry_points().select(group="vpype.plugins")]
    assert "ctrace" in names


def test_ctrace_adds_one_line_per_curve_scaled_by_the_dpi(samples):
    image = samples / "letters-clean.png"
    drawing = crawltrace.trace(image)
    document = vpype_cli.execute(f"ctrace '{image}'")
    assert document.count() == 1  # one layer
    lines = list(document.layers[1])
    assert len(lines) == len(drawing.curves)
    for line, curve in zip(lines, drawing.curves):
        expected = curve.points[:, 0] + 1j * curve.points[:, 1]
        if curve.closed:
            expected = np.append(expected, expected[0])
            assert line[0] == line[-1]
        np.testing.assert_allclose(line, expected)  # 96 dpi: a pixel is a CSS pixel

    at_300 = vpype_cli.execute(f"ctrace --dpi 300 '{image}'")
    scale = 96 / 300
    np.testing.assert_allclose(np.array(at_300.bounds()), np.array(document.bounds()) * scale)
    # A second ctrace goes to a new layer when asked.
    two = vpype_cli.execute(f"ctrace '{image}' ctrace -l new '{image}'")
    assert two.count() == 2


def test_the_plotter_pipeline_writes_hpgl(samples, tmp_path):
    image = samples / "face-scan.jpg"
    result = vpype(
        # vpype chains commands: a command's options come before its arguments.
        "ctrace", "--dpi", "300", str(image),
        "linemerge", "linesort",
        "write", "--device", "hp7475a", "--page-size", "a4", "--center", "out.hpgl",
        cwd=tmp_path,
    )
    assert result.returncode == 0, result.stderr
    hpgl = (tmp_path / "out.hpgl").read_text()
    assert hpgl.startswith("IN;") and "PD" in hpgl
    # One pen-down run per curve at most (linemerge may join some).
    assert 1 <= hpgl.count("PU") <= len(crawltrace.trace(image).curves) + 2


def test_a_pipe_from_the_command_into_vpype(samples, binary, tmp_path):
    image = samples / "face-scan.jpg"
    script = f"cat '{image}' | '{binary}' trace - -o - -q | '{VPYPE}' read - stat"
    result = subprocess.run(["sh", "-c", script], cwd=tmp_path, capture_output=True, text=True)
    assert result.returncode == 0, result.stderr
    assert "Layer 1" in result.stdout or "layer" in result.stdout.lower(), result.stdout


def test_a_bad_image_or_dpi_is_a_vpype_error(tmp_path, samples):
    (tmp_path / "bad.png").write_bytes(b"not an image")
    for args, message in [
        (["bad.png"], "bad.png: not an image"),
        (["--dpi", "0", str(samples / "face-clean.png")], "dpi: must be a positive number"),
    ]:
        result = vpype("ctrace", *args, "stat", cwd=tmp_path)
        assert result.returncode != 0
        assert message in result.stderr, result.stderr
        assert "Traceback" not in result.stderr
