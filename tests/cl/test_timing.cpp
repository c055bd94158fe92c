// test_timing.cpp - the profiling-event plausibility rule (launch_timing.hpp)
// and bench on a driver whose events are implausible (Mesa rusticl, when
// installed and enabled as in CI).
#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include "cl/launch_timing.hpp"
#include "cli_run.hpp"
#include "test_util.hpp"

// (clrt_tests is a unity build: each file's code is in a namespace of its own.)
namespace test_timing {

using namespace clrt;

TEST_CASE("plausible event times are kept", "[timing]") {
  // A kernel that took most of the host's wait.
  LaunchTime t = launch_time(24.0, 25.3);
  CHECK(t.from_events);
  CHECK(t.ms == 24.0);
  // Launch overhead dominating a tiny launch: 0.01 ms kernel in a 0.3 ms wait.
  CHECK(launch_time(0.01, 0.3).from_events);
  // 2% of a 10 ms wait is still possible (queueing, first-launch work).
  CHECK(launch_time(0.2, 10).from_events);
  // Clock granularity: an event marginally longer than the host wait.
  CHECK(launch_time(10.04, 10.0).from_events);
}

TEST_CASE("implausible event times fall back to the host wall time", "[timing]") {
  // What rusticl on llvmpipe reports: ~1 ns for a 35 ms launch.
  LaunchTime t = launch_time(1e-6, 35.0);
  CHECK_FALSE(t.from_events);
  CHECK(t.ms == 35.0);
  CHECK(t.event_ms == 1e-6);
  // Zero, negative (END before START), NaN, and longer than the host waited.
  CHECK_FALSE(launch_time(0, 5).from_events);
  CHECK_FALSE(launch_time(-3, 5).from_events);
  CHECK_FALSE(launch_time(std::nan(""), 5).from_events);
  CHECK_FALSE(launch_time(20, 10).from_events);
  CHECK(launch_time(20, 10).ms == 10);
  // Below 1% of a wait of at least 1 ms.
  CHECK_FALSE(launch_time(0.009, 1.0).from_events);
  CHECK(launch_time(0.011, 1.0).from_events);
}

TEST_CASE("a total says where its time came from", "[timing]") {
  CHECK(time_source(0, 5) == "events");
  CHECK(time_source(5, 5) == "host");
  CHECK(time_source(2, 5) == "mixed");
  CHECK(time_source_note(0, 5).empty());
  CHECK(time_source_note(5, 5).find("host wall clock") != std::string::npos);
  CHECK(time_source_note(2, 5).find("2 of 5") != std::string::npos);
}

namespace {
// Mesa rusticl's llvmpipe device, enabled for the clrt run that uses it.
const std::string kRusticl = "RUSTICL_ENABLE=${RUSTICL_ENABLE:-swrast}";
bool has_rusticl() {
  auto r = clrt_test::run_clrt({"devices"}, kRusticl);
  return r.status == 0 && r.out.find("rusticl") != std::string::npos;
}
}  // namespace

TEST_CASE("bench on rusticl: plausible times, and it says which clock", "[timing][cli][bench][slow]") {
  if (!has_rusticl()) {
    WARN("no rusticl device (install mesa-opencl-icd, set RUSTICL_ENABLE=swrast); skipped");
    return;
  }
  auto r = clrt_test::run_clrt({"bench", clrt_test::source_path("scenes/cgfs-demo.json"), "--device", "rusticl",
                                "--width", "96", "--height", "64", "--repeat", "3", "--json"},
                               kRusticl);
  INFO(r.err);
  REQUIRE(r.status == 0);
  auto j = nlohmann::json::parse(r.out);
  const std::string source = j["kernel_time_source"];
  INFO("kernel_time_source " << source);
  CHECK((source == "events" || source == "host" || source == "mixed"));
  // Whatever the source, the kernel time is plausible against the frame it
  // is part of (the rule of launch_timing.hpp), so the derived throughput is.
  const double kernel = j["kernel"]["median_ms"], frame = j["frame"]["median_ms"];
  CHECK(kernel >= 0.01 * frame);
  CHECK(kernel <= 1.1 * frame + 0.05);
  CHECK(j["host_timed_launches"].get<int>() <= j["launches"].get<int>());
  // Rays per second from a plausible time: at most ~1e4 Mrays/s for a CPU
  // driver rendering 96x64 (the ~1 ns events gave 1.5e9 Mrays/s).
  CHECK(j["mrays_per_s"].get<double>() < 1e4);
  // The text output names the clock when it is not the events.
  auto text = clrt_test::run_clrt({"bench", clrt_test::source_path("scenes/cgfs-demo.json"), "--device", "rusticl",
                                   "--width", "96", "--height", "64", "--repeat", "2", "--no-omp"},
                                  kRusticl);
  REQUIRE(text.status == 0);
  if (source == "host") CHECK(text.out.find("host wall clock") != std::string::npos);
}

}  // namespace test_timing
