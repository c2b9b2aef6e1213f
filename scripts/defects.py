#!/usr/bin/env python3
"""Counts the defects of crawltrace's output on benchmark drawings, finer than "exact or not".

Usage: scripts/defects.py SPLIT_DIR... [--families animals,arches,...] [--out FILE] [--base FILE]

Each drawing of the given families in each split directory (made by `examples/make_bench`) is
traced with target/release/crawltrace (or $CRAWLTRACE_BIN) and four kinds of defect are counted:
  truth-far   stretches of the truth farther than the tolerance from every output path (grouped
              within 12 px), as `scripts/overlay.py` rings them;
  path-far    the same for the output's paths against the truth;
  path-count  |output paths - true curves|;
  open-count  |open output paths - open true curves|.
An animal with three broken feet counts three defects where the pass rate counts one failure, so
a rule that mends one mechanism shows even where the drawing still fails for another. The
distances are to any path (no matching), so a curve traced as two pieces counts in path-count,
not in truth-far. `--out` writes one line per drawing; `--base` compares with such a file and
lists the drawings whose counts changed. Default families: the touching-parts ones (issue 9).
Use it on development splits only (docs/benchmark.md). Needs Pillow (for overlay.py's reader).
"""
import argparse
import json
import math
import os
import subprocess
import sys
import tempfile
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from overlay import dense, polylines  # noqa: E402

ROOT = Path(__file__).resolve().parent.parent
GROUP_PX = 12.0
STEP_PX = 0.5


class Grid:
    """Points bucketed by cell, for nearest-point queries within a few pixels."""

    def __init__(self, points, cell):
        self.cell, self.buckets = cell, {}
        for p in points:
            self.buckets.setdefault((int(p[0] // cell), int(p[1] // cell)), []).append(p)

    def farther_than(self, p, distance):
        """Whether every point lies farther than `distance` (at most one cell) from `p`."""
        cx, cy = int(p[0] // self.cell), int(p[1] // self.cell)
        for dx in (-1, 0, 1):
            for dy in (-1, 0, 1):
                for q in self.buckets.get((cx + dx, cy + dy), ()):
                    if math.dist(p, q) <= distance:
                        return False
        return True


def groups(points):
    """How many groups the points make, each point within GROUP_PX of its group's first."""
    firsts = []
    for p in points:
        if all(math.dist(p, f) > GROUP_PX for f in firsts):
            firsts.append(p)
    return len(firsts)


def far(points, others, tolerance):
    grid = Grid(others, max(tolerance, 1.0))
    return [p for p in points if grid.farther_than(p, tolerance)]


def count(drawing, entry):
    truth_text = drawing.with_name(entry["truth"]).read_text()
    with tempfile.TemporaryDirectory() as tmp:
        traced = Path(tmp) / "out.svg"
        binary = os.environ.get("CRAWLTRACE_BIN", str(ROOT / "target/release/crawltrace"))
        subprocess.run([binary, "trace", str(drawing), "-o",
                        str(traced), "--force", "--quiet"], check=True)
        output_text = traced.read_text()
    truth, output = polylines(truth_text), polylines(output_text)

    def is_open(path):
        return not (path and path[-1] and path[-1][0] == path[-1][-1] and len(path[-1]) > 2)

    def points(paths):
        return [p for path in paths for line in path for p in dense(line, STEP_PX)]

    tolerance = entry["tolerance"]
    truth_points, output_points = points(truth), points(output)
    return [
        groups(far(truth_points, output_points, tolerance)) if output_points else len(truth),
        groups(far(output_points, truth_points, tolerance)),
        abs(len(output) - len(truth)),
        abs(sum(map(is_open, output)) - sum(map(is_open, truth))),
    ]


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("splits", nargs="+", type=Path)
    parser.add_argument("--families", default="animals,arches,meanders,spikes")
    parser.add_argument("--out", type=Path)
    parser.add_argument("--base", type=Path)
    args = parser.parse_args()
    families = set(args.families.split(","))
    jobs = []
    for split in args.splits:
        for line in (split / "manifest.jsonl").read_text().splitlines():
            entry = json.loads(line)
            if entry["family"] in families:
                jobs.append((f"{split.name} {entry['name']}", split / entry["image"], entry))
    with ThreadPoolExecutor(2) as pool:
        counts = list(pool.map(lambda job: count(job[1], job[2]), jobs))
    rows = {name: c for (name, _, _), c in zip(jobs, counts)}
    totals = [sum(c[k] for c in counts) for k in range(4)]
    print(f"{len(rows)} drawings: truth-far {totals[0]}, path-far {totals[1]}, "
          f"path-count {totals[2]}, open-count {totals[3]}, all {sum(totals)}")
    if args.out:
        args.out.write_text("".join(f"{name} {' '.join(map(str, c))}\n" for name, c in rows.items()))
    if args.base:
        base = {}
        for line in args.base.read_text().splitlines():
            *name, a, b, c, d = line.split()
            base[" ".join(name)] = [int(a), int(b), int(c), int(d)]
        for name, c in rows.items():
            if name in base and base[name] != c:
                print(f"{name}: {base[name]} -> {c}")


if __name__ == "__main__":
    main()
