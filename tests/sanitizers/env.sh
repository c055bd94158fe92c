# env.sh - sanitizer runtime options for the -DCLRT_SANITIZE=ON build. Source
# it before ctest: `. tests/sanitizers/env.sh && ctest --test-dir build-asan`.
# docs/developer/sanitizers.md explains every option and suppression.
_clrt_san_dir=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
# intercept_tls_get_addr=0: LeakSanitizer (GCC 12, glibc 2.36) read a bogus
# dynamic-TLS range of a dlopen'ed library at exit ("DTLS 37 at
# 0x3803-0x800004905", then "Tracer caught signal 11") once PLplot's
# libraries were linked: docs/developer/sanitizers.md.
export ASAN_OPTIONS="halt_on_error=1:detect_leaks=1:strict_init_order=1:check_initialization_order=1:intercept_tls_get_addr=0"
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1"
export LSAN_OPTIONS="suppressions=${_clrt_san_dir}/lsan.supp:print_suppressions=0"
# mesa-opencl-icd installs Mesa rusticl (rusticl.icd), which the tests use,
# and Mesa's legacy clover (mesa.icd), which has no device on a machine
# without a supported GPU. Clover leaks 128 bytes at exit from code the ICD
# loader has already unloaded, so the leak's frames carry no module name a
# suppression could match. The sanitizer run loads only the ICDs whose
# devices clrt is tested on: PoCL and rusticl.
_clrt_icds=$(mktemp -d "${TMPDIR:-/tmp}/clrt-sanitizer-icds.XXXXXX")
for _clrt_icd in pocl rusticl; do
  if [ -e "/etc/OpenCL/vendors/$_clrt_icd.icd" ]; then ln -s "/etc/OpenCL/vendors/$_clrt_icd.icd" "$_clrt_icds/"; fi
done
export OCL_ICD_VENDORS="$_clrt_icds"
unset _clrt_san_dir _clrt_icds _clrt_icd
