#!/usr/bin/env bash
# Fuzzes the file readers (fuzz/, docs/fuzzing.md): builds the libFuzzer
# targets with clang (ASan + UBSan) into build-fuzz, replays every saved
# regression input, then runs each target for SECONDS on a copy of its seed
# corpus. Exit 1 if any target crashes, leaks, hangs or throws anything but
# hapcine::Error; the inputs that did are kept in build-fuzz/findings/.
#   scripts/fuzz.sh [SECONDS] [TARGET...]    # default: 60 s, every target
#   scripts/fuzz.sh 3600                     # release run: an hour each
#   HAPCINE_FUZZ_NO_BUILD=1 scripts/fuzz.sh 3600 tum &   # parallel runs, one build
set -euo pipefail
cd "$(dirname "$0")/.."

SECONDS_EACH=${1:-60}
shift || true
if ! [[ "$SECONDS_EACH" =~ ^[0-9]+$ ]] || [ "$SECONDS_EACH" -lt 1 ]; then
  echo "usage: scripts/fuzz.sh [SECONDS] [TARGET...]  (SECONDS: a whole number >= 1)" >&2
  exit 2
fi
TARGETS=("$@")
if [ ${#TARGETS[@]} -eq 0 ]; then
  TARGETS=(camera_path haptic_track keyframes seat_json edits platform study_plan study_results tum colmap)
fi
BUILD_DIR=${BUILD_DIR:-build-fuzz}
FINDINGS="$BUILD_DIR/findings"

CMAKE_ARGS=(-DCMAKE_CXX_COMPILER="${CXX_FUZZ:-clang++}" -DHAPCINE_FUZZ=ON
            -DHAPCINE_BUILD_TESTS=OFF -DCMAKE_BUILD_TYPE=RelWithDebInfo)
if command -v ccache >/dev/null 2>&1; then
  CMAKE_ARGS+=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
  source scripts/ccache_env.sh
fi
# HAPCINE_FUZZ_NO_BUILD=1: use the targets as built (several runs in parallel on one build).
if [ "${HAPCINE_FUZZ_NO_BUILD:-0}" != "1" ]; then
  echo "== Fuzz build ($BUILD_DIR)"
  cmake -S . -B "$BUILD_DIR" "${CMAKE_ARGS[@]}" >/dev/null
  cmake --build "$BUILD_DIR" -j"$(nproc)" --target hapcine_fuzzers
fi

# The working corpus grows in a temporary folder: the checked-in seeds stay as they are.
WORK=$(mktemp -d "${TMPDIR:-/tmp}/hapcine-fuzz.XXXXXX")
trap 'rm -rf "$WORK"' EXIT
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
failed=()

# Saved crash inputs must keep passing: each is run once.
replay_regressions() {
  local target=$1 bin=$2 dir=fuzz/regressions/$1
  [ -d "$dir" ] || return 0
  local inputs=("$dir"/*)
  [ -e "${inputs[0]}" ] || return 0
  if ! TMPDIR="$WORK" "$bin" "${inputs[@]}" >"$WORK/$target.replay.log" 2>&1; then
    echo "fuzz: $target: a regression input fails again:" >&2
    tail -n 40 "$WORK/$target.replay.log" | cut -c1-240 >&2
    return 1
  fi
  echo "fuzz: $target: regression inputs pass (${#inputs[@]})"
}

fuzz_target() {
  local target=$1 bin=$2 log=$WORK/$1.log
  rm -rf "$FINDINGS/$target"  # only this run's findings
  mkdir -p "$WORK/$target" "$FINDINGS/$target"
  cp fuzz/corpus/"$target"/* "$WORK/$target/"
  local dict=()
  [ -f "fuzz/$target.dict" ] && dict=(-dict="fuzz/$target.dict")
  # TMPDIR: the readers that take a path get their scratch files there.
  if ! TMPDIR="$WORK" "$bin" "$WORK/$target" "${dict[@]}" -max_total_time="$SECONDS_EACH" -timeout=10 \
       -rss_limit_mb=2048 -print_final_stats=1 -artifact_prefix="$FINDINGS/$target/" \
       >"$log" 2>&1; then
    cp "$log" "$FINDINGS/$target/fuzz.log"
    echo "fuzz: $target: FAILED (input and log in $FINDINGS/$target/):" >&2
    grep -v '^#[0-9]' "$log" | tail -n 40 | cut -c1-240 >&2
    return 1
  fi
  local runs cov
  runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log")
  cov=$(grep -o 'cov: [0-9]*' "$log" | tail -n 1)
  echo "fuzz: $target: ${SECONDS_EACH} s, ${runs:-?} runs, ${cov:-cov: ?}, corpus $(ls "$WORK/$target" | wc -l) inputs: ok"
}

for target in "${TARGETS[@]}"; do
  bin="$BUILD_DIR/fuzz/${target}_fuzzer"
  if [ ! -x "$bin" ]; then
    echo "fuzz: unknown target '$target' (no $bin)" >&2
    exit 2
  fi
  replay_regressions "$target" "$bin" || { failed+=("$target"); continue; }
  fuzz_target "$target" "$bin" || failed+=("$target")
done

if [ ${#failed[@]} -ne 0 ]; then
  echo "== Fuzzing FAILED: ${failed[*]} (inputs in $FINDINGS; add them to fuzz/regressions/<target>/ once fixed)"
  exit 1
fi
echo "== Fuzzing passed: ${#TARGETS[@]} targets, ${SECONDS_EACH} s each, no crash"
