#!/usr/bin/env bash
# The nightly fuzz run: the [fuzz] test of brdfbake_tests (tests/test_fuzz.cpp) with many more
# cases than CI runs, any seed, and the memory-hungry inputs (/dev/zero, /dev/urandom as n,k
# files) that CI leaves out. Every failing case is printed with its command line and the
# variables that rerun it alone (BRDFBAKE_FUZZ_SEED, BRDFBAKE_FUZZ_ONLY); its inputs are kept.
#
# Usage: scripts/fuzz.sh SEED COUNT [BUILD_DIR]     (BUILD_DIR: default build, as README builds)
#   e.g. scripts/fuzz.sh "$(date +%Y%m%d)" 5000
# Environment: BRDFBAKE_FUZZ_TIMEOUT (seconds per run, default 20), BRDFBAKE_FUZZ_JOBS (runs at a
# time, default: the number of CPUs), BRDFBAKE_FUZZ_HOSTILE (default 1 here), POCL_CACHE_DIR.
# Exit status: 0 when every case held, 1 when one failed, 2 for a usage error.
set -euo pipefail

if [ $# -lt 2 ] || ! [[ "$1" =~ ^[0-9]+$ ]] || ! [[ "$2" =~ ^[0-9]+$ ]] || [ "$2" -eq 0 ]; then
  echo "usage: scripts/fuzz.sh SEED COUNT [BUILD_DIR]   (SEED and COUNT: whole numbers, COUNT > 0)" >&2
  exit 2
fi
seed=$1 count=$2
build=${3:-build}
tests="$build/brdfbake_tests"
if [ ! -x "$tests" ]; then
  echo "fuzz.sh: $tests not found: build it first (cmake --build $build --target brdfbake brdfbake_tests)" >&2
  exit 2
fi

export BRDFBAKE_FUZZ_SEED=$seed BRDFBAKE_FUZZ_COUNT=$count
export BRDFBAKE_FUZZ_JOBS=${BRDFBAKE_FUZZ_JOBS:-$(nproc)}
export BRDFBAKE_FUZZ_HOSTILE=${BRDFBAKE_FUZZ_HOSTILE:-1}
export BRDFBAKE_FUZZ_TIMEOUT=${BRDFBAKE_FUZZ_TIMEOUT:-20}
echo "fuzz.sh: seed $seed, $count cases, $BRDFBAKE_FUZZ_JOBS at a time, ${BRDFBAKE_FUZZ_TIMEOUT} s per run" >&2
start=$(date +%s)
# Run from the build folder, as ctest does (some tests use relative paths).
cd "$build"
status=0
./brdfbake_tests "[fuzz]" || status=1
echo "fuzz.sh: $(( $(date +%s) - start )) s; $([ $status -eq 0 ] && echo 'every case held' || echo 'FAILED: see the cases above')" >&2
exit $status
