#!/usr/bin/env bash
# Speed of `hapcine estimate` against the decoding floor (issue 3, "Speed to
# reach"), and a small speed-against-error table. docs/estimate.md "Speed".
#
#   bash bench/speed.sh ratio [--build DIR] [--runs N] [--clip F] [-- ESTIMATE_OPTIONS...]
#     Decoding alone (`ffmpeg -nostdin -threads T -i F -f null -`) and
#     `hapcine estimate F --decode-threads T [ESTIMATE_OPTIONS]`, N runs each
#     (default 3), interleaved; prints wall, CPU (user+sys) and peak RSS per
#     run, their medians and the wall and CPU ratios estimate / decode.
#     Default clip: the 1920x1080 traveling of bench/run.sh.
#   bash bench/speed.sh sweep [--build DIR] [--clips DIR] [--out DIR] [--settings FILE]
#     Every `<clip>.mp4` + `<clip>.camera.csv` of DIR (default /tmp/d/clips)
#     at each setting (lines "label|options" of FILE, default below): CPU
#     seconds and rotation mean error (deg, `hapcine eval`) per clip, then
#     one summary line per setting. Clips run one at a time.
#
# CPU time is the steadier figure on a shared machine; wall time is what the
# issue's target is stated in. Both are printed.
set -uo pipefail
ROOT=$(cd "$(dirname "$0")/.." && pwd)
MODE=${1:-}
[ -n "$MODE" ] && shift
BUILD="$ROOT/build" RUNS=3 THREADS=2
CLIP=/tmp/hapcine-bench/clips/1080p/traveling.mp4
CLIPS=/tmp/d/clips OUT=/tmp/hapcine-speed SETTINGS=""
EXTRA=()
while [ $# -gt 0 ]; do
  case $1 in
    --build) BUILD=$2; shift ;;
    --runs) RUNS=$2; shift ;;
    --clip) CLIP=$2; shift ;;
    --clips) CLIPS=$2; shift ;;
    --out) OUT=$2; shift ;;
    --settings) SETTINGS=$2; shift ;;
    --threads) THREADS=$2; shift ;;
    --) shift; EXTRA=("$@"); break ;;
    -h|--help) sed -n 2,19p "$0"; exit 0 ;;
    *) echo "speed.sh: unknown argument '$1' (see --help)" >&2; exit 2 ;;
  esac
  shift
