"""Shared fixtures: the repository's samples, a drawing of known geometry made here with numpy,
and the crawltrace binary for the tests that compare with the command line."""

from __future__ import annotations

import os
import shutil
from pathlib import Path

import numpy as np
import pytest

REPOSITORY = Path(__file__).resolve().parents[2]
SAMPLES = REPOSITORY / "samples"

#: The rectangle of `rectangle_image`: left, top, right, bottom, in pixel coordinates (pixel
#: centres at +0.5, as crawltrace writes them).
RECTANGLE = (100.0, 80.0, 500.0, 320.0)
#: Its pen: a disc of this radius, drawn in dashes of DASH pixels with GAP pixel gaps.
PEN_RADIUS = 2.0
DASH, GAP = 24.0, 7.0


def rectangle_outline(width: int = 600, height: int = 400) -> np.ndarray:
    """A skip-stroke rectangle outline: black dashes on white, uint8 (height, width)."""
    left, top, right, bottom = RECTANGLE
    corners = [(left, top), (right, top), (right, bottom), (left, bottom), (left, top)]
    ys, xs = np.mgrid[0:height, 0:width]
    centres_x, centres_y = xs + 0.5, ys + 0.5
    ink = np.zeros((height, width), dtype=bool)
    travelled = 0.0
    for (x0, y0), (x1, y1) in zip(corners, corners[1:]):
        length = float(np.hypot(x1 - x0, y1 - y0))
        for step in np.arange(0.0, length, 0.5):
            if (travelled + step) % (DASH + GAP) < DASH:
                x = x0 + (x1 - x0) * step / length
                y = y0 + (y1 - y0) * step / length
                box = (slice(max(int(y) - 4, 0), int(y) + 5), slice(max(int(x) - 4, 0), int(x) + 5))
                near = np.hypot(centres_x[box] - x, centres_y[box] - y) <= PEN_RADIUS
                ink[box] |= near
        travelled += length
    return np.where(ink, 0, 255).astype(np.uint8)


def distance_to_rectangle(points: np.ndarray) -> np.ndarray:
    """Distance of each (x, y) in pixels to the outline of RECTANGLE."""
    left, top, right, bottom = RECTANGLE
    x, y = points[:, 0], points[:, 1]
    inside = (x >= left) & (x <= right) & (y >= top) & (y <= bottom)
    dx = np.maximum.reduce([left - x, np.zeros_like(x), x - right])
    dy = np.maximum.reduce([top - y, np.zeros_like(y), y - bottom])
    outside = np.hypot(dx, dy)
    to_edge = np.minimum.reduce([x - left, right - x, y - top, bottom - y])
    return np.where(inside, to_edge, outside)


@pytest.fixture(scope="session")
def rectangle_image() -> np.ndarray:
    return rectangle_outline()


@pytest.fixture(scope="session")
def samples() -> Path:
    return SAMPLES


def find_binary() -> Path | None:
    """The crawltrace command: $CRAWLTRACE_BIN, else a build in the repository, else PATH."""
    if os.environ.get("CRAWLTRACE_BIN"):
        return Path(os.environ["CRAWLTRACE_BIN"])
    for profile in ("release", "debug"):
        candidate = REPOSITORY / "target" / profile / "crawltrace"
        if candidate.exists():
            return candidate
    found = shutil.which("crawltrace")
    return Path(found) if found else None


@pytest.fixture(scope="session")
def binary() -> Path:
    found = find_binary()
    if found is None:
        if os.environ.get("CI"):
            pytest.fail("CI must set CRAWLTRACE_BIN to the crawltrace binary")
        pytest.skip("no crawltrace binary: set CRAWLTRACE_BIN or run cargo build")
    return found
