#!/bin/bash
# Estimates and scores every synthetic clip, two at a time, and prints a table
# (docs/estimate.md, "Accuracy").
#   scripts/estimate_accuracy.sh HAPCINE_BINARY OUT_DIR [extra estimate options...]
# Clips: /tmp/d/clips/<clip>.mp4 + <clip>.camera.csv (hapcine synth), or CLIPS=dir.
set -u
BIN=$1; OUT=$2; shift 2
CLIPS=${CLIPS:-/tmp/d/clips}
mkdir -p "$OUT"
ls "$CLIPS"/*.mp4 | xargs -n1 basename | sed 's/\.mp4$//' | \
  xargs -P2 -I{} sh -c "$BIN estimate $CLIPS/{}.mp4 -o $OUT/{}.est.camera.csv --quiet $* 2>$OUT/{}.err; \
    $BIN eval --gt $CLIPS/{}.camera.csv --est $OUT/{}.est.camera.csv --json > $OUT/{}.json 2>>$OUT/{}.err"
python3 - "$OUT" <<'PY'
import json, sys
out = sys.argv[1]
order = ("crane_shot dutch_angle arcing traveling tilting zoom_in vertigo slow_pan whip_pan "
         "handheld_shake telephoto_zoom_pan dolly_zoom_parallax low_texture noise_compression "
         "hard_cut fade_to_black static_camera").split()
print("%-20s %8s %8s %8s %8s %8s" % ("clip", "rotmean", "rotmax", "fov%", "zoom%", "ATE%"))
for c in order:
    try:
        o = json.load(open(f"{out}/{c}.json"))["overall"]
        ate = o.get("ate_percent")
        print("%-20s %8.4f %8.3f %8.2f %8.3f %8s" % (
            c, o["rotation_deg"]["mean"], o["rotation_deg"]["max"], o["fov_percent"]["mean"],
            o["zoom_ratio_percent"]["mean"], "n/a" if ate is None else "%.3f" % ate))
    except (OSError, KeyError, ValueError) as e:
        print("%-20s missing (%s)" % (c, e))
PY
