#!/usr/bin/env bash
# Checks that a refactoring changed no output byte: rebuilds the release binary, runs it on every
# sample and compares the results byte for byte with reference outputs recorded earlier.
#
# Usage:
#   scripts/check-identical.sh --record [REFDIR]   # before the change: record the reference
#   scripts/check-identical.sh [REFDIR]            # after each step: compare with it
#
# REFDIR defaults to ${TMPDIR:-/tmp}/crawltrace-reference, outside the repository. What is run,
# for every image in samples/ (the 4000×3000 page included):
#   crawltrace trace IMG -o NAME.svg                      (default options)
#   crawltrace trace IMG -o NAME.points.svg --method points   (the robust point-set crawl)
#   crawltrace trace IMG -o NAME.paper.svg --method paper     (the paper's crawl)
#   crawltrace trace IMG -o NAME.straight.svg --no-smooth
# and once each:
#   crawltrace points samples/points/shapes.txt -o shapes.json          (JSON)
#   crawltrace points samples/points/shapes.txt -o shapes.svg           (SVG)
#   crawltrace points samples/points/shapes.txt -o shapes.dots.svg --show-points
#   crawltrace points samples/points/shapes.txt -o shapes.paper.json --method paper
#   crawltrace trace samples/face-scan.jpg -o debug.svg --debug debug/  (the stage pictures)
# Exit status: 0 when every file is identical (and none is missing or new), 1 otherwise.
set -euo pipefail
cd "$(dirname "$0")/.."

record=false
if [[ "${1:-}" == "--record" ]]; then
    record=true
    shift
fi
reference="${1:-${TMPDIR:-/tmp}/crawltrace-reference}"

cargo build --release --quiet --bin crawltrace
binary="$PWD/target/release/crawltrace"

outputs="$(mktemp -d)"
trap 'rm -rf "$outputs"' EXIT

for image in samples/*.png samples/*.jpg; do
    name="$(basename "${image%.*}")"
    "$binary" trace -q "$image" -o "$outputs/$name.svg"
    "$binary" trace -q "$image" -o "$outputs/$name.points.svg" --method points
    "$binary" trace -q "$image" -o "$outputs/$name.paper.svg" --method paper
    "$binary" trace -q "$image" -o "$outputs/$name.straight.svg" --no-smooth
done
points=samples/points/shapes.txt
"$binary" points "$points" -o "$outputs/shapes.json"
"$binary" points "$points" -o "$outputs/shapes.svg"
"$binary" points "$points" -o "$outputs/shapes.dots.svg" --show-points
"$binary" points "$points" -o "$outputs/shapes.paper.json" --method paper
"$binary" trace -q samples/face-scan.jpg -o "$outputs/debug.svg" --debug "$outputs/debug"

if $record; then
    rm -rf "$reference"
    mkdir -p "$reference"
    cp -r "$outputs/." "$reference/"
    echo "recorded $(find "$reference" -type f | wc -l) reference files in $reference"
    exit 0
fi

if [[ ! -d "$reference" ]]; then
    echo "no reference in $reference: record one first with --record" >&2
    exit 1
fi
# `diff -r` reports files that differ and files on one side only; `-q` names them without content.
if diff -rq "$reference" "$outputs"; then
    echo "identical: $(find "$outputs" -type f | wc -l) files match $reference"
else
    echo "outputs differ from $reference (listed above)" >&2
    exit 1
fi
