#!/usr/bin/env bash
# Installs every Debian 12 package hapcine needs to build, test and run.
# Idempotent: installs only what is missing. Needs root (or sudo).
set -euo pipefail

PACKAGES=(
  build-essential cmake pkg-config git
  libeigen3-dev libopencv-dev libceres-dev
  libavformat-dev libavcodec-dev libavutil-dev libswscale-dev libswresample-dev ffmpeg
  libusb-1.0-0-dev libmpv-dev
  # Opened at run time (dlopen), not linked, so that start-up loads neither
  # unless used: libmpv by `hapcine play` (player/mpv_library.h), OpenCV's
  # image codecs by image I/O (lazy_imgcodecs/). The -dev packages above pull
  # them in today; listed so that they stay installed whatever those depend on.
  libmpv2 libopencv-imgcodecs406
  libcli11-dev nlohmann-json3-dev
  # The studio's HTTP server (studio/, `hapcine studio`).
  libcpp-httplib-dev
  libgtest-dev libgmock-dev
  colmap
  # Slurm test (batch issue): a real single-node cluster.
  slurmctld slurmd slurm-client munge
  # Camera exports: the Blender test runs the exported script headless
  # (about 1.5 min to install; the test is skipped without it).
  blender
  # Headless playback tests and screenshots.
  xvfb
  # Benchmarks (bench/run.sh): /usr/bin/time for wall time and peak RSS.
  time
  # MPEG-I Haptics reference software (tests/hjif_reference_test.sh runs
  # ../shared/tools/mpeg-haptics/validate.sh: cmake, make, g++ above, and
  # its schema check in python jsonschema).
  python3 python3-jsonschema
  # Compiler cache: rebuilds of unchanged files are nearly free.
  ccache
  # Fuzzing the readers (scripts/fuzz.sh): clang and its libFuzzer runtime.
  clang libclang-rt-14-dev
)

missing=()
for p in "${PACKAGES[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "install_deps: all ${#PACKAGES[@]} packages present"
  exit 0
fi

SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
echo "install_deps: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