done
case $BUILD in /*) ;; *) BUILD="$ROOT/$BUILD" ;; esac
HC="$BUILD/cli/hapcine"
[ -x "$HC" ] || { echo "speed.sh: $HC not built (cmake --build $BUILD --target hapcine)" >&2; exit 1; }
for tool in ffmpeg /usr/bin/time; do
  command -v $tool >/dev/null || { echo "speed.sh: '$tool' not found" >&2; exit 1; }
done
mkdir -p "$OUT"
# The build's own source tree (a --build of another checkout or worktree), for the
# commit line: its HEAD when this runs, and when the binary was linked.
SRC=$(sed -n 's/^CMAKE_HOME_DIRECTORY:INTERNAL=//p' "$BUILD/CMakeCache.txt" 2>/dev/null)
[ -d "$SRC" ] || SRC=$ROOT
COMMIT="$(git -C "$SRC" rev-parse --short HEAD 2>/dev/null) of $SRC, binary built $(date -u -r "$HC" '+%F %H:%M UTC')"

# Runs a command under /usr/bin/time; prints "wall cpu rss_mb".
timed() {
  local t="$OUT/time.$$"
  /usr/bin/time -o "$t" -f "%e %U %S %M" "$@" >/dev/null 2>"$OUT/stderr.$$" || {
    echo "speed.sh: failed: $* ($(tail -1 "$OUT/stderr.$$"))" >&2; rm -f "$t"; return 1; }
  awk '{printf "%.2f %.2f %.0f\n", $1, $2 + $3, $4 / 1024}' "$t"
  rm -f "$t" "$OUT/stderr.$$"
}

median() { sort -g | awk '{v[NR]=$1} END {print (NR % 2) ? v[(NR+1)/2] : (v[NR/2] + v[NR/2+1]) / 2}'; }

ratio() {
  [ -f "$CLIP" ] || { echo "speed.sh: no clip $CLIP (bench/run.sh renders it)" >&2; exit 1; }
  echo "clip: $CLIP ($(ffprobe -v error -select_streams v:0 -show_entries stream=width,height,nb_frames -of csv=p=0 "$CLIP"))"
  echo "decode:   ffmpeg -nostdin -threads $THREADS -i CLIP -f null -"
  echo "estimate: hapcine estimate CLIP -o OUT --quiet --decode-threads $THREADS ${EXTRA[*]}"
  echo "commit: $COMMIT, load: $(cut -d' ' -f1-3 /proc/loadavg)"
  printf "%-9s %4s %8s %8s %8s\n" what run wall_s cpu_s rss_mb
  local dec=() est=()
  for ((i = 1; i <= RUNS; i++)); do
    local d e
    d=$(timed ffmpeg -nostdin -v error -threads "$THREADS" -i "$CLIP" -f null -) || exit 1
    e=$(timed "$HC" estimate "$CLIP" -o "$OUT/ratio.camera.csv" --quiet \
          --decode-threads "$THREADS" "${EXTRA[@]}") || exit 1
    printf "%-9s %4d %8s %8s %8s\n" decode $i $d
    printf "%-9s %4d %8s %8s %8s\n" estimate $i $e
    dec+=("$d") est+=("$e")
  done
  local col dw dc ew ec er
  col() { printf "%s\n" "${@:2}" | awk -v c="$1" '{print $c}' | median; }
  dw=$(col 1 "${dec[@]}") dc=$(col 2 "${dec[@]}")
  ew=$(col 1 "${est[@]}") ec=$(col 2 "${est[@]}") er=$(col 3 "${est[@]}")
  echo "median decode wall ${dw} s, cpu ${dc} s; estimate wall ${ew} s, cpu ${ec} s, peak RSS ${er} MB"
  awk -v ew="$ew" -v dw="$dw" -v ec="$ec" -v dc="$dc" \
    'BEGIN {printf "ratio estimate/decode: wall %.2fx, cpu %.2fx (target: wall <= 1.5x)\n", ew / dw, ec / dc}'
}

sweep() {
  local settings=("defaults|")
  if [ -n "$SETTINGS" ]; then
    mapfile -t settings < <(grep -v '^#' "$SETTINGS" | grep .)
  else
    settings+=("--fast|--fast"
               "--skip-nonref|--skip-nonref"
               "--draft|--draft"
               "640px|--max-side 640"
               "300 tracks|--tracks 300"
               "KLT window 15|--klt-window 15"
               "BA window 60|--window 60")
  fi
  local clips=()
  for f in "$CLIPS"/*.camera.csv; do clips+=("$(basename "$f" .camera.csv)"); done
  [ ${#clips[@]} -gt 0 ] || { echo "speed.sh: no <clip>.camera.csv in $CLIPS" >&2; exit 1; }
  echo "commit: $COMMIT, clips: $CLIPS (${#clips[@]}), load: $(cut -d' ' -f1-3 /proc/loadavg)"
  local summary=()
  for s in "${settings[@]}"; do
    local label=${s%%|*} opts=${s#*|} tag
    tag=$(echo "$label" | tr -c 'A-Za-z0-9\n' _)
    local cpu_total=0 rots=()
    echo "## $label ($opts)"
    printf "%-22s %7s %8s %9s\n" clip cpu_s wall_s rot_mean
    for c in "${clips[@]}"; do
      local est="$OUT/$c.$tag.camera.csv" t rot
      # shellcheck disable=SC2086
      t=$(timed "$HC" estimate "$CLIPS/$c.mp4" -o "$est" --quiet $opts) || { rots+=(nan); continue; }
      rot=$("$HC" eval --gt "$CLIPS/$c.camera.csv" --est "$est" |
            awk '/^rotation error \(deg\)/ {print $4}')
      printf "%-22s %7s %8s %9s\n" "$c" "$(echo $t | cut -d' ' -f2)" "$(echo $t | cut -d' ' -f1)" "$rot"
      cpu_total=$(awk -v a="$cpu_total" -v b="$(echo $t | cut -d' ' -f2)" 'BEGIN {print a + b}')
      rots+=("$rot")
    done
    local med max
    med=$(printf "%s\n" "${rots[@]}" | median)
    max=$(printf "%s\n" "${rots[@]}" | sort -g | tail -1)
    summary+=("$(printf "| %s | \`%s\` | %.1f | %.3f | %.3f |" "$label" "$opts" "$cpu_total" "$med" "$max")")
  done
  echo
  echo "| setting | options | CPU s, all clips | rot mean, median over clips (deg) | worst clip (deg) |"
  echo "|---|---|---|---|---|"
  printf "%s\n" "${summary[@]}"
}

case $MODE in
  ratio) ratio ;;
  sweep) sweep ;;
  *) sed -n 2,19p "$0"; exit 2 ;;
esac
