#!/usr/bin/env python3
"""Draws a benchmark drawing's truth over crawltrace's output, to see where a failure is.

Usage: scripts/overlay.py DRAWING OUT.png [--crop X0,Y0,X1,Y1] [--scale S] [--tolerance PX]

DRAWING is a benchmark drawing or sample (its `.truth.svg` must lie beside it). The drawing is
traced with target/release/crawltrace, then drawn faint, the output's paths in blue (each path in
its own shade), the truth in red, and every point of the truth farther than the tolerance from the
output ringed in orange; the rings' groups are printed as `x,y worst-distance`. The tolerance is
read from the truth (pen width / 2 + jitter + 2 px, as `bench_score` has it) unless given.
Needs Pillow (`pip install pillow`). Use it on development splits only (docs/benchmark.md).
"""
import argparse
import bisect
import math
import re
import subprocess
import sys
import tempfile
from pathlib import Path

from PIL import Image, ImageDraw


def polylines(svg_text):
    """The paths of an SVG as lists of polylines (cubics flattened into 8 pieces)."""
    result = []
    for d in re.findall(r' d="([^"]*)"', svg_text):
        tokens = re.findall(r"[A-Za-z]|-?\d+\.?\d*(?:e-?\d+)?", d)
        lines, line, at, command, i = [], [], None, None, 0
        while i < len(tokens):
            if tokens[i].isalpha():
                command = tokens[i]
                i += 1
                if command in "Zz" and line:
                    line.append(line[0])
                continue
            numbers = []
            for t in tokens[i:i + 6]:
                if t.isalpha():
                    break
                numbers.append(float(t))
            if command in "ML" and len(numbers) < 2:
                i += len(numbers) or 1
            elif command == "M":
                if line:
                    lines.append(line)
                at = (numbers[0], numbers[1])
                line, command, i = [at], "L", i + 2
            elif command == "L":
                at = (numbers[0], numbers[1])
                line.append(at)
                i += 2
            elif command == "C" and len(numbers) == 6:
                p1, p2, p3 = numbers[0:2], numbers[2:4], numbers[4:6]
                for k in range(1, 9):
                    t, u = k / 8, 1 - k / 8
                    line.append(tuple(u ** 3 * a + 3 * u * u * t * b + 3 * u * t * t * c + t ** 3 * e
                                      for a, b, c, e in zip(at, p1, p2, p3)))
                at = tuple(p3)
                i += 6
            else:
                i += 1  # a command this reader does not draw (h, v, arcs): skip its numbers
        if line:
            lines.append(line)
        result.append(lines)
    return result


def dense(line, step):
    points = []
    for a, b in zip(line, line[1:]):
        n = max(1, int(math.dist(a, b) / step))
        points.extend((a[0] + (b[0] - a[0]) * k / n, a[1] + (b[1] - a[1]) * k / n) for k in range(n))
    return points + line[-1:]


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("drawing", type=Path)
    parser.add_argument("out", type=Path)
    parser.add_argument("--crop", help="X0,Y0,X1,Y1 in the drawing's pixels")
    parser.add_argument("--scale", type=float, default=3.0)
    parser.add_argument("--tolerance", type=float)
    args = parser.parse_args()
    truth_path = args.drawing.with_suffix(".truth.svg")
    truth = truth_path.read_text()
    root = Path(__file__).resolve().parent.parent
    with tempfile.TemporaryDirectory() as tmp:
        traced = Path(tmp) / "out.svg"
        subprocess.run([str(root / "target/release/crawltrace"), "trace", str(args.drawing), "-o",
                        str(traced), "--force", "--quiet"], check=True)
        output = traced.read_text()
    tolerance = args.tolerance
    if tolerance is None:
        # Benchmark truths carry data-pen; the samples' truths give the pen as the stroke width.
        pen_match = (re.search(r'data-pen="([\d.]+)"', truth)
                     or re.search(r'stroke-width="([\d.]+)"', truth))
        pen = float(pen_match.group(1))
        jitter = float((re.search(r'data-jitter="([\d.]+)"', truth) or [0, 0])[1])
        tolerance = pen / 2 + jitter + 2
    image = Image.open(args.drawing).convert("L")
    box = tuple(int(v) for v in args.crop.split(",")) if args.crop else (0, 0) + image.size
    scale = args.scale
    canvas = image.crop(box).resize((int((box[2] - box[0]) * scale), int((box[3] - box[1]) * scale)))
    canvas = Image.eval(canvas, lambda v: 200 + v * 55 // 255).convert("RGB")
    draw = ImageDraw.Draw(canvas)
    to_canvas = lambda p: ((p[0] - box[0]) * scale, (p[1] - box[1]) * scale)
    shades = [(0, 0, 255), (0, 140, 0), (190, 0, 190), (0, 140, 140), (140, 90, 0)]
    out_paths = polylines(output)
    for k, lines in enumerate(out_paths):
        for line in lines:
            if len(line) > 1:
                draw.line([to_canvas(p) for p in line], fill=shades[k % len(shades)], width=2)
    for lines in polylines(truth):
        for line in lines:
            if len(line) > 1:
                draw.line([to_canvas(p) for p in line], fill=(255, 0, 0), width=1)
    # Truth points farther than the tolerance from every output path.
    near = sorted(p for lines in out_paths for line in lines for p in dense(line, 0.5))
    xs = [p[0] for p in near]
    def distance(p, reach=3 * tolerance + 10):
        i, j = bisect.bisect_left(xs, p[0] - reach), bisect.bisect_right(xs, p[0] + reach)
        return min((math.dist(p, q) for q in near[i:j]), default=math.inf)
    groups = []
    for lines in polylines(truth):
        for line in lines:
            for p in dense(line, 1.0):
                d = distance(p)
                if d <= tolerance:
                    continue
                r = 1.5
                draw.ellipse([to_canvas((p[0] - r, p[1] - r)), to_canvas((p[0] + r, p[1] + r))],
                             outline=(255, 120, 0))
                group = next((g for g in groups if math.dist(g[0], p) < 10), None)
                if group:
                    group[1] = max(group[1], d)
                else:
                    groups.append([p, d])
    canvas.save(args.out)
    print(f"tolerance {tolerance:.2f} px; truth farther than that from the output:")
    for p, d in groups:
        print(f"  {p[0]:.0f},{p[1]:.0f} {d:.1f} px" if d != math.inf else f"  {p[0]:.0f},{p[1]:.0f} no path")


if __name__ == "__main__":
    sys.exit(main())
