#!/usr/bin/env bash
# Installs what is missing, builds, and runs the main job on a sample made on
# the spot: a synthetic clip -> camera path -> haptic track (+ plots, eval).
set -euo pipefail
cd "$(dirname "$0")/.."
OUT=${1:-out/demo}

bash scripts/install_deps.sh
BUILD_DIR=build bash scripts/build.sh --target hapcine
HAPCINE=build/cli/hapcine
mkdir -p "$OUT"

echo "== 1/4 synth: rendering the paper's zoom-in clip with its ground truth"
$HAPCINE synth zoom_in -o "$OUT"
echo "== 2/4 estimate: camera path from the video alone"
$HAPCINE estimate "$OUT/zoom_in.mp4" -o "$OUT/zoom_in.est.camera.csv"
echo "== 3/4 eval: estimate against ground truth"
$HAPCINE eval --gt "$OUT/zoom_in.camera.csv" --est "$OUT/zoom_in.est.camera.csv"
echo "== 4/4 haptics: cinematic haptic track (+ MPEG-I .hjif) and a plot"
$HAPCINE haptics "$OUT/zoom_in.est.camera.csv" --model cinematic \
  -o "$OUT/zoom_in.cinematic.haptic.csv" --hjif "$OUT/zoom_in.cinematic.hjif"
$HAPCINE plot haptic "$OUT/zoom_in.cinematic.haptic.csv" -o "$OUT/zoom_in.cinematic" || true

echo
echo "Outputs in $OUT/:"
ls -1 "$OUT" | sed 's/^/  /'
