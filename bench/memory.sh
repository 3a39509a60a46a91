#!/usr/bin/env bash
# Peak RSS of the file readers and writers against the size of what they read
# (docs/benchmarks.md, "Memory of the readers and of a two-hour film"):
#   - hapcine haptics --hjif on a two-hour camera path (24 fps, 172 800 rows;
#     its track is 7.2 M samples at 1 kHz), and without --hjif;
#   - the haptic-track reader on that track (hapcine_read_bench);
#   - the camera-path reader on a large path written as hapcine writes it,
#     and on one of minimal rows (ten short fields), and `hapcine convert
#     --to-tum` on the large one (reader and writer).
# The inputs come from bench/long_camera_path.py. Runs alone (a few minutes);
# bench/run.sh does not run it.
#
#   bash bench/memory.sh [--quick] [--camera-path] [--out DIR] [--build DIR] [--hapcine EXE]
#     --quick        a 10-minute film and 1 M-row paths (checks the script)
#     --camera-path  only the two camera-path reader rows (after a change to CameraFrame)
#     --out DIR      inputs, outputs and memory.md (default /tmp/hapcine-memory[-quick])
#     --build DIR    build folder (default build); hapcine and hapcine_read_bench
#                    are built there if needed
#     --hapcine EXE  measure this hapcine instead (e.g. an older build, for a comparison)
set -uo pipefail
ROOT=$(cd "$(dirname "$0")/.." && pwd)
MODE=full ONLY_CAMERA=0 OUT="" BUILD="$ROOT/build" HC=""
while [ $# -gt 0 ]; do
  case $1 in
    --quick) MODE=quick ;;
    --out) OUT=$2; shift ;;
    --build) BUILD=$2; shift ;;
    --hapcine) HC=$2; shift ;;
    --camera-path) ONLY_CAMERA=1 ;;
    -h|--help) sed -n 2,20p "$0"; exit 0 ;;
    *) echo "memory.sh: unknown argument '$1' (see --help)" >&2; exit 2 ;;
  esac
  shift
done
[ -n "$OUT" ] || OUT=/tmp/hapcine-memory$([ $MODE = quick ] && echo -quick)
command -v /usr/bin/time >/dev/null || { echo "memory.sh: /usr/bin/time not found" >&2; exit 1; }
cmake --build "$BUILD" -j2 --target hapcine hapcine_read_bench >/dev/null ||
  { echo "memory.sh: build failed" >&2; exit 1; }
[ -n "$HC" ] || HC="$BUILD/cli/hapcine"
READ="$BUILD/bench/hapcine_read_bench"
if [ $MODE = quick ]; then FILM_S=600 BIG_ROWS=1000000; else FILM_S=7200 BIG_ROWS=10000000; fi
mkdir -p "$OUT"
GEN="python3 $ROOT/bench/long_camera_path.py"
film="$OUT/film-${FILM_S}s.camera.csv"
full="$OUT/full-${BIG_ROWS}.camera.csv"     # as hapcine writes it: every column
minimal="$OUT/minimal-${BIG_ROWS}.camera.csv"
[ -f "$film" ] || [ $ONLY_CAMERA = 1 ] || $GEN "$FILM_S" 24 "$film"
# A fifth of the rows in full: about the size of the minimal file.
[ -f "$full" ] || $GEN "$(awk "BEGIN{print $BIG_ROWS / 5 / 24}")" 24 "$full"
[ -f "$minimal" ] || $GEN "$(awk "BEGIN{print $BIG_ROWS / 24}")" 24 "$minimal" --minimal

table="$OUT/memory.md"
echo "| what | input | input MB | rows | wall s | peak RSS MB | RSS / input size | exit |" >"$table"
echo "|---|---|---|---|---|---|---|---|" >>"$table"
# measure LABEL INPUT -- command...
measure() {
  local label=$1 input=$2
  shift 3
  local tf="$OUT/time.txt"
  /usr/bin/time -f "%e %M" -o "$tf" "$@" >"$OUT/last.log" 2>&1
  local rc=$? wall rss_kb rows
  read -r wall rss_kb <"$tf"
  rows=$(grep -vc '^#' "$input")
  rows=$((rows - 1))
  awk -v l="$label" -v f="$(basename "$input")" -v b="$(stat -c %s "$input")" -v n="$rows" \
    -v w="$wall" -v k="$rss_kb" -v rc="$rc" 'BEGIN {
      printf "| %s | `%s` | %.0f | %d | %s | %.0f | %.2f | %s |\n", l, f, b / 1e6, n, w,
             k * 1024 / 1e6, k * 1024 / b, rc }' >>"$table"
  echo "[$(date +%H:%M:%S)] $label: rc $rc, ${wall} s, $((rss_kb * 1024 / 1000000)) MB peak RSS"
}
if [ $ONLY_CAMERA = 0 ]; then
  measure "haptics --hjif (cinematic)" "$film" -- \
    "$HC" haptics "$film" -o "$OUT/film.haptic.csv" --hjif "$OUT/film.hjif"
  measure "haptics (cinematic, no --hjif)" "$film" -- "$HC" haptics "$film" -o "$OUT/film.haptic.csv"
  measure "haptic-track reader" "$OUT/film.haptic.csv" -- "$READ" haptic "$OUT/film.haptic.csv"
fi
measure "camera-path reader" "$full" -- "$READ" camera "$full"
measure "camera-path reader, minimal rows" "$minimal" -- "$READ" camera "$minimal"
[ $ONLY_CAMERA = 1 ] || measure "convert --to-tum" "$full" -- "$HC" convert "$full" --to-tum "$OUT/full.tum.txt"
{
  echo
  echo "command: \`bash bench/memory.sh$([ $MODE = quick ] && echo " --quick")$([ $ONLY_CAMERA = 1 ] && echo " --camera-path")\`, $(date -u '+%Y-%m-%d %H:%M UTC'),"
  echo "hapcine $("$HC" --version 2>/dev/null | head -n 1) commit $(git -C "$ROOT" rev-parse --short HEAD 2>/dev/null)," \
       "$(nproc) cores, load average $(cut -d' ' -f1-3 /proc/loadavg)"
} >>"$table"
cat "$table"
