#!/usr/bin/env bash
# One command for docs/benchmarks.md: renders the synthetic clips it needs
# (hapcine synth, cached in OUT/clips), then times and scores on the same
# clips in the same run: hapcine estimate at several settings, COLMAP 3.8,
# OpenCV stitching (rotation + focal) and OpenCV videostab (2-D motion); the
# decoding floor (720p and 1080p H.264); peak RSS against clip length; the
# 1 kHz haptic loop on simulated Falcons. Writes OUT/report.md + OUT/fig/.
#
#   bash bench/run.sh [--quick] [--out DIR] [--build DIR] [--clips DIR] [--publish]
#     --quick     small clips and few runs: checks the harness (< 3 min)
#     --out DIR   results folder (default /tmp/hapcine-bench[-quick])
#     --build DIR build folder (default build); the targets are built if needed
#     --clips DIR take already rendered 1280x720 presets (<name>.mp4 +
#                 <name>.camera.csv) from DIR instead of rendering them
#     --publish   copy the report into docs/benchmarks.md (between the
#                 GENERATED markers) and the figures into docs/benchmarks/
#     --report-only  measure nothing: redraw the report of the run in OUT
#                 (e.g. with --publish after checking it)
set -uo pipefail
ROOT=$(cd "$(dirname "$0")/.." && pwd)
MODE=full OUT="" BUILD="$ROOT/build" SEED="" PUBLISH=0 REPORT_ONLY=0
while [ $# -gt 0 ]; do
  case $1 in
    --quick) MODE=quick ;;
    --out) OUT=$2; shift ;;
    --build) BUILD=$2; shift ;;
    --clips) SEED=$2; shift ;;
    --publish) PUBLISH=1 ;;
    --report-only) REPORT_ONLY=1 ;;
    -h|--help) sed -n 2,18p "$0"; exit 0 ;;
    *) echo "run.sh: unknown argument '$1' (see --help)" >&2; exit 2 ;;
  esac
  shift
