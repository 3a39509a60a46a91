#!/usr/bin/env bash
# The .hjif of a long film through the MPEG-I Haptics reference software
# (docs/haptics.md, "MPEG-I Haptics"): hapcine haptics --hjif on a camera
# path of SECONDS (bench/long_camera_path.py, 24 fps; default two hours),
# then the reference loader, its JSON re-export (Encoder) compared field by
# field with the original, and with --hmpg the binary round trip (Encoder -b,
# Decoder, comparison within the format's quantisation). Each step's wall
# time, CPU time and peak RSS. The reference Encoder -b and Decoder take
# time quadratic in the film's length (about 10 + 13 CPU s for 100 s, 37 +
# 50 for 200 s): use --hmpg with a few hundred seconds, not two hours.
# validate.sh's rendering step is left out (its pure-Python WAV check of
# 2 h x 8 kHz x 9 channels would take hours). Needs the reference software
# built by validate.sh (it builds it if not).
#
#   bash bench/hjif_film.sh [--seconds S] [--hmpg] [--out DIR] [--build DIR]
set -uo pipefail
ROOT=$(cd "$(dirname "$0")/.." && pwd)
SECONDS_FILM=7200 OUT=/tmp/hapcine-hjif-film BUILD="$ROOT/build" HMPG=0
while [ $# -gt 0 ]; do
  case $1 in
    --seconds) SECONDS_FILM=$2; shift ;;
    --hmpg) HMPG=1 ;;
    --out) OUT=$2; shift ;;
    --build) BUILD=$2; shift ;;
    -h|--help) sed -n 2,16p "$0"; exit 0 ;;
    *) echo "hjif_film.sh: unknown argument '$1' (see --help)" >&2; exit 2 ;;
  esac
  shift
done
MH="$ROOT/../shared/tools/mpeg-haptics"
[ -d "$MH" ] || MH="$ROOT/../../shared/tools/mpeg-haptics"
[ -f "$MH/validate.sh" ] || { echo "hjif_film.sh: no ../shared/tools/mpeg-haptics" >&2; exit 1; }
RS="${TMPDIR:-/tmp}/mpeg-haptics-build"
bash "$MH/validate.sh" --build-only >/dev/null || { echo "hjif_film.sh: reference build failed" >&2; exit 1; }
HC="$BUILD/cli/hapcine"
mkdir -p "$OUT"
film="$OUT/film.camera.csv"
[ -f "$film" ] || python3 "$ROOT/bench/long_camera_path.py" "$SECONDS_FILM" 24 "$film"
ulimit -Sn 1024  # the reference loader's schema recursion (validate.sh README)
# step LABEL command...: one line of wall s, CPU s (user + system: on a
# shared machine the wall time mostly measures the others), peak RSS MB, exit.
step() {
  local label=$1
  shift
  /usr/bin/time -f "%e %U %S %M" -o "$OUT/time.txt" nice "$@" >"$OUT/$label.log" 2>&1
  local rc=$? wall user sys rss
  read -r wall user sys rss < <(tail -n 1 "$OUT/time.txt")  # after "Command exited with ..."
  printf '| %s | %s | %s | %d | %d |\n' "$label" "$wall" "$(awk "BEGIN{print $user + $sys}")" \
    $((rss / 1024)) "$rc"
}
echo "| step | wall s | CPU s | peak RSS MB | exit |"
echo "|---|---|---|---|---|"
step haptics "$HC" haptics "$film" -o "$OUT/film.haptic.csv" --hjif "$OUT/film.hjif"
step load "$RS/hjif_load_check" "$OUT/film.hjif"
TOL=(--tol amplitude_modulation=0.0079 --tol mixing_coefficient=2.4e-6)
step reexport "$RS/source/Encoder/Encoder" -f "$OUT/film.hjif" -o "$OUT/film.json.hjif"
step compare-json python3 "$MH/tools/compare_hjif.py" "$OUT/film.hjif" "$OUT/film.json.hjif"
if [ $HMPG = 1 ]; then
  step encode "$RS/source/Encoder/Encoder" -f "$OUT/film.hjif" -o "$OUT/film.hmpg" -b
  step decode "$RS/source/Decoder/Decoder" -f "$OUT/film.hmpg" -o "$OUT/film.rt.hjif"
  step compare-hmpg python3 "$MH/tools/compare_hjif.py" "$OUT/film.hjif" "$OUT/film.rt.hjif" "${TOL[@]}"
fi
echo
echo "film.hjif: $(stat -c %s "$OUT/film.hjif") bytes$([ $HMPG = 1 ] && echo "; film.hmpg: $(stat -c %s "$OUT/film.hmpg") bytes")"
grep -h "LOAD\|loaded" "$OUT/load.log" | head -2
for c in compare-json compare-hmpg; do [ -f "$OUT/$c.log" ] && echo "$c: $(tail -n 1 "$OUT/$c.log")"; done
