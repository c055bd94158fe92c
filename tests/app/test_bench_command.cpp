// test_bench_command.cpp - `clrt bench --json` and `clrt sweep --csv --plot`:
// the keys, rows and files the commands promise (on the test device).
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "cl/program.hpp"
#include "cli_run.hpp"
#include "eval/bench.hpp"
#include "test_util.hpp"

// (clrt_tests is a unity build: each file's code is in a namespace of its own.)
namespace test_bench_command {

namespace {

// The field of `row` in the column `name` of `header` ("?" when there is
// none); no field of the rows these tests read holds a comma.
std::string csv_column(const std::string& header, const std::string& row, const std::string& name) {
  std::istringstream h(header), v(row);
  std::string hn, vv;
  while (std::getline(h, hn, ',') && std::getline(v, vv, ','))
    if (hn == name) return vv;
  return "?";
}

}  // namespace

TEST_CASE("clrt bench --json reports the documented keys", "[cli][bench][opencl]") {
  // 320x240: launches of about a millisecond, so that a loaded machine's
  // scheduling delay cannot make PoCL's events look implausibly short
  // against the host's wait (launch_timing.hpp: under 1% of a wait >= 1 ms;
  // at 40x30 a 1.2 ms wait for a 10 us kernel did, under ASan in CI).
  auto r = clrt_test::run_clrt({"bench", clrt_test::source_path("scenes/cgfs-demo.json"), "--width", "320", "--height",
                                "240", "--depth", "1", "--repeat", "2", "--json", "-D", "spheres.1.specular=10"});
  INFO(r.err);
  REQUIRE(r.status == 0);
  auto j = nlohmann::json::parse(r.out);
  CHECK(j["overrides"] == nlohmann::json::parse(R"({"spheres.1.specular": 10})"));
  for (const char* k : {"kernel_ms_median",
                        "kernel_ms_min",
                        "kernel_ms_max",
                        "rays_total",
                        "rays_primary",
                        "rays_shadow",
                        "rays_reflection",
                        "rays_refraction",
                        "mrays_per_s",
                        "reference_ms",
                        "omp_ms_median",
                        "opencl_speedup_vs_omp",
                        "build_cold_ms",
                        "build_warm_ms",
                        "upload_ms",
                        "download_ms",
                        "end_to_end_ms",
                        "gflops",
                        "peak_gflops",
                        "ns_per_sphere_test",
                        "embree_ms_median",
                        "embree_build_ms",
                        "embree_threads",
                        "opencl_speedup_vs_embree",
                        "embree_vs_omp_differ",
                        "embree_vs_omp_max_levels"})
    CHECK(j.contains(k));
  CHECK(j["kernel_ms"].size() == 2);
  // Warm builds load clrt's cached binary, or, where the driver keeps its
  // programs itself (PoCL), come from the driver's cache (cl/program.hpp).
  const bool driver_keeps = driver_caches_programs(clrt_test::test_device());
  CHECK(j["build_warm_cached"] == !driver_keeps);
  CHECK(j["build_warm_driver_cached"] == driver_keeps);
  // Every timed figure comes with N, median, mean, sd, min and max, each
  // name with its unit: ms for times, ratio for speedups.
  for (const std::string k :
       {"kernel", "frame", "download", "omp", "speedup_vs_omp", "kernel_speedup_vs_omp", "build_cold", "build_warm",
        "upload", "reference", "embree", "embree_build", "speedup_vs_embree"}) {
    INFO(k);
    REQUIRE(j.contains(k));
    const std::string u = k.find("speedup") != std::string::npos ? "_ratio" : "_ms";
    CHECK(j[k].contains("n"));
    for (const char* f : {"median", "mean", "sd", "min", "max"}) CHECK(j[k].contains(f + u));
    CHECK(j[k]["min" + u].get<double>() <= j[k]["median" + u].get<double>());
    CHECK(j[k]["median" + u].get<double>() <= j[k]["max" + u].get<double>());
  }
  CHECK(j["frame"]["n"] == 2);
  CHECK(j["omp"]["n"] == 2);
  CHECK(j["embree"]["n"] == 2);  // one Embree frame per round, its build apart
  CHECK(j["embree_build"]["n"] == 2);
  CHECK(j["speedup_vs_embree"]["n"] == 2);
  CHECK(j["opencl_speedup_vs_embree"] == j["speedup_vs_embree"]["median_ratio"]);
  CHECK(j["embree_build_ms"] == j["embree_build"]["median_ms"]);
  // The Embree tracer draws the OpenMP tracer's image (tests/eval/test_embree_tracer.cpp).
  CHECK(j["embree_vs_omp_differ"] == 0);
  CHECK(j["embree_vs_omp_max_levels"].get<int>() <= 1);
  CHECK(j["build_cold"]["n"] == 2);  // min(--repeat, 3)
  // The headline ratio is frame against frame: the same work on both sides.
  CHECK(j["opencl_speedup_vs_omp"] == j["speedup_vs_omp"]["median_ratio"]);
  CHECK(j["kernel"]["median_ms"].get<double>() <= j["frame"]["median_ms"].get<double>());
  // PoCL's events are plausible; the peak is measured, not assumed.
  CHECK(j["kernel_time_source"] == "events");
  REQUIRE(j["peaks"].size() == 1);
  CHECK(j["peaks"][0]["measured"] == true);
  CHECK(j["peak_gflops"].get<double>() > 0);
  // Every pixel shoots one primary ray; the totals add up.
  CHECK(j["rays_primary"] == 320 * 240);
  CHECK(j["rays_total"].get<uint64_t>() == j["rays_primary"].get<uint64_t>() + j["rays_shadow"].get<uint64_t>() +
                                               j["rays_reflection"].get<uint64_t>() +
                                               j["rays_refraction"].get<uint64_t>());
}

TEST_CASE("clrt bench --no-embree, --no-omp and --no-reference drop their comparisons", "[cli][bench][opencl]") {
  const std::vector<std::string> base = {"bench",    clrt_test::source_path("scenes/cgfs-demo.json"),
                                         "--width",  "24",
                                         "--height", "16",
                                         "--depth",  "1",
                                         "--repeat", "1"};
  auto with = [&](std::vector<std::string> extra) {
    std::vector<std::string> args = base;
    args.insert(args.end(), extra.begin(), extra.end());
    return clrt_test::run_clrt(args);
  };
  auto j_run = with({"--no-embree", "--json"});
  INFO(j_run.err);
  REQUIRE(j_run.status == 0);
  auto j = nlohmann::json::parse(j_run.out);
  CHECK(j["embree"]["n"] == 0);
  CHECK(j["omp"]["n"] == 1);
  CHECK(j["embree_vs_omp_differ"].is_null());  // not checked, and says so
  auto text = with({"--no-omp"});
  INFO(text.err);
  REQUIRE(text.status == 0);
  CHECK(text.out.find("OpenMP float") == std::string::npos);
  CHECK(text.out.find("Embree float") != std::string::npos);
  CHECK(text.out.find("(Embree frame / clrt frame") != std::string::npos);
  CHECK(text.out.find("not checked") != std::string::npos);
  auto no_reference = with({"--no-reference", "--json"});
  INFO(no_reference.err);
  REQUIRE(no_reference.status == 0);
  auto k = nlohmann::json::parse(no_reference.out);
  CHECK(k["reference"]["n"] == 0);
  CHECK(j["reference"]["n"] == 1);
}

TEST_CASE("clrt sweep writes one CSV row per depth and both plots", "[cli][sweep][opencl][slow]") {
  clrt_test::TempDir dir;
  auto r =
      clrt_test::run_clrt({"sweep", clrt_test::source_path("scenes/cgfs-demo.json"), "--depths", "0:2", "--width", "32",
                           "--height", "24", "--repeat", "1", "--csv", dir / "s.csv", "--plot", dir / "s.png"});
  INFO(r.err);
  REQUIRE(r.status == 0);
  CHECK(r.err.find('\r') == std::string::npos);  // no progress bar when stderr is not a terminal
  std::istringstream csv(clrt_test::slurp(dir / "s.csv"));
  std::string header, line;
  std::getline(csv, header);
  std::vector<std::string> rows;
  while (std::getline(csv, line)) rows.push_back(line);
  REQUIRE(rows.size() == 3);
  // The report header's columns first (docs/guide/output.md).
  CHECK(header.rfind("clrt_version,timestamp_utc,device_driver,device,depth,kernel_ms_median", 0) == 0);
  CHECK(header.find(",error_pixels_off_by_gt1,") != std::string::npos);
  // Depth 0 traces no reflection ray: the rays_reflection column is 0.
  auto column = [&](const std::string& row, const std::string& name) { return csv_column(header, row, name); };
  CHECK(column(rows[0], "depth") == "0");
  CHECK(column(rows[0], "rays_reflection") == "0");
  CHECK(column(rows[0], "rays_primary") == "768");
  CHECK(column(rows[2], "depth") == "2");
  CHECK(std::filesystem::file_size(dir / "s.png") > 0);
  CHECK(std::filesystem::file_size(dir / "s-rays.png") > 0);
}

TEST_CASE("clrt scaling writes one CSV row per count and a log-log plot", "[cli][bench][opencl][slow]") {
  clrt_test::TempDir dir;
  auto r = clrt_test::run_clrt({"scaling", "--spheres", "8,40", "--width", "24", "--height", "16", "--repeat", "1",
                                "--csv", dir / "s.csv", "--plot", dir / "s.png"});
  INFO(r.err);
  REQUIRE(r.status == 0);
  CHECK(r.out.find("Embree/clrt") != std::string::npos);
  std::ifstream csv(dir / "s.csv");
  std::string header, line;
  REQUIRE(std::getline(csv, header));
  CHECK(header.rfind("clrt_version,timestamp_utc,device_driver,device,spheres,triangles,json_bytes,parse_ms,", 0) == 0);
  std::vector<std::string> rows;
  while (std::getline(csv, line)) rows.push_back(line);
  REQUIRE(rows.size() == 2);
  auto column = [&](const std::string& row, const std::string& name) { return csv_column(header, row, name); };
  CHECK(column(rows[0], "spheres") == "8");
  CHECK(column(rows[1], "spheres") == "40");
  // 8 spheres (and the floor) test every sphere; 40 walk the hierarchy
  // (kBvhMinSpheres = 32): bvh_bytes.
  CHECK(column(rows[0], "bvh_bytes") == "0");
  CHECK(std::stod(column(rows[1], "bvh_bytes")) > 0);
  CHECK(std::filesystem::file_size(dir / "s.png") > 1000);
}

TEST_CASE("clrt scaling --triangles loads a grid of tori and checks Embree's image against clrt's",
          "[cli][bench][opencl][slow]") {
  clrt_test::TempDir dir;
  auto r = clrt_test::run_clrt(
      {"scaling", "--triangles", "300", "--width", "48", "--height", "32", "--repeat", "1", "--csv", dir / "m.csv"});
  INFO(r.err);
  REQUIRE(r.status == 0);
  CHECK(r.out.find("mesh scenes") != std::string::npos);
  std::ifstream csv(dir / "m.csv");
  std::string header, row;
  REQUIRE(std::getline(csv, header));
  REQUIRE(std::getline(csv, row));
  auto column = [&](const std::string& name) { return std::stod(csv_column(header, row, name)); };
  // Only the mesh scene runs (no --spheres): at most 300 triangles (one
  // torus of 18 x 8 quads: 288).
  CHECK(column("spheres") == 0);
  CHECK(column("triangles") <= 300);
  CHECK(column("triangles") >= 250);
  CHECK(column("prepare_ms") > 0);
  CHECK(column("embree_build_once_ms") > 0);
  // The same picture: bench's tolerance (eval/bench.hpp), 1% of the pixels.
  CHECK(column("embree_vs_clrt_differ") >= 0);
  CHECK(column("embree_vs_clrt_differ") <= clrt::kEmbreeVsClrtTolerance);
}

TEST_CASE("clrt scaling rejects bad counts before measuring", "[cli]") {
  for (const char* counts : {"0", "abc", "1,,2", "1,", "-5", "3000000", "1e3"}) {
    INFO(counts);
    auto r = clrt_test::run_clrt({"scaling", "--spheres", counts, "--width", "8", "--height", "8"});
    CHECK(r.status == 2);
    CHECK(r.one_line_error());
    CHECK(r.err.find("clrt: error: --spheres") == 0);
  }
  for (const char* counts : {"0", "4000001", "1,"}) {
    INFO(counts);
    auto r = clrt_test::run_clrt({"scaling", "--triangles", counts, "--width", "8", "--height", "8"});
    CHECK(r.status == 2);
    CHECK(r.one_line_error());
    CHECK(r.err.find("clrt: error: --triangles") == 0);
  }
}

}  // namespace test_bench_command
