#!/usr/bin/env bash
# ctest hjif_reference_software: the .hjif of each haptic model for one
# Table 1 clip (hapcine synth zoom_in, a 7 s camera path) through the MPEG-I
# Haptics reference software (../shared/tools/mpeg-haptics/validate.sh):
# schema, the reference loader, JSON re-export, the .hmpg round trip (within
# the binary format's quantisation, docs/haptics.md) and rendering.
# Exit 77 (ctest SKIP) only when validate.sh's build tools are missing.
#
#   bash tests/hjif_reference_test.sh HAPCINE_EXE WORK_DIR
set -uo pipefail
HC=$1 WORK=$2
ROOT=$(cd "$(dirname "$0")/.." && pwd)
# ../shared beside the repository; a worktree in wt/NAME has it two up.
MH=""
for d in "$ROOT/../shared/tools/mpeg-haptics" "$ROOT/../../shared/tools/mpeg-haptics"; do
  [ -f "$d/validate.sh" ] && { MH=$d; break; }
done
[ -n "$MH" ] || { echo "FAIL: no ../shared/tools/mpeg-haptics/validate.sh beside $ROOT"; exit 1; }
missing=()
for t in cmake make g++ python3; do command -v "$t" >/dev/null || missing+=("$t"); done
command -v python3 >/dev/null && ! python3 -c "import jsonschema" 2>/dev/null &&
  missing+=("python3-jsonschema")
if [ ${#missing[@]} -gt 0 ]; then
  echo "SKIP: validate.sh needs ${missing[*]} (scripts/install_deps.sh installs them)"
  exit 77
fi
rm -rf "$WORK" && mkdir -p "$WORK" || exit 1
"$HC" synth zoom_in -o "$WORK" --width 64 --height 36 --supersample 1 -j 2 >"$WORK/synth.log" 2>&1 ||
  { cat "$WORK/synth.log"; exit 1; }
files=()
for m in cinematic semantic random none; do
  "$HC" haptics "$WORK/zoom_in.camera.csv" --model "$m" -o "$WORK/zoom_in.$m.haptic.csv" \
    --hjif "$WORK/zoom_in.$m.hjif" || exit 1
  files+=("$WORK/zoom_in.$m.hjif")
done
# The binary format's quantisation, nothing else (docs/haptics.md):
# amplitude_modulation in 8 bits over [-1, 1] by truncation (one step 2/255),
# mixing_coefficient in 32 bits over [0, 10000] by truncation (one step 2.33e-6).
bash "$MH/validate.sh" -O "$WORK/validate" --tol amplitude_modulation=0.0079 \
  --tol mixing_coefficient=2.4e-6 "${files[@]}"
