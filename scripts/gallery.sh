#!/usr/bin/env bash
# Regenerates the README's gallery pictures in docs/gallery/: traces some samples with `crawltrace trace`
# and rasterizes the results with `crawltrace render`; also reconstructs the sample point set.
# Usage: scripts/gallery.sh   (from anywhere; builds the release binary first)
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release --quiet
crawltrace=target/release/crawltrace
out=docs/gallery
mkdir -p "$out"
for name in face-scan letters-clean squares-triangles-thick spiral-waves-thin silhouettes-scan weather-alpha \
  cat-fork-clean; do
  input=samples/"$name".png
  [ -f "$input" ] || input=samples/"$name".jpg
  "$crawltrace" trace "$input" -o "$out/$name.svg" --quiet
  "$crawltrace" render "$out/$name.svg" -o "$out/$name-traced.png"
done
# Two drawings of the generalization benchmark (made by `make_bench --seed 1`, kept as inputs in
# docs/gallery/bench-*.png): a silhouette whose leg's foot is a pen lift, and a lasso.
for name in bench-animals-clean-000 bench-meanders-thick-000; do
  "$crawltrace" trace "$out/$name.png" -o "$out/$name.svg" --quiet
  "$crawltrace" render "$out/$name.svg" -o "$out/$name-traced.png"
done
if [ -f samples/points/shapes.txt ]; then
  "$crawltrace" points samples/points/shapes.txt -o "$out/points.svg" --show-points
  "$crawltrace" render "$out/points.svg" -o "$out/points-reconstructed.png" --scale 0.5
fi
echo "gallery written to $out/"
