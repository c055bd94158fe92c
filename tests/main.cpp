// main.cpp - Catch2 (v2) entry point. The program binary cache is pointed at
// a fresh temporary directory for the whole test process (unless the caller
// set CLRT_CACHE_DIR), so tests never read or fill the user's cache, and
// PoCL's workers are left unpinned.
#define CATCH_CONFIG_RUNNER
#include <catch2/catch.hpp>
#include <cstdlib>

#include "cli_run.hpp"
#include "dist/communicator.hpp"

int main(int argc, char** argv) {
  // PoCL's workers free to move (unless the caller chose): tests run several
  // processes at once, and pinned workers cannot share the cores out among
  // them (the fast tier: 97-107 s pinned, 92-95 s not, cl/pocl_workers.hpp).
  ::setenv("POCL_AFFINITY", "0", 0);
  // Under mpirun (the [mpi] tests, ctest's mpi_tests_3_ranks): every rank
  // runs the same tests together; otherwise a world of one.
  clrt::dist::Session mpi(argc, argv);
  const char* set = std::getenv("CLRT_CACHE_DIR");
  std::unique_ptr<clrt_test::TempDir> cache;
  if (!set || !*set) {
    cache = std::make_unique<clrt_test::TempDir>();
    ::setenv("CLRT_CACHE_DIR", cache->path().c_str(), 1);
  }
  return Catch::Session().run(argc, argv);
}
