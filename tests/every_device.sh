#!/usr/bin/env bash
# every_device.sh CLRT CLRT_TESTS - runs the OpenCL tests that compare with
# the reference on every device `clrt devices` lists besides the default one
# (the plain test run covers that), one run per device with CLRT_TEST_DEVICE
# set to its index. Multi-device tests stay on the default device: they pick
# their devices themselves; so do the [cli] tests, which run the clrt binary
# on its default device (tagged [opencl] because they need one), and so do
# tests tagged [per-case-builds], which build a program per generated case
# (40 builds: under a minute on PoCL, ~5 minutes on rusticl with cold
# caches, most of this script's time in CI). Tests that sweep a matrix of
# builds (lane counts, generic, fp64) run only the default build here
# (CLRT_TEST_BUILDS=default, tests/test_util.hpp: every_build()): each program
# is a cold build of 10-40 s on rusticl. Registered with CTest
# (CMakeLists.txt).
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
status=0
for index in "${others[@]}"; do
  echo "== OpenCL tests on device $index: $("$clrt" devices | awk -v i="$index" '$1 == i {$1=""; print}' | cut -c1-90)"
  CLRT_TEST_DEVICE=$index CLRT_TEST_BUILDS=default "$tests" '[opencl]~[multidevice]~[cli]~[per-case-builds]' ||
    status=1
done
exit $status
