"""The ``ctrace`` command of vpype: trace a scanned line drawing into lines on a layer.

    vpype ctrace scan.png linemerge linesort write out.hpgl

vpype works in CSS pixels (96 to the inch); the traced curves, in image pixels, are scaled by
96 / dpi, where dpi is ``--dpi``, else the density the image file records, else 96. Closed
curves end where they start, as vpype expects of closed lines.
"""

from __future__ import annotations

from typing import Optional

import click
import numpy as np
import vpype as vp
import vpype_cli

import crawltrace

#: vpype's unit: a CSS pixel, 1/96 inch.
CSS_PIXELS_PER_INCH = 96.0


def curves_to_lines(drawing: crawltrace.Drawing) -> vp.LineCollection:
    """The drawing's curves as vpype lines (complex x + iy), in CSS pixels."""
    scale = CSS_PIXELS_PER_INCH / drawing.dpi
    lines = vp.LineCollection()
    for curve in drawing.curves:
        points = curve.points * scale
        if curve.closed:
            points = np.vstack([points, points[:1]])
        lines.append(points[:, 0] + 1j * points[:, 1])
    return lines


@click.command()
@click.argument("image", type=vpype_cli.PathType(exists=True, dir_okay=False))
@click.option(
    "--dpi",
    type=float,
    default=None,
    help="Pixels per inch of the image (default: its file's density, else 96).",
)
@click.option("--threshold", type=click.IntRange(0, 255), default=None, help="Fixed gray level 0-255: darker is ink.")
@click.option("--adaptive", is_flag=True, help="Always flatten uneven lighting first.")
@click.option("--invert", is_flag=True, help="Light ink on dark paper.")
@click.option("--simplify", type=float, default=None, help="Largest deviation from the traced curve, in image pixels.")
@click.option("--no-smooth", is_flag=True, help="Straight segments instead of smooth curves.")
@vpype_cli.generator
def ctrace(
    image: str,
    dpi: Optional[float],
    threshold: Optional[int],
    adaptive: bool,
    invert: bool,
    simplify: Optional[float],
    no_smooth: bool,
) -> vp.LineCollection:
    """Trace a scanned line drawing (centre lines, one line per shape) with crawltrace."""
    try:
        drawing = crawltrace.trace(
            image,
            dpi=dpi,
            threshold=threshold,
            adaptive=adaptive,
            invert=invert,
            simplify=simplify,
            smooth=not no_smooth,
        )
    except crawltrace.CrawltraceError as problem:
        raise click.ClickException(str(problem)) from None
    return curves_to_lines(drawing)
