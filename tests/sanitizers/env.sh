# env.sh - sanitizer runtime options for the -DCLRT_SANITIZE=ON build. Source
# it before ctest: `. tests/sanitizers/env.sh && ctest --test-dir build-asan`.
# docs/sanitizers.md explains every option and suppression.
_clrt_san_dir=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
export ASAN_OPTIONS="halt_on_error=1:detect_leaks=1:strict_init_order=1:check_initialization_order=1"
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1"
export LSAN_OPTIONS="suppressions=${_clrt_san_dir}/lsan.supp:print_suppressions=0"
unset _clrt_san_dir