done
[ -n "$OUT" ] || OUT=/tmp/hapcine-bench$([ $MODE = quick ] && echo -quick)
case $BUILD in /*) ;; *) BUILD="$ROOT/$BUILD" ;; esac
for tool in ffmpeg ffprobe colmap /usr/bin/time timeout; do
  command -v $tool >/dev/null || { echo "run.sh: '$tool' not found (scripts/install_deps.sh installs it)" >&2; exit 1; }
done

# ---- Build (timed apart from the run) ----
# The commit measured is the one built (others may commit during the run).
commit=$(git -C "$ROOT" rev-parse --short HEAD 2>/dev/null || echo unknown)
dirty=$(git -C "$ROOT" status --porcelain --untracked-files=no 2>/dev/null | grep -c . || true)
build_start=$(date +%s)
cmake -S "$ROOT" -B "$BUILD" -DCMAKE_BUILD_TYPE=Release >/dev/null || exit 1
targets="hapcine hapcine_loop_bench hapcine_peer_stitch hapcine_peer_videostab hapcine_path_fill hapcine_bench_report"
[ $REPORT_ONLY = 1 ] && targets=hapcine_bench_report
# shellcheck disable=SC2086
cmake --build "$BUILD" -j2 --target $targets >/dev/null || { echo "run.sh: build failed" >&2; exit 1; }
build_s=$(( $(date +%s) - build_start ))
HC="$BUILD/cli/hapcine"

# ---- Plan ----
if [ $MODE = quick ]; then
  W=640 H=360 DUR=3
  CLIPS=(tilting zoom_in traveling)
  SWEEP_CLIPS=(tilting zoom_in traveling)
  SETTINGS=("320px 150tr w60|--max-side 320 --tracks 150 --window 60" "960px 600tr w120 (default)|")
  STITCH_CLIPS=(tilting zoom_in)
  COLMAP_CLIPS=(traveling) COLMAP_STEP=3 COLMAP_SIDE=320 COLMAP_TIMEOUT=60
  FLOOR_CLIP=traveling FLOOR_1080=0
  MEM_MINUTES=(0.5) MEM_FPS=6
  LOOP_S=2
else
  W=1280 H=720 DUR=7
  CLIPS=(crane_shot dutch_angle arcing traveling tilting zoom_in vertigo
         slow_pan whip_pan handheld_shake telephoto_zoom_pan dolly_zoom_parallax low_texture
         noise_compression hard_cut fade_to_black static_camera)
  # The default setting runs on every clip, the sweep over settings on the
  # seven Table 1 clips.
  SWEEP_CLIPS=(crane_shot dutch_angle arcing traveling tilting zoom_in vertigo)
  SETTINGS=("480px 200tr w60|--max-side 480 --tracks 200 --window 60"
            "640px 300tr w120|--max-side 640 --tracks 300"
            "960px 600tr w120 (default)|"
            "1280px 1000tr w240|--max-side 0 --tracks 1000 --window 240")
  # The clips a rotation-and-focal model can explain (no camera translation,
  # apart from the 1.5 cm of handheld_shake and the second shot of hard_cut).
  STITCH_CLIPS=(dutch_angle tilting zoom_in slow_pan whip_pan handheld_shake telephoto_zoom_pan
                low_texture hard_cut fade_to_black static_camera)
  # COLMAP needs translation to initialise: the Table 1 clips that move and
  # the strong dolly zoom, plus one rotation clip to show the failure.
  # Every 6th frame at 480 px.
  COLMAP_CLIPS=(crane_shot arcing traveling vertigo dolly_zoom_parallax tilting)
  COLMAP_STEP=6 COLMAP_SIDE=480 COLMAP_TIMEOUT=240
  FLOOR_CLIP=traveling FLOOR_1080=1
  MEM_MINUTES=(1 10 60) MEM_FPS=3
  LOOP_S=10
fi
mkdir -p "$OUT/clips" "$OUT/est" "$OUT/eval" "$OUT/logs" "$OUT/fig"
RUNS="$OUT/runs.tsv"
log() { echo "[$(date +%H:%M:%S)] $*"; }
if [ $REPORT_ONLY = 0 ]; then
printf 'group\ttool\tsetting\tclip\trc\twall_s\tuser_s\tsys_s\tmaxrss_kb\tframes\teval_json\tnote\n' >"$RUNS"
run_start=$(date +%s)
load_start=$(cut -d' ' -f1-3 /proc/loadavg)

# ---- Clips (rendered unless cached or seeded) ----
render_start=$(date +%s)
missing=()
for c in "${CLIPS[@]}"; do
  if [ ! -f "$OUT/clips/$c.mp4" ] && [ -n "$SEED" ] && [ $MODE = full ] && [ -f "$SEED/$c.mp4" ]; then
    ln -s "$SEED/$c.mp4" "$OUT/clips/$c.mp4"; ln -s "$SEED/$c.camera.csv" "$OUT/clips/$c.camera.csv"
  fi
  [ -f "$OUT/clips/$c.mp4" ] && [ -f "$OUT/clips/$c.camera.csv" ] || missing+=("$c")
done
if [ ${#missing[@]} -gt 0 ]; then
  log "rendering ${missing[*]} (${W}x$H, $DUR s)"
  "$HC" synth "${missing[@]}" -o "$OUT/clips" --width $W --height $H --duration-s $DUR -j2 >"$OUT/logs/synth.log" 2>&1 ||
    { echo "run.sh: synth failed, see $OUT/logs/synth.log" >&2; exit 1; }
fi
if [ $FLOOR_1080 = 1 ] && [ ! -f "$OUT/clips/1080p/$FLOOR_CLIP.mp4" ]; then
  log "rendering $FLOOR_CLIP at 1920x1080"
  "$HC" synth $FLOOR_CLIP -o "$OUT/clips/1080p" --width 1920 --height 1080 -j2 >"$OUT/logs/synth1080.log" 2>&1 ||
    { echo "run.sh: synth failed, see $OUT/logs/synth1080.log" >&2; exit 1; }
fi
render_s=$(( $(date +%s) - render_start ))
frames_of() { ffprobe -v error -count_packets -select_streams v:0 -show_entries stream=nb_read_packets -of csv=p=0 "$1"; }

# record GROUP TOOL SETTING CLIP FRAMES EST_CSV GT_CSV -- command...
# Times the command with /usr/bin/time, scores EST_CSV against GT_CSV with
# `hapcine eval --json` when both exist, appends a row to runs.tsv.
record() {
  local group=$1 tool=$2 setting=$3 clip=$4 frames=$5 est=$6 gt=$7
  shift 8
  local slug; slug=$(echo "$group-$tool-$setting-$clip" | tr -c 'A-Za-z0-9_.-' '_')
  local tf="$OUT/logs/$slug.time" lf="$OUT/logs/$slug.log" ev=""
  rm -f "$est"
  /usr/bin/time -f "%e %U %S %M" -o "$tf" "$@" >"$lf" 2>&1
  local rc=$?
  local wall user sys rss
  read -r wall user sys rss < <(tail -n 1 "$tf")
  if [ $rc -eq 0 ] && [ -n "$gt" ] && [ -f "$est" ]; then
    ev="eval/$slug.json"
    "$HC" eval --gt "$gt" --est "$est" --json -o "$OUT/$ev" >/dev/null 2>>"$lf" || ev=""
  fi
  local note; note=$(grep -v '^\s*$' "$lf" | tail -n 1 | tr '\t\r' '  ' | cut -c1-200)
  printf '%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\n' "$group" "$tool" "$setting" "$clip" "$rc" \
    "$wall" "$user" "$sys" "$rss" "$frames" "$ev" "$note" >>"$RUNS"
  log "$tool $setting $clip: rc=$rc ${wall}s"
}

# ---- Accuracy and speed on the synth clips ----
in_list() { local x=$1; shift; for y in "$@"; do [ "$x" = "$y" ] && return 0; done; return 1; }
for c in "${CLIPS[@]}"; do
  v="$OUT/clips/$c.mp4" gt="$OUT/clips/$c.camera.csv"
  n=$(frames_of "$v")
  for s in "${SETTINGS[@]}"; do
    name=${s%%|*} args=${s#*|}
    [[ $name == *default* ]] || in_list "$c" "${SWEEP_CLIPS[@]}" || continue
    est="$OUT/est/$c.hapcine-$(echo "$name" | tr -c 'A-Za-z0-9' '_').camera.csv"
    # shellcheck disable=SC2086
    record accuracy hapcine "$name" "$c" "$n" "$est" "$gt" -- "$HC" estimate "$v" -o "$est" -q $args
  done
  est="$OUT/est/$c.videostab.camera.csv"
  record accuracy opencv-videostab "" "$c" "$n" "$est" "$gt" -- \
    "$BUILD/bench/hapcine_peer_videostab" "$v" -o "$est" --max-side 640
  if in_list "$c" "${STITCH_CLIPS[@]}"; then
    est="$OUT/est/$c.stitching.camera.csv"
    record accuracy opencv-stitching "" "$c" "$n" "$est" "$gt" -- \
      "$BUILD/bench/hapcine_peer_stitch" "$v" -o "$est" --max-side 640 --step 8
  fi
  if in_list "$c" "${COLMAP_CLIPS[@]}"; then
    est="$OUT/est/$c.colmap.camera.csv"
    record accuracy colmap "1/$COLMAP_STEP frames ${COLMAP_SIDE}px" "$c" "$n" "$est" "$gt" -- \
      timeout $COLMAP_TIMEOUT "$ROOT/bench/colmap_peer.sh" "$v" "$est" $COLMAP_STEP $COLMAP_SIDE "$BUILD"
  fi
done

# ---- Decoding floor: estimate time over decode-only time ----
floor() {  # label video
  local n; n=$(frames_of "$2")
  record decode ffmpeg "$1" "$(basename "$2")" "$n" "" "" -- ffmpeg -nostdin -loglevel error -threads 2 -i "$2" -f null -
  record decode hapcine "$1" "$(basename "$2")" "$n" "$OUT/est/floor-$1.camera.csv" "" -- \
    "$HC" estimate "$2" -o "$OUT/est/floor-$1.camera.csv" -q
  record decode hapcine "$1 --draft" "$(basename "$2")" "$n" "$OUT/est/floor-$1-draft.camera.csv" "" -- \
    "$HC" estimate "$2" -o "$OUT/est/floor-$1-draft.camera.csv" -q --draft
}
floor "${H}p" "$OUT/clips/$FLOOR_CLIP.mp4"
[ $FLOOR_1080 = 1 ] && floor 1080p "$OUT/clips/1080p/$FLOOR_CLIP.mp4"

# ---- Memory against clip length: one clip looped ----
# The source is shrunk to 320x180 at MEM_FPS frames/s and estimated at
# --max-side 320 --tracks 150, so an hour fits the time budget; every loop
# is a hard cut, i.e. a new shot, as in a film.
small="$OUT/clips/mem-source-${MEM_FPS}fps.mp4"
[ -f "$small" ] || ffmpeg -nostdin -loglevel error -y -i "$OUT/clips/$FLOOR_CLIP.mp4" \
  -vf "scale=320:180,fps=$MEM_FPS" -c:v libx264 -preset ultrafast -crf 23 "$small"
for m in "${MEM_MINUTES[@]}"; do
  long="$OUT/clips/mem-${m}min-${MEM_FPS}fps.mp4"
  secs=$(awk "BEGIN{print $m * 60}")
  [ -f "$long" ] || ffmpeg -nostdin -loglevel error -y -stream_loop -1 -i "$small" -t "$secs" -c copy "$long"
  record memory hapcine "320px 150tr, ${MEM_FPS} fps" "$m" "$(frames_of "$long")" "$OUT/est/mem-$m.camera.csv" "" -- \
    "$HC" estimate "$long" -o "$OUT/est/mem-$m.camera.csv" -q --max-side 320 --tracks 150
done

# ---- Haptic loop on simulated Falcons ----
log "haptic loop, $LOOP_S s"
"$BUILD/player/hapcine_loop_bench" "$LOOP_S" >"$OUT/loop.txt" 2>&1 || echo "(hapcine_loop_bench exited with $?)" >>"$OUT/loop.txt"

# ---- Report ----
run_s=$(( $(date +%s) - run_start ))
{
  echo "command: \`bash bench/run.sh $([ $MODE = quick ] && echo --quick)\` ($MODE mode), $(date -u '+%Y-%m-%d %H:%M UTC')"
  echo "hapcine commit: $commit ($dirty tracked files modified in the working tree when it was built)"
  echo "machine: $(nproc) cores, $(awk '/MemTotal/{printf "%.0f GiB", $2/1048576}' /proc/meminfo); load average at start $load_start, at end $(cut -d' ' -f1-3 /proc/loadavg)"
  echo "clips: ${#CLIPS[@]} presets at ${W}x$H, $DUR s, 24 fps ($([ ${#missing[@]} -gt 0 ] && echo "${#missing[@]} rendered in this run, " )render $render_s s, build $build_s s; neither counted below)"
  echo "measured run (everything after rendering): $((run_s - render_s)) s wall"
  echo "tools: $(colmap -h 2>/dev/null | head -n 1 | cut -c1-40); OpenCV $(pkg-config --modversion opencv4 2>/dev/null); $(ffmpeg -version | head -n 1 | cut -d' ' -f1-3)"
} >"$OUT/meta.txt"
log "measured in $run_s s"
fi  # REPORT_ONLY
[ -f "$RUNS" ] && [ -f "$OUT/meta.txt" ] || { echo "run.sh: no run in $OUT to report" >&2; exit 1; }
"$BUILD/bench/hapcine_bench_report" --runs "$RUNS" --md "$OUT/report.md" --figures "$OUT/fig" \
  --figure-link fig --loop "$OUT/loop.txt" --meta "$OUT/meta.txt" || exit 1
log "report: $OUT/report.md"

if [ $PUBLISH = 1 ]; then
  doc="$ROOT/docs/benchmarks.md"
  mkdir -p "$ROOT/docs/benchmarks"
  cp "$OUT"/fig/*.png "$ROOT/docs/benchmarks/"
  sed 's#](fig/#](benchmarks/#g' "$OUT/report.md" >"$OUT/report.published.md"
  awk -v gen="$OUT/report.published.md" '
    /<!-- BEGIN GENERATED/ { print; while ((getline l < gen) > 0) print l; skip = 1; next }
    /<!-- END GENERATED/ { skip = 0 }
    !skip { print }' "$doc" >"$doc.tmp" && mv "$doc.tmp" "$doc"
  log "published into $doc"
fi
