#!/usr/bin/env bash
# ctest fuzz_replay_leaves_no_scratch: a replay of a reader that takes a
# folder (COLMAP's text model, written to a scratch folder per input) leaves
# nothing in TMPDIR when it ends.
#   bash fuzz/replay_scratch_test.sh COLMAP_REPLAY INPUT_DIR
set -euo pipefail
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
TMPDIR="$tmp" "$1" "$2" >/dev/null 2>&1
left=$(ls -A "$tmp")
if [ -n "$left" ]; then
  echo "FAIL: the replay left $left in TMPDIR"
  exit 1
fi
echo "ok: nothing left in TMPDIR"
