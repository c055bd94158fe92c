#!/usr/bin/env bash
# every_device.sh CLRT CLRT_TESTS - runs the OpenCL tests that compare with
# the reference on every device `clrt devices` lists besides the default one
# (the plain test run covers that), one run per device with CLRT_TEST_DEVICE
# set to its index. What runs there is the fast tier's device tests: the
# cases that render and compare on one device. Left to the default device
# (docs/testing.md has the measurements):
# - multi-device tests, which pick their devices themselves, and the [cli]
#   and [mpi-cli] tests, which run the clrt binary on its default device
#   (tagged [opencl] because they need one); [dist] tests (the MPI layer in
#   a world of one: the farm, not the device);
# - the slow tier ([slow]) and [per-case-builds]: a program per case or per
#   cell of a matrix, each a cold build on rusticl;
# - supersampling ([spp]): with Mesa's shader cache empty, two of its cases
#   took 412 s and 430 s on rusticl.
# Tests that sweep a matrix of builds (lane counts, generic, fp64) run only
# the default build here (CLRT_TEST_BUILDS=default, tests/test_util.hpp:
# every_build()). Registered with CTest (CMakeLists.txt).
set -euo pipefail
clrt=$1 tests=$2
# Mesa rusticl exposes its llvmpipe device only when asked.
export RUSTICL_ENABLE=${RUSTICL_ENABLE:-swrast}
# Device rows start with the index; the default device's index carries a '*'.
mapfile -t others < <("$clrt" devices | awk '$1 ~ /^[0-9]+$/ {print $1}')
if [ ${#others[@]} -eq 0 ]; then
  echo "every_device: only the default device is installed; nothing more to run"
  exit 0
fi
spec='[opencl]~[multidevice]~[cli]~[mpi-cli]~[per-case-builds]~[slow]~[dist]~[spp]'
# One case per process, as many processes at a time as cores, each taking
# the next case when it is done (xargs -P): a driver's compiler (rusticl's)
# runs on one thread, so one process would leave the other cores idle, and
# a fixed share of the cases per process left one core idle while the other
# finished its share. Nothing is lost between cases: programs are shared
# through the program cache (CLRT_CACHE_DIR) and the driver's own. (Names
# go to Catch2's --input-file with its test-spec characters escaped, as
# CTest's registration escapes them.)
jobs=$(nproc 2>/dev/null || echo 1)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
"$tests" "$spec" --list-test-names-only | sed -e '/^$/d' -e 's/[][,\\]/\\&/g' >"$work/names" || true
[ -s "$work/names" ] || { echo "every_device: no test matches $spec"; exit 1; }
count=$(wc -l <"$work/names")
# run_case INDEX K: the K-th case on device INDEX, its output in case.K.log;
# a failed case leaves case.K.failed. (Called by xargs, through bash -c.)
# shellcheck disable=SC2317
run_case() {
  sed -n "$2p" "$work/names" >"$work/case.$2"
  CLRT_TEST_DEVICE=$1 CLRT_TEST_BUILDS=default "$tests" --input-file "$work/case.$2" --durations yes \
    >"$work/case.$2.log" 2>&1 || touch "$work/case.$2.failed"
}
export -f run_case
export work tests
status=0
for index in "${others[@]}"; do
  echo "== OpenCL tests on device $index: $("$clrt" devices | awk -v i="$index" '$1 == i {$1=""; print}' | cut -c1-90)"
  rm -f "$work"/case.*
  # shellcheck disable=SC2016
  seq 1 "$count" | xargs -P "$jobs" -n 1 bash -c 'run_case "$0" "$1"' "$index"
  for k in $(seq 1 "$count"); do
    if [ -e "$work/case.$k.failed" ]; then
      status=1
      echo "-- FAILED: $(cat "$work/case.$k")"
    fi
    cat "$work/case.$k.log"
  done
  echo "-- $count cases, $(find "$work" -name 'case.*.failed' | wc -l) failed"
done
exit $status
