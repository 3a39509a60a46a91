#!/usr/bin/env bash
# Extract speed on generated H.264 clips: ffmpeg's own decode time, our
# decode-only time (decode + swscale to the working size, gray + BGR), and
# decode + shot detection + KLT tracking. 2 decode threads, like the target
# machine. Also prints CPU seconds (user+sys), steadier on a busy machine.
#   bench/extract_speed.sh [build_dir]   (default: build)
set -euo pipefail
BUILD=${1:-build}
BENCH="$BUILD/extract/hapcine_extract_bench"
[ -x "$BENCH" ] || { echo "build hapcine_extract_bench first ($BENCH)"; exit 1; }
TMP=${TMPDIR:-/tmp}/hapcine_extract_speed
mkdir -p "$TMP"
for size in 1280x720 1920x1080; do
  clip="$TMP/testsrc2_$size.mp4"
  # The lavfi test pattern with moving parts (cheap to generate).
  [ -f "$clip" ] || ffmpeg -nostdin -loglevel error -y -f lavfi \
      -i "testsrc2=size=$size:rate=24" -t 20 -c:v libx264 -pix_fmt yuv420p "$clip"
  echo "== $clip"
  # Wall times are only meaningful on an idle machine; CPU (user+sys) is the
  # more stable comparison on a shared one.
  /usr/bin/time -f "  ffmpeg -threads 2 -f null: %e s wall, %U+%S s cpu" \
      ffmpeg -nostdin -loglevel error -threads 2 -i "$clip" -f null -
  /usr/bin/time -f "  %e s wall, %U+%S s cpu" "$BENCH" "$clip" --threads 2 --decode-only
  /usr/bin/time -f "  %e s wall, %U+%S s cpu" "$BENCH" "$clip" --threads 2
done
