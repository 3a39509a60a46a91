#!/usr/bin/env bash
# The studio server's speed (docs/studio.md, "HTTP API"): for a film of
# SECONDS (a camera path from bench/long_camera_path.py at 24 fps, a new shot
# every 12 s; the "film" is a placeholder file, which the server serves as it
# is), the time from `hapcine studio --camera` to its first answer (reading
# the path, rendering the track, building the curve pyramids), the
# whole-film and a zoomed curves query at 2000 points, and a save (PUT of
# edits: parse, re-render with MakeHapticTrack, write the edits file). Each
# request is timed by curl, best of 5.
#
#   bash bench/studio_server.sh [--seconds S] [--model M] [--build DIR]
set -uo pipefail
ROOT=$(cd "$(dirname "$0")/.." && pwd)
SECONDS_FILM=120 MODEL=cinematic BUILD="$ROOT/build"
while [ $# -gt 0 ]; do
  case $1 in
    --seconds) SECONDS_FILM=$2; shift ;;
    --model) MODEL=$2; shift ;;
    --build) BUILD=$2; shift ;;
    -h|--help) sed -n 2,12p "$0"; exit 0 ;;
    *) echo "studio_server.sh: unknown argument '$1' (see --help)" >&2; exit 2 ;;
  esac
  shift
done
HAPCINE="$BUILD/cli/hapcine"
OUT=$(mktemp -d /tmp/hapcine-studio-bench.XXXXXX)
trap 'kill "$PID" 2>/dev/null; wait "$PID" 2>/dev/null; rm -rf "$OUT"' EXIT
python3 "$ROOT/bench/long_camera_path.py" "$SECONDS_FILM" 24 "$OUT/film.camera.csv"
head -c 1000000 /dev/urandom > "$OUT/film.mp4"

start=$(date +%s.%N)
"$HAPCINE" studio "$OUT/film.mp4" --camera "$OUT/film.camera.csv" --model "$MODEL" --port 0 \
  > "$OUT/url.txt" 2> "$OUT/log.txt" &
PID=$!
URL=""
for _ in $(seq 1 600); do
  URL=$(grep -o 'http://[^ ]*' "$OUT/url.txt" 2>/dev/null | head -1)
  [ -n "$URL" ] && break
  kill -0 "$PID" 2>/dev/null || { cat "$OUT/log.txt" >&2; exit 1; }
  sleep 0.1
done
URL=${URL%/}
curl -sf "$URL/api/films" > /dev/null || { echo "no answer from $URL" >&2; exit 1; }
ready=$(echo "$(date +%s.%N) - $start" | bc)

best() {  # best-of-5 wall time of a curl request, seconds
  local t b=999
  for _ in 1 2 3 4 5; do
    t=$(curl -s -o /dev/null -w '%{time_total}' "$@")
    b=$(echo "if ($t < $b) $t else $b" | bc)
  done
  echo "$b"
}
whole=$(best "$URL/api/films/f0/curves?points=2000")
size=$(curl -s "$URL/api/films/f0/curves?points=2000" | wc -c)
zoom=$(best "$URL/api/films/f0/curves?from=60&to=90&points=2000")
save_best=999
for rev in 0 1 2 3 4; do
  body="{\"format\":\"hapcine-edits\",\"version\":1,\"revision\":$rev,\"shots\":[{\"shot\":0,\"gain\":0.$((rev + 1))}]}"
  t=$(curl -s -o /dev/null -w '%{time_total}' -X PUT -H 'Content-Type: application/json' \
        --data "$body" "$URL/api/films/f0/edits")
  save_best=$(echo "if ($t < $save_best) $t else $save_best" | bc)
done
printf 'film %s s, model %s\n' "$SECONDS_FILM" "$MODEL"
printf '  start to first answer        %.2f s\n' "$ready"
printf '  curves, whole film, 2000 pts %.3f s (%d bytes)\n' "$whole" "$size"
printf '  curves, 30 s, 2000 pts       %.3f s\n' "$zoom"
printf '  save (re-render), best of 5  %.3f s\n' "$save_best"
