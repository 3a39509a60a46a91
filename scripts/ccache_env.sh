# Sourced by scripts/build.sh and scripts/fuzz.sh (from the checkout's root).
# ccache keys an object on the compiler's command line and, with debug info,
# on the working folder: both hold the checkout's absolute path. A base
# folder makes ccache write paths under it relative, and not hashing the
# working folder lets a clone elsewhere (CI's clean clone) reuse the objects
# of a build made here. (Debug info of a reused object names the first
# checkout's folder: only the file names in a sanitizer's stack trace.)
export CCACHE_BASEDIR=${CCACHE_BASEDIR:-$PWD}
export CCACHE_NOHASHDIR=${CCACHE_NOHASHDIR:-1}
