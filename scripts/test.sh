#!/usr/bin/env bash
# Installs what is missing, builds, and runs every test:
#   1. Release build: all tests (unit, end-to-end, Slurm cluster).
#   2. AddressSanitizer + UBSan build: the unit tests.
#   3. libFuzzer on every file reader, 20 s each (scripts/fuzz.sh; skip with
#      HAPCINE_SKIP_FUZZ=1).
# Exit code non-zero if anything fails. Used by .ci/run.
set -euo pipefail
cd "$(dirname "$0")/.."
JOBS=$(nproc)

bash scripts/install_deps.sh

echo "== Release build"
BUILD_DIR=build bash scripts/build.sh
echo "== Tests (Release)"
(cd build && ctest --output-on-failure -j"$JOBS" --timeout 900)

if [ "${HAPCINE_SKIP_SANITIZERS:-0}" != "1" ]; then
  echo "== ASan/UBSan build"
  HAPCINE_SANITIZE=1 BUILD_DIR=build-asan bash scripts/build.sh
  echo "== Unit tests (ASan/UBSan)"
  export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1
  export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
  (cd build-asan && ctest --output-on-failure -j"$JOBS" -L unit --timeout 900)
fi
if [ "${HAPCINE_SKIP_FUZZ:-0}" != "1" ]; then
  echo "== Fuzzing the readers (clang, ASan/UBSan)"
  bash scripts/fuzz.sh 20
fi
echo "== All tests passed"
