// test_pocl_workers.cpp - when clrt pins PoCL's worker threads
// (cl/pocl_workers.hpp): the rule, and what a clrt process reports.
#include <unistd.h>

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include "cl/pocl_workers.hpp"
#include "cli_run.hpp"
#include "test_util.hpp"

// (clrt_tests is a unity build: each file's code is in a namespace of its own.)
namespace test_pocl_workers {

using namespace clrt;

TEST_CASE("PoCL's workers are pinned only where every CPU is the process's and the user chose nothing",
          "[pocl-workers]") {
  const std::vector<int> two{0, 1}, four{0, 1, 2, 3};
  CHECK(should_pin_pocl_workers(nullptr, nullptr, two, 2));
  CHECK(should_pin_pocl_workers(nullptr, nullptr, four, 4));
  // the user's own setting, either way, and a thread count of the user's
  CHECK_FALSE(should_pin_pocl_workers("0", nullptr, two, 2));
  CHECK_FALSE(should_pin_pocl_workers("1", nullptr, two, 2));
  CHECK_FALSE(should_pin_pocl_workers("", nullptr, two, 2));
  CHECK_FALSE(should_pin_pocl_workers(nullptr, "1", two, 2));
  // a process bound to some CPUs (taskset, mpirun's binding): worker i
  // would be pinned to CPU i, outside its mask or beside another rank's
  CHECK_FALSE(should_pin_pocl_workers(nullptr, nullptr, {0}, 2));
  CHECK_FALSE(should_pin_pocl_workers(nullptr, nullptr, {1, 2, 3}, 4));
  CHECK_FALSE(should_pin_pocl_workers(nullptr, nullptr, {0, 1, 3}, 3));  // (CPU 2 offline: ids not 0..n-1)
  // one CPU: nothing to balance
  CHECK_FALSE(should_pin_pocl_workers(nullptr, nullptr, {0}, 1));
}

// POCL_AFFINITY as `clrt bench --json` reports it, in a process started
// with `env` before the command.
std::string reported_affinity(const std::string& env) {
  const auto r = clrt_test::run_clrt(
      {"bench", clrt_test::source_path("scenes/cgfs-demo.json"), "--device", "pthread", "--width", "16", "--height",
       "16", "--repeat", "1", "--no-omp", "--no-embree", "--no-reference", "--json"},
      env);
  REQUIRE(r.status == 0);
  return nlohmann::json::parse(r.out).at("pocl_affinity").get<std::string>();
}

TEST_CASE("a clrt process sets POCL_AFFINITY=1 where the rule says so, and keeps the user's", "[pocl-workers]") {
  CHECK(reported_affinity("env POCL_AFFINITY=0") == "0");
  CHECK(reported_affinity("env -u POCL_AFFINITY POCL_MAX_PTHREAD_COUNT=1") == "unset");
  // Unset: the rule on this process's CPUs (a child inherits its mask).
  const std::vector<int> allowed = process_cpus();
  REQUIRE(!allowed.empty());
  const bool pinned = should_pin_pocl_workers(nullptr, nullptr, allowed, sysconf(_SC_NPROCESSORS_ONLN));
  CHECK(reported_affinity("env -u POCL_AFFINITY -u POCL_MAX_PTHREAD_COUNT") == (pinned ? "1" : "unset"));
}

}  // namespace test_pocl_workers
