#!/usr/bin/env bash
# The generalisation table (docs/generalisation.md): development and test
# material side by side, at hapcine's defaults, --draft and (on request)
# COLMAP, each run timed against decoding alone.
#
#   bash bench/generalisation.sh OUT_DIR [options]
#
#   --colmap               also run COLMAP 3.8 (bench/colmap_peer.sh: a subsample of the
#                          frames at --colmap-side px, the others interpolated)
#   --colmap-only REGEX    ... only on clips whose "set/clip" matches REGEX
#   --colmap-rate R        images COLMAP gets per second of video (default 4; never fewer
#                          than 30 images, nor a frame skipped on clips under 60 frames)
#   --colmap-side PX       longest side of COLMAP's images (default 480)
#   --colmap-full          run `estimate --backend colmap` on every frame instead (slow:
#                          20+ minutes per 168-frame clip on 2 cores)
#   --colmap-args "ARGS"   extra estimate options for --colmap-full (e.g. "--max-side 480")
#   --jobs N               runs in parallel (default 2)
#   --timeout S            per-run time limit, hapcine (default 900 s)
#   --colmap-timeout S     per-run time limit, COLMAP (default 900 s)
#   --bin PATH             hapcine binary (default build/cli/hapcine of this checkout)
#   --dev-clips DIR        the 17 presets (<p>.mp4 + <p>.camera.csv); default: rendered
#                          into OUT_DIR/clips/dev with `hapcine synth --all`
#   --test-clips DIR       where the variants (DIR/variants) and movers (DIR/movers) are
#                          or are rendered (default OUT_DIR/clips)
#   --test-size WxH        frame size of rendered test clips (default 1280x720)
#   --realgt DIR           real sequences with ground truth (default /work/shared/realgt;
#                          REALGT_DIR in the environment also works); skipped when absent
#   --only REGEX           run only the clips whose "set/clip" matches (the table shows all
#                          results found)
#   --no-render            use the clips found, render none
#   --fresh                re-run everything (default: a run whose result exists is kept,
#                          so an interrupted table resumes)
#   --report-only          only rebuild the table from the results in OUT_DIR
#
# Writes OUT_DIR/generalisation.md (the table, with targets and PASS/FAIL) and
# OUT_DIR/generalisation.json (one record per run). Splits: development = the
# 17 presets + the real sequences; test = the presets' test variants + the
# mover presets (never tuned on). Prints its own runtime at the end.
set -uo pipefail
ROOT=$(cd "$(dirname "$0")/.." && pwd)
START=$(date +%s)
OUT=${1:-}
# The comment block at the top of this file, without its "# " (--help).
usage() { sed -n '2,/^[^#]/s/^# \{0,1\}//p' "$0"; }
if [ -z "$OUT" ] || [ "${OUT#-}" != "$OUT" ]; then usage; exit 2; fi
shift
BIN="$ROOT/build/cli/hapcine" JOBS=2 TIMEOUT=900 CTIMEOUT=900 COLMAP=0 CONLY="" CARGS=""
CRATE=4 CSIDE=480 CFULL=0
DEV="" TEST="" SIZE=1280x720 REALGT=${REALGT_DIR:-/work/shared/realgt} ONLY="" FRESH=0 REPORT_ONLY=0 RENDER=1
while [ $# -gt 0 ]; do
  case $1 in
    --colmap) COLMAP=1 ;;
    --colmap-only) CONLY=$2; shift ;;
    --colmap-args) CARGS=$2; shift ;;
    --colmap-rate) CRATE=$2; shift ;;
    --colmap-side) CSIDE=$2; shift ;;
    --colmap-full) CFULL=1 ;;
    --jobs) JOBS=$2; shift ;;
    --timeout) TIMEOUT=$2; shift ;;
    --colmap-timeout) CTIMEOUT=$2; shift ;;
    --bin) BIN=$2; shift ;;
    --dev-clips) DEV=$2; shift ;;
    --test-clips) TEST=$2; shift ;;
    --test-size) SIZE=$2; shift ;;
    --realgt) REALGT=$2; shift ;;
    --only) ONLY=$2; shift ;;
    --fresh) FRESH=1 ;;
    --no-render) RENDER=0 ;;
    --report-only) REPORT_ONLY=1 ;;
    -h|--help) usage; exit 0 ;;
    *) echo "generalisation.sh: unknown argument '$1' (see --help)" >&2; exit 2 ;;
  esac
  shift
