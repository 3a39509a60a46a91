#!/usr/bin/env bash
# Configures and builds hapcine into BUILD_DIR (default: build).
#   HAPCINE_SANITIZE=1 scripts/build.sh   # AddressSanitizer + UBSan build in build-asan
set -euo pipefail
cd "$(dirname "$0")/.."
if [ "${HAPCINE_SANITIZE:-0}" = "1" ]; then
  BUILD_DIR=${BUILD_DIR:-build-asan}
  EXTRA=(-DHAPCINE_SANITIZE=ON -DCMAKE_BUILD_TYPE=Debug)
else
  BUILD_DIR=${BUILD_DIR:-build}
  EXTRA=(-DCMAKE_BUILD_TYPE=Release)
fi
# ccache, where installed, makes rebuilds of unchanged files (CI after a
# local run, several work trees) nearly free: scripts/ccache_env.sh makes a
# fresh clone in another folder hit the objects of an earlier build.
if command -v ccache >/dev/null 2>&1; then
  EXTRA+=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
  source scripts/ccache_env.sh
fi
cmake -S . -B "$BUILD_DIR" "${EXTRA[@]}" >/dev/null
cmake --build "$BUILD_DIR" -j"$(nproc)" "$@"
