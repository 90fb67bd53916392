#!/usr/bin/env bash
# The project under sanitizers, each in its own build folder (clang-14 when installed, else the
# default compiler; RelWithDebInfo):
#
#   tools/sanitize.sh [address|thread|all] [--prefix DIR]
#
# address: AddressSanitizer + UBSan (-DDSS_SANITIZE=ON) on every library, executable and test
#   (DSS_BUILD_TOOLS=ON), then the whole CTest suite, in DIR/build-asan-full.
# thread: ThreadSanitizer (-DDSS_SANITIZE=thread), in DIR/build-tsan, on what runs threads: the
#   parallel planner test (pRRT, two threads, tests/planning), the 4-thread stress test of the
#   continuous motion check (tests/checker, concurrent_motion) and `dss_check --threads 4
#   --random 20000` on our arm in its shelf scene.
# all (default): both. DIR defaults to the repository. A report stops the run with a non-zero
# exit status (halt_on_error); there are no suppressions. docs/sanitizers.md has the last
# results and their times.
set -euo pipefail
src=$(cd "$(dirname "$0")/.." && pwd)
what=all
prefix=$src
while [ $# -gt 0 ]; do
  case "$1" in
    address | thread | all) what=$1; shift ;;
    --prefix) prefix=$2; shift 2 ;;
    *) sed -n '2,15p' "$0" >&2; exit 2 ;;
  esac
done
jobs=${DSS_JOBS:-2}
# clang builds the instrumented project several times faster than g++ (whose AddressSanitizer
# builds of the search's instantiations take most of an hour on two cores).
compilers=()
if command -v clang++-14 > /dev/null; then
  compilers=(-DCMAKE_CXX_COMPILER=clang++-14)
fi

step() { echo "+ $*"; "$@"; }
timed() {
  local label=$1 start=$SECONDS
  shift
  "$@"
  echo "= $label: $((SECONDS - start)) s"
}

if [ "$what" = address ] || [ "$what" = all ]; then
  b=$prefix/build-asan-full
  export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1:strict_string_checks=1:detect_stack_use_after_return=1
  export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
  timed "asan+ubsan configure and build" bash -c "
    cmake -S '$src' -B '$b' ${compilers[*]} -DCMAKE_BUILD_TYPE=RelWithDebInfo -DDSS_SANITIZE=ON -DDSS_BUILD_TOOLS=ON > /dev/null &&
    cmake --build '$b' -j$jobs"
  timed "asan+ubsan ctest" step ctest --test-dir "$b" --output-on-failure -j1
fi

if [ "$what" = thread ] || [ "$what" = all ]; then
  b=$prefix/build-tsan
  export TSAN_OPTIONS=halt_on_error=1:second_deadlock_stack=1:exitcode=66
  timed "tsan configure and build" bash -c "
    cmake -S '$src' -B '$b' ${compilers[*]} -DCMAKE_BUILD_TYPE=RelWithDebInfo -DDSS_SANITIZE=thread -DDSS_BUILD_TOOLS=ON > /dev/null &&
    cmake --build '$b' -j$jobs --target test_planning test_checker dss_check"
  timed "tsan parallel planner" step "$b/tests/test_planning" --run_test=parallel_planner \
    --log_level=test_suite --report_level=short
  timed "tsan concurrent motion" step "$b/tests/test_checker" --run_test=concurrent_motion \
    --log_level=test_suite --report_level=short
  arm=$src/robots/dss_arm7
  # The answers (one line per state) are not kept; the summary goes to stderr.
  timed "tsan dss_check --threads 4" step bash -c "'$b/tools/dss_check' --robot '$arm/dss_arm7.urdf' \
    --srdf '$arm/dss_arm7.srdf' --scene '$arm/scenes/shelf.yaml' --random 20000 --threads 4 \
    > /dev/null"
fi
echo "sanitizers: no report"