done
mkdir -p "$OUT" || exit 1
OUT=$(cd "$OUT" && pwd)
DEV=${DEV:-$OUT/clips/dev}
TEST=${TEST:-$OUT/clips}
REAL_SEQS="kitti07 lego_orbit debug_moves dino_sparse_ring vtest"
[ -x "$BIN" ] || { echo "generalisation.sh: no hapcine binary at $BIN" >&2; exit 1; }
W=${SIZE%x*} H=${SIZE#*x}

# Renders the presets of a set that are missing (both files must exist).
render_missing() {  # DIR SELECT_FLAG [synth options...]
  local dir=$1 flag=$2; shift 2
  local names missing=()
  names=$("$BIN" synth --list | awk -v movers="$flag" '
    /^$/ {next} /^with independently/ {m=1; next}
    {if ((movers=="--movers") == (m==1)) print $1}')
  for p in $names; do
    [ -s "$dir/$p.mp4" ] && [ -s "$dir/$p.camera.csv" ] || missing+=("$p")
  done
  [ ${#missing[@]} -eq 0 ] && return 0
  echo "rendering ${#missing[@]} clip(s) into $dir" >&2
  "$BIN" synth "${missing[@]}" -o "$dir" "$@" >/dev/null
}

# Task lines: set|clip|video|gt|method
tasks() {
  local m
  for v in "$DEV"/*.mp4; do
    [ -e "$v" ] || continue
    c=$(basename "$v" .mp4)
    echo "presets|$c|$v|${v%.mp4}.camera.csv"
  done
  for s in $REAL_SEQS; do
    [ -f "$REALGT/$s/video.mp4" ] && [ -f "$REALGT/$s/gt.camera.csv" ] &&
      echo "realgt|$s|$REALGT/$s/video.mp4|$REALGT/$s/gt.camera.csv"
  done
  for set in variants movers; do
    for v in "$TEST/$set"/*.mp4; do
      [ -e "$v" ] || continue
      c=$(basename "$v" .mp4)
      echo "$set|$c|$v|${v%.mp4}.camera.csv"
    done
  done
}

# One run: estimate (timed, time-limited), then eval --json.
run_one() {  # set clip video gt method
  local set=$1 clip=$2 video=$3 gt=$4 method=$5
  local dir="$OUT/runs/$set" base="$OUT/runs/$set/$clip.$method"
  mkdir -p "$dir"
  [ "$FRESH" = 0 ] && [ -f "$base.time" ] && return 0
  local cmd=("$BIN" estimate "$video" -o "$base.camera.csv" -q) limit=$TIMEOUT
  case $method in
    draft) cmd+=(--draft) ;;
    colmap)
      limit=$CTIMEOUT
      if [ "$CFULL" = 1 ]; then
        cmd+=(--backend colmap $CARGS)
      else
        cmd=(bash "$ROOT/bench/colmap_peer.sh" "$video" "$base.camera.csv" "$(colmap_step "$video")"
          "$CSIDE" "$(dirname "$(dirname "$BIN")")")
      fi ;;
  esac
  local t0 t1 rc
  t0=$(date +%s.%N)
  timeout --kill-after=10 "$limit" "${cmd[@]}" 2>"$base.err"
  rc=$?
  t1=$(date +%s.%N)
  rm -f "$base.json"
  if [ $rc -eq 0 ]; then
    "$BIN" eval --gt "$gt" --est "$base.camera.csv" --json >"$base.json" 2>>"$base.err" ||
      rm -f "$base.json"
  elif [ $rc -eq 124 ] || [ $rc -eq 137 ]; then
    echo "time limit ${limit} s" >>"$base.err"
  fi
  echo "$(echo "$t1 - $t0" | bc) $rc" >"$base.time"
  echo "$set/$clip $method: rc $rc, $(cut -d' ' -f1 "$base.time") s" >&2
}

# COLMAP's frame step on VIDEO: --colmap-rate images per second, at least 30
# images (incremental SfM needs views that overlap), every frame of a short clip.
colmap_step() {  # VIDEO
  local fps frames
  fps=$(ffprobe -v error -select_streams v:0 -show_entries stream=r_frame_rate -of csv=p=0 "$1" |
    awk -F/ '{print ($2 ? $1/$2 : $1)}')
  frames=$(ffprobe -v error -select_streams v:0 -count_packets -show_entries \
    stream=nb_read_packets -of csv=p=0 "$1")
  awk -v fps="$fps" -v n="$frames" -v rate="$CRATE" 'BEGIN {
    s = int(fps / rate + 0.5); m = int(n / 30); if (m < s) s = m; if (s < 1) s = 1; print s }'
}

# Decoding alone (the floor the estimator's time is compared with).
decode_one() {  # set clip video
  local f="$OUT/decode/$1/$2.time"
  mkdir -p "$OUT/decode/$1"
  [ "$FRESH" = 0 ] && [ -s "$f" ] && return 0
  local t0 t1
  t0=$(date +%s.%N)
  ffmpeg -nostdin -v error -threads 2 -i "$3" -f null - 2>/dev/null
  t1=$(date +%s.%N)
  echo "$t1 - $t0" | bc >"$f"
}
export -f run_one decode_one colmap_step
export OUT BIN TIMEOUT CTIMEOUT CARGS FRESH ROOT CRATE CSIDE CFULL

if [ "$REPORT_ONLY" = 0 ] && [ "$RENDER" = 1 ]; then
  [ -d "$DEV" ] && ls "$DEV"/*.mp4 >/dev/null 2>&1 || render_missing "$DEV" --all -j "$JOBS"
  render_missing "$TEST/variants" --all --variant test --width "$W" --height "$H" -j "$JOBS" ||
    echo "generalisation.sh: rendering the variants failed" >&2
  render_missing "$TEST/movers" --movers --width "$W" --height "$H" -j "$JOBS" ||
    echo "generalisation.sh: rendering the mover presets failed" >&2
fi
if [ "$REPORT_ONLY" = 0 ]; then
  [ -d "$REALGT" ] || echo "generalisation.sh: no $REALGT: real sequences skipped" >&2
  tasks | { if [ -n "$ONLY" ]; then awk -F'|' -v re="$ONLY" '($1 "/" $2) ~ re'; else cat; fi; } \
    >"$OUT/tasks.txt"
  # Decoding floors one at a time (no other run beside them), then the runs.
  while IFS='|' read -r set clip video gt; do decode_one "$set" "$clip" "$video"; done <"$OUT/tasks.txt"
  {
    while IFS='|' read -r set clip video gt; do
      echo "$set|$clip|$video|$gt|default"
      echo "$set|$clip|$video|$gt|draft"
      if [ "$COLMAP" = 1 ] && { [ -z "$CONLY" ] || echo "$set/$clip" | grep -Eq "$CONLY"; }; then
        echo "$set|$clip|$video|$gt|colmap"
      fi
    done <"$OUT/tasks.txt"
  } | tr '|' '\n' | xargs -d '\n' -n5 -P "$JOBS" bash -c 'run_one "$@"' _
fi

COMMIT=$(git -C "$ROOT" rev-parse --short HEAD 2>/dev/null || echo unknown)
CLABEL=$([ "$CFULL" = 1 ] && echo "every frame" || echo "$CRATE images/s, ${CSIDE} px")
python3 "$ROOT/bench/generalisation_table.py" "$OUT" "$COMMIT" "$COLMAP" "$CLABEL" >"$OUT/generalisation.md" ||
  exit 1
cat "$OUT/generalisation.md"
echo "generalisation.sh: $(( $(date +%s) - START )) s wall; table in $OUT/generalisation.md" >&2
