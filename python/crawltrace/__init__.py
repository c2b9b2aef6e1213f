"""Centre-line tracing of scanned line drawings, and curve reconstruction from 2D point sets.

crawltrace turns a scan of a drawing made of short strokes into one vector curve per shape
(closed where the shape is closed), using the *Crawl through Neighbors* reconstruction
(S. N. Parakkat and R. Muthuganapathy, Computer Graphics Forum 35(5), 2016). No option is needed
for a good result.

>>> import crawltrace
>>> drawing = crawltrace.trace("scan.png")            # doctest: +SKIP
>>> [curve.closed for curve in drawing.curves]         # doctest: +SKIP
>>> open("scan.svg", "w").write(drawing.to_svg())      # doctest: +SKIP
"""

from __future__ import annotations

import os
from typing import Optional, Sequence, Tuple, Union

import numpy as np

from ._crawltrace import CrawltraceError, Curve, Drawing
from ._crawltrace import reconstruct_points as _reconstruct_points
from ._crawltrace import trace_drawing as _trace_drawing

__all__ = ["trace", "reconstruct", "Drawing", "Curve", "CrawltraceError"]

ImageSource = Union[str, os.PathLike, bytes, bytearray, memoryview, np.ndarray]


def trace(
    source: ImageSource,
    *,
    threshold: Optional[int] = None,
    adaptive: bool = False,
    invert: bool = False,
    spacing: Optional[float] = None,
    method: str = "strokes",
    smooth: bool = True,
    simplify: Optional[float] = None,
    stroke_width: Optional[float] = None,
    color: str = "#000000",
    dpi: Optional[float] = None,
    size: Optional[str] = None,
    units: Optional[str] = None,
) -> Drawing:
    """Trace a line drawing into one curve per drawn shape.

    ``source`` is a path to an image file (PNG, JPEG, TIFF, BMP, GIF, WebP, …), the bytes of
    one, or a numpy array: ``(height, width)`` gray or ``(height, width, channels)`` with 1, 2
    (gray and alpha), 3 (RGB) or 4 (RGBA) channels, of uint8 or uint16; dark ink on light paper.

    The options are those of ``crawltrace trace`` (``--stroke-width`` is ``stroke_width``):
    ``threshold`` (0–255) or ``adaptive``, ``invert``, ``spacing`` and ``simplify`` (pixels),
    ``method`` (``"strokes"`` or ``"points"``), ``smooth``, ``stroke_width`` and ``color`` (of
    the SVG), and the physical size: ``dpi`` (default: the file's own density, else 96), or
    ``size`` of the longer side (``"210mm"``, ``"8in"``), written in ``units`` (``"mm"`` or
    ``"in"``; default the unit of ``size``, else mm).

    The GIL is released while tracing, so threads trace in parallel.

    Raises ``CrawltraceError`` (a ``ValueError``) with the command line's one-line message
    for a file that cannot be read or is not an image, a blank page, an option out of range or
    an array of the wrong shape or dtype; ``TypeError`` for a source of another type.
    """
    return _trace_drawing(
        source,
        threshold=threshold,
        adaptive=adaptive,
        invert=invert,
        spacing=spacing,
        method=method,
        smooth=smooth,
        simplify=simplify,
        stroke_width=stroke_width,
        color=color,
        dpi=dpi,
        size=size,
        units=units,
    )


def reconstruct(points: Union[np.ndarray, Sequence[Sequence[float]]]) -> Tuple[list, np.ndarray]:
    """Reconstruct curves from a planar point set, with no parameter.

    ``points`` is anything numpy reads as an ``(N, 2)`` array of ``x, y`` numbers. Returns
    ``(curves, outliers)``: a list of ``Curve`` (``.points`` an ``(M, 2)`` float64 array,
    ``.indices`` the input index of each point, ``.closed``) and an int64 array of the indices
    of the points on no curve. A point that repeats an earlier one exactly is merged into it
    and appears in neither. Raises ``CrawltraceError`` for another shape, or a coordinate that
    is not a finite number (or too large or too small to triangulate).
    """
    try:
        array = np.asarray(points, dtype=np.float64)
    except (TypeError, ValueError) as problem:
        raise CrawltraceError(f"points: not an (N, 2) array of numbers ({problem})") from None
    if array.ndim != 2 or array.shape[1] != 2:
        raise CrawltraceError(f"points: must be an (N, 2) array of x, y; got shape {array.shape}")
    return _reconstruct_points(array)
