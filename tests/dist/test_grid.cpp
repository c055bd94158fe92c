// test_grid.cpp - evaluation grids across ranks (dist/grid.hpp,
// dist/eval_grids.hpp): the row and image encoders round-trip every field;
// run_grid in a world of one is a plain loop; the distributed sweep and
// accuracy drivers give run_sweep's and measure_accuracy's rows; and
// `mpirun -np 3 clrt sweep|accuracy --json` reports what one process
// reports, timings aside (skipped where mpirun is not on PATH or clrt was
// built without MPI).
#include <catch2/catch.hpp>
#include <cstdlib>
#include <nlohmann/json.hpp>

#include "cli_run.hpp"
#include "dist/eval_grids.hpp"
#include "dist/eval_wire.hpp"
#include "dist/grid.hpp"
#include "dist/single_process.hpp"
#include "mpi_run.hpp"
#include "test_util.hpp"
#include "util/error.hpp"

// (clrt_tests is a unity build: each file's code is in a namespace of its own.)
namespace test_grid {

using namespace clrt;
using Catch::Matchers::Contains;
using Catch::Matchers::StartsWith;
using clrt_test::RunResult;
using clrt_test::TempDir;

namespace {

// Distinct values for every field, so a field read into another shows.
struct Counter {
  int n = 0;
  int i() { return ++n * 7 + 1; }
  double d() { return ++n * 1.375 + 0.0625; }
  std::string s() { return "text " + std::to_string(++n); }
  Stats stats() { return Stats{i(), d(), d(), d(), d(), d()}; }
};

Comparison fill_comparison(Counter& c) {
  Comparison x;
  x.pixels = size_t(c.i()), x.differ = size_t(c.i()), x.off_by_gt1 = size_t(c.i()), x.max_abs_8bit = c.i();
  x.rmse_8bit = c.d(), x.psnr_8bit = c.d(), x.max_abs_float = c.d(), x.rmse_float = c.d(), x.psnr_float = c.d();
  x.nan_inf = size_t(c.i()), x.nan_inf_reference = size_t(c.i()), x.hit_flips = size_t(c.i());
  x.shadow_flips = size_t(c.i()), x.worst_x = c.i(), x.worst_y = c.i();
  for (int k = 0; k < 3; ++k) x.worst_test[k] = uint8_t(c.i()), x.worst_reference[k] = uint8_t(c.i());
  return x;
}

void check_same(const Stats& a, const Stats& b) {
  CHECK(a.n == b.n);
  CHECK(a.median == b.median);
  CHECK(a.mean == b.mean);
  CHECK(a.sd == b.sd);
  CHECK(a.min == b.min);
  CHECK(a.max == b.max);
}

void check_same(const Comparison& a, const Comparison& b) {
  CHECK(a.pixels == b.pixels);
  CHECK(a.differ == b.differ);
  CHECK(a.off_by_gt1 == b.off_by_gt1);
  CHECK(a.max_abs_8bit == b.max_abs_8bit);
  CHECK(a.rmse_8bit == b.rmse_8bit);
  CHECK(a.psnr_8bit == b.psnr_8bit);
  CHECK(a.max_abs_float == b.max_abs_float);
  CHECK(a.rmse_float == b.rmse_float);
  CHECK(a.psnr_float == b.psnr_float);
  CHECK(a.nan_inf == b.nan_inf);
  CHECK(a.nan_inf_reference == b.nan_inf_reference);
  CHECK(a.hit_flips == b.hit_flips);
  CHECK(a.shadow_flips == b.shadow_flips);
  CHECK(a.worst_x == b.worst_x);
  CHECK(a.worst_y == b.worst_y);
  for (int k = 0; k < 3; ++k) {
    CHECK(a.worst_test[k] == b.worst_test[k]);
    CHECK(a.worst_reference[k] == b.worst_reference[k]);
  }
}

Image fill_image(Counter& c, int w, int h, FrameContents contents) {
  Image img(w, h, contents);
  for (auto& v : img.rgb) v = c.d();
  for (auto& v : img.rgba8) v = uint8_t(c.i());
  for (auto& v : img.unit) v = float(c.d());
  for (auto& v : img.hit) v = c.i() - 40;
  for (auto& v : img.shadowed) v = c.i();
  return img;
}

void check_same(const Image& a, const Image& b) {
  CHECK(a.width == b.width);
  CHECK(a.height == b.height);
  CHECK(a.contents == b.contents);
  CHECK(a.rgb == b.rgb);
  CHECK(a.rgba8 == b.rgba8);
  CHECK(a.unit == b.unit);
  CHECK(a.hit == b.hit);
  CHECK(a.shadowed == b.shadowed);
}

BenchResult fill_bench(Counter& c) {
  BenchResult b;
  b.device = c.s(), b.options = c.s();
  b.width = c.i(), b.height = c.i(), b.depth = c.i(), b.spp = c.i(), b.repeat = c.i();
  b.subsample = Subsample::Interpolate, b.rgba8 = true, b.tracers_not_run = c.s();
  b.omp_not_run = c.s();
  b.build_cold = c.stats(), b.build_warm = c.stats(), b.build_warm_cached = true, b.upload = c.stats();
  b.end_to_end_ms = c.d(), b.first_launch_ms = c.d();
  b.bvh = true, b.bvh_build_ms = c.d(), b.bvh_bytes = size_t(c.i()), b.bvh_depth = c.i();
  b.kernel_ms = {c.d(), c.d(), c.d()};
  b.kernel = c.stats(), b.launches = c.i(), b.host_timed_launches = c.i();
  b.frame = c.stats(), b.download = c.stats();
  for (int k = 0; k < 2; ++k) {
    DeviceShare s;
    s.device = c.s(), s.tiles = c.i(), s.rows = c.i(), s.kernel_ms = c.d(), s.host_timed_launches = c.i();
    s.busy_ms = c.d(), s.max_launch_ms = c.d();
    b.shares.push_back(s);
  }
  b.rays.primary = uint64_t(c.i()), b.rays.shadow = uint64_t(c.i()), b.rays.reflection = uint64_t(c.i());
  b.rays.sphere_tests = uint64_t(c.i()) << 33, b.rays.refraction = uint64_t(c.i());
  b.mrays_per_s = c.d(), b.ns_per_sphere_test = c.d(), b.gflops = c.d();
  for (int k = 0; k < 2; ++k) {
    PeakFlops p;
    p.measured = k == 0, p.gflops = c.d(), p.launch_ms = c.stats(), p.from_events = k == 1, p.note = c.s();
    b.peaks.push_back(p);
  }
  b.peak_gflops = c.d(), b.reference = c.stats(), b.speedup_vs_reference = c.d();
  b.omp = c.stats(), b.omp_threads = c.i(), b.speedup_vs_omp = c.stats(), b.kernel_speedup_vs_omp = c.stats();
  b.embree = c.stats(), b.embree_build = c.stats(), b.embree_build_ms = c.d(), b.embree_threads = c.i();
  b.speedup_vs_embree = c.stats(), b.embree_vs_omp_differ = c.d(), b.embree_vs_omp_max_levels = c.i();
  b.embree_vs_clrt_differ = c.d(), b.embree_vs_clrt_max_levels = c.i();
  b.image = fill_image(c, 3, 2, {PixelFormat::Float, true});
  b.reference_image = fill_image(c, 2, 3, {PixelFormat::Rgba8, false});
  return b;
}

void check_same(const BenchResult& a, const BenchResult& b) {
  CHECK(a.device == b.device);
  CHECK(a.options == b.options);
  CHECK(a.width == b.width);
  CHECK(a.height == b.height);
  CHECK(a.depth == b.depth);
  CHECK(a.spp == b.spp);
  CHECK(a.repeat == b.repeat);
  CHECK(a.subsample == b.subsample);
  CHECK(a.rgba8 == b.rgba8);
  CHECK(a.tracers_not_run == b.tracers_not_run);
  check_same(a.build_cold, b.build_cold);
  check_same(a.build_warm, b.build_warm);
  CHECK(a.build_warm_cached == b.build_warm_cached);
  check_same(a.upload, b.upload);
  CHECK(a.end_to_end_ms == b.end_to_end_ms);
  CHECK(a.first_launch_ms == b.first_launch_ms);
  CHECK(a.bvh == b.bvh);
  CHECK(a.bvh_build_ms == b.bvh_build_ms);
  CHECK(a.bvh_bytes == b.bvh_bytes);
  CHECK(a.bvh_depth == b.bvh_depth);
  CHECK(a.kernel_ms == b.kernel_ms);
  check_same(a.kernel, b.kernel);
  CHECK(a.launches == b.launches);
  CHECK(a.host_timed_launches == b.host_timed_launches);
  check_same(a.frame, b.frame);
  check_same(a.download, b.download);
  REQUIRE(a.shares.size() == b.shares.size());
  for (size_t k = 0; k < a.shares.size(); ++k) {
    CHECK(a.shares[k].device == b.shares[k].device);
    CHECK(a.shares[k].tiles == b.shares[k].tiles);
    CHECK(a.shares[k].rows == b.shares[k].rows);
    CHECK(a.shares[k].kernel_ms == b.shares[k].kernel_ms);
    CHECK(a.shares[k].host_timed_launches == b.shares[k].host_timed_launches);
    CHECK(a.shares[k].busy_ms == b.shares[k].busy_ms);
    CHECK(a.shares[k].max_launch_ms == b.shares[k].max_launch_ms);
  }
  CHECK(a.rays.primary == b.rays.primary);
  CHECK(a.rays.shadow == b.rays.shadow);
  CHECK(a.rays.reflection == b.rays.reflection);
  CHECK(a.rays.sphere_tests == b.rays.sphere_tests);
  CHECK(a.rays.refraction == b.rays.refraction);
  CHECK(a.mrays_per_s == b.mrays_per_s);
  CHECK(a.ns_per_sphere_test == b.ns_per_sphere_test);
  CHECK(a.gflops == b.gflops);
  REQUIRE(a.peaks.size() == b.peaks.size());
  for (size_t k = 0; k < a.peaks.size(); ++k) {
    CHECK(a.peaks[k].measured == b.peaks[k].measured);
    CHECK(a.peaks[k].gflops == b.peaks[k].gflops);
    check_same(a.peaks[k].launch_ms, b.peaks[k].launch_ms);
    CHECK(a.peaks[k].from_events == b.peaks[k].from_events);
    CHECK(a.peaks[k].note == b.peaks[k].note);
  }
  CHECK(a.peak_gflops == b.peak_gflops);
  check_same(a.reference, b.reference);
  CHECK(a.speedup_vs_reference == b.speedup_vs_reference);
  check_same(a.omp, b.omp);
  CHECK(a.omp_threads == b.omp_threads);
  check_same(a.speedup_vs_omp, b.speedup_vs_omp);
  check_same(a.kernel_speedup_vs_omp, b.kernel_speedup_vs_omp);
  check_same(a.embree, b.embree);
  check_same(a.embree_build, b.embree_build);
  CHECK(a.embree_build_ms == b.embree_build_ms);
  CHECK(a.embree_threads == b.embree_threads);
  check_same(a.speedup_vs_embree, b.speedup_vs_embree);
  CHECK(a.embree_vs_omp_differ == b.embree_vs_omp_differ);
  CHECK(a.embree_vs_omp_max_levels == b.embree_vs_omp_max_levels);
  CHECK(a.omp_not_run == b.omp_not_run);
  CHECK(a.embree_vs_clrt_differ == b.embree_vs_clrt_differ);
  CHECK(a.embree_vs_clrt_max_levels == b.embree_vs_clrt_max_levels);
  check_same(a.image, b.image);
  check_same(a.reference_image, b.reference_image);
}

// The bytes of a comparison: equal bytes, equal fields (doubles as bits).
dist::Bytes bytes_of(const Comparison& c) {
  dist::Writer w;
  dist::put_comparison(w, c);
  return w.bytes;
}

}  // namespace

TEST_CASE("sweep rows round-trip through bytes, every field", "[dist][grid][sweep]") {
  Counter c;
  SweepRow row;
  row.device = c.s(), row.device_index = c.i(), row.device_pd = c.s(), row.depth = c.i();
  row.bench = fill_bench(c);
  row.error = fill_comparison(c), row.change = fill_comparison(c);
  row.kernel_ms_delta = -c.d(), row.reference_ms = c.d(), row.speedup_vs_reference = c.d();
  const dist::Bytes bytes = dist::encode_sweep_row(row);
  const SweepRow back = dist::decode_sweep_row(bytes);
  CHECK(back.device == row.device);
  CHECK(back.device_index == row.device_index);
  CHECK(back.device_pd == row.device_pd);
  CHECK(back.depth == row.depth);
  check_same(back.bench, row.bench);
  check_same(back.error, row.error);
  check_same(back.change, row.change);
  CHECK(back.kernel_ms_delta == row.kernel_ms_delta);
  CHECK(back.reference_ms == row.reference_ms);
  CHECK(back.speedup_vs_reference == row.speedup_vs_reference);
  // Short or long messages are errors, never reads past the end.
  CHECK_THROWS_AS(dist::decode_sweep_row(dist::Bytes(bytes.begin(), bytes.end() - 1)), DeviceError);
  dist::Bytes longer = bytes;
  longer.push_back(0);
  CHECK_THROWS_AS(dist::decode_sweep_row(longer), DeviceError);
}

TEST_CASE("accuracy rows round-trip through bytes, every field", "[dist][grid][accuracy]") {
  Counter c;
  for (bool supported : {true, false}) {
    AccuracyRow row;
    row.scene = c.s(), row.variant = c.s(), row.depth = c.i(), row.supported = supported, row.note = c.s();
    if (supported) row.kernel_ms = {c.d(), c.d()};
    row.median_ms = c.d(), row.launches = c.i(), row.host_timed_launches = c.i();
    row.error = fill_comparison(c);
    const dist::Bytes bytes = dist::encode_accuracy_row(row);
    const AccuracyRow back = dist::decode_accuracy_row(bytes);
    CHECK(back.scene == row.scene);
    CHECK(back.variant == row.variant);
    CHECK(back.depth == row.depth);
    CHECK(back.supported == row.supported);
    CHECK(back.note == row.note);
    CHECK(back.kernel_ms == row.kernel_ms);
    CHECK(back.median_ms == row.median_ms);
    CHECK(back.launches == row.launches);
    CHECK(back.host_timed_launches == row.host_timed_launches);
    check_same(back.error, row.error);
    for (size_t cut : {size_t(1), size_t(9), bytes.size() / 2})
      CHECK_THROWS_AS(dist::decode_accuracy_row(dist::Bytes(bytes.begin(), bytes.end() - long(cut))), DeviceError);
  }
}

TEST_CASE("images round-trip through bytes, malformed image messages are errors", "[dist][grid]") {
  Counter c;
  for (const FrameContents contents :
       {FrameContents{PixelFormat::Float, true}, FrameContents{PixelFormat::Rgba8, false},
        FrameContents{PixelFormat::Rgba8, true}, FrameContents{PixelFormat::Unit, false}}) {
    const Image img = fill_image(c, 5, 3, contents);
    check_same(dist::decode_image(dist::encode_image(img)), img);
  }
  check_same(dist::decode_image(dist::encode_image(Image())), Image());
  // Buffers that do not fit the size: a 5x3 image's colour said to be 4x3.
  dist::Bytes b = dist::encode_image(fill_image(c, 5, 3, {PixelFormat::Float, false}));
  const int32_t four = 4;
  std::memcpy(b.data(), &four, sizeof four);
  CHECK_THROWS_AS(dist::decode_image(b), DeviceError);
  // A length beyond the message.
  dist::Bytes huge = dist::encode_image(Image(2, 2, {PixelFormat::Float, false}));
  huge.resize(huge.size() - 8);
  CHECK_THROWS_AS(dist::decode_image(huge), DeviceError);
}

TEST_CASE("run_grid in a world of one: every cell once, in order, on the calling thread", "[dist][grid]") {
  dist::SingleProcess one;
  std::vector<int> computed, gathered;
  std::vector<std::pair<int, int>> progress;
  dist::GridSettings g;
  g.progress = [&](int done, int total, const std::string&) { progress.emplace_back(done, total); };
  dist::GridStats stats;
  dist::run_grid(
      one, 4,
      [&](int cell) {
        computed.push_back(cell);
        return dist::Bytes(size_t(cell), uint8_t(cell));
      },
      [&](int cell, dist::Bytes&& b) {
        CHECK(b == dist::Bytes(size_t(cell), uint8_t(cell)));
        gathered.push_back(cell);
      },
      g, &stats);
  CHECK(computed == std::vector<int>{0, 1, 2, 3});
  CHECK(gathered == std::vector<int>{0, 1, 2, 3});
  CHECK(progress.front() == std::make_pair(0, 4));
  CHECK(progress.back() == std::make_pair(4, 4));
  REQUIRE(stats.ranks.size() == 1);
  CHECK(stats.ranks[0].units == 4);
  CHECK(stats.cells == 4);
  // A cell's failure is the caller's exception.
  CHECK_THROWS_AS(dist::run_grid(
                      one, 2, [](int) -> dist::Bytes { throw UserError("no"); }, [](int, dist::Bytes&&) {}),
                  UserError);
}

TEST_CASE("the grid drivers give run_sweep's and measure_accuracy's rows (a world of one)",
          "[dist][grid][sweep][accuracy][opencl][slow]") {
  dist::SingleProcess one;
  const DeviceInfo dev = clrt_test::test_device();
  const Scene scene = clrt_test::load("scenes/cgfs-demo.json");
  SECTION("sweep") {
    SweepSettings s;
    s.bench.width = 20, s.bench.height = 14, s.bench.repeat = 1;
    s.bench.omp = s.bench.embree = s.bench.builds = false;
    s.depth_from = 0, s.depth_to = 2;
    const RenderSettings settings;
    const auto single = run_sweep(scene, {dev}, settings, s);
    dist::SweepInput in{dist::decode_scene(dist::encode_scene(scene)), 0, 2, {dist::device_label(dev)}};
    const auto grid = dist::sweep_across_ranks(
        one, in, [&] { return std::vector<DeviceInfo>{dev}; }, settings, s, nullptr);
    REQUIRE(grid.size() == single.size());
    for (size_t i = 0; i < grid.size(); ++i) {
      INFO("row " << i);
      CHECK(grid[i].device == single[i].device);
      CHECK(grid[i].device_index == single[i].device_index);
      CHECK(grid[i].device_pd == single[i].device_pd);
      CHECK(grid[i].depth == single[i].depth);
      CHECK(grid[i].bench.rays.total() == single[i].bench.rays.total());
      CHECK(grid[i].bench.image.pixels() == 0);  // dropped, as run_sweep drops it
      CHECK(bytes_of(grid[i].error) == bytes_of(single[i].error));
      CHECK(bytes_of(grid[i].change) == bytes_of(single[i].change));
    }
    CHECK(grid[1].change.differ > 0);  // depth 1 reflects what depth 0 does not
  }
  SECTION("accuracy") {
    AccuracySettings s;
    s.width = 20, s.height = 14, s.repeat = 2;
    s.variants = {parse_accuracy_variant("naive"), parse_accuracy_variant("robust+subsample-interpolate"),
                  parse_accuracy_variant("fp64")};
    const std::vector<NamedScene> scenes{{"demo", scene}, {"glass", clrt_test::load("scenes/glass.json")}};
    const auto single = measure_accuracy(scenes, dev, s);
    const auto grid = dist::accuracy_across_ranks(
        one, dist::AccuracyInput{scenes, dist::device_label(dev)}, [&] { return dev; }, s, nullptr);
    REQUIRE(grid.size() == single.size());
    for (size_t i = 0; i < grid.size(); ++i) {
      INFO("row " << i);
      CHECK(grid[i].scene == single[i].scene);
      CHECK(grid[i].variant == single[i].variant);
      CHECK(grid[i].depth == single[i].depth);
      CHECK(grid[i].supported == single[i].supported);
      CHECK(grid[i].note == single[i].note);
      CHECK(grid[i].kernel_ms.size() == single[i].kernel_ms.size());
      CHECK(bytes_of(grid[i].error) == bytes_of(single[i].error));
    }
  }
}

TEST_CASE("a rank whose devices differ from rank 0's is refused", "[dist][grid]") {
  DeviceInfo a, b;
  a.name = "A", b.name = "B";
  CHECK_NOTHROW(dist::check_same_devices({a, b}, {dist::device_label(a), dist::device_label(b)}, "--devices"));
  CHECK_THROWS_WITH(dist::check_same_devices({b}, {dist::device_label(a)}, "--device"),
                    Contains("--device selects B on this rank but A on rank 0"));
  CHECK_THROWS_AS(dist::check_same_devices({a}, {dist::device_label(a), dist::device_label(b)}, "--devices"),
                  UserError);
}

// ---- under mpirun ------------------------------------------------------------

namespace {

using clrt_test::clrt_lines;
using clrt_test::run_mpi;
bool have_mpirun() {
  return clrt_test::can_run_mpi();
}

// A report without what differs from run to run: the header's timestamp,
// mpi_ranks, and every timed figure of the rows.
nlohmann::json untimed(nlohmann::json j, const std::vector<std::string>& timed) {
  j.erase("timestamp_utc");
  j.erase("mpi_ranks");
  for (auto& row : j["rows"])
    for (const auto& k : timed) row.erase(k);
  return j;
}

const std::vector<std::string> kSweepTimed = {
    "kernel_ms_median", "kernel_ms_min",        "kernel_ms_max",      "kernel_ms_mean",
    "kernel_ms_sd",     "kernel_time_source",   "kernel_ms_delta",    "frame_ms_median",
    "frame_ms_mean",    "frame_ms_sd",          "build_warm_ms",      "upload_ms",
    "download_ms",      "mrays_per_s",          "ns_per_sphere_test", "gflops",
    "reference_ms",     "speedup_vs_reference", "omp_ms_median",      "opencl_speedup_vs_omp"};
const std::vector<std::string> kAccuracyTimed = {"kernel_ms_median", "kernel_ms", "kernel", "kernel_time_source"};

}  // namespace

TEST_CASE("mpirun -np 3 clrt sweep and accuracy --json: the single-process report, timings aside",
          "[dist][grid][mpi-cli]") {
  if (!have_mpirun()) {
    WARN("skipped: mpirun not on PATH or clrt built without MPI");
    return;
  }
  const std::vector<std::string> size = {"--width", "24", "--height", "24", "--repeat", "2"};
  SECTION("sweep: 4 depths") {
    std::vector<std::string> args = {"sweep", clrt_test::source_path("scenes/cgfs-demo.json"), "--depths", "0:3",
                                     "--json"};
    args.insert(args.end(), size.begin(), size.end());
    const RunResult one = clrt_test::run_clrt(args);
    REQUIRE(one.status == 0);
    const RunResult three = run_mpi(3, args);
    INFO("stdout: " << three.out << "\nstderr: " << three.err);
    REQUIRE(three.status == 0);
    const auto a = nlohmann::json::parse(one.out), b = nlohmann::json::parse(three.out);
    CHECK_FALSE(a.contains("mpi_ranks"));
    CHECK(b["mpi_ranks"] == 3);
    REQUIRE(b["rows"].size() == 4);
    CHECK(b["rows"][3]["depth"] == 3);
    CHECK(untimed(a, kSweepTimed) == untimed(b, kSweepTimed));
    CHECK(b["rows"][2]["change"]["pixels_differ"].get<long>() > 0);
  }
  SECTION("accuracy: 2 scenes x 3 variants") {
    std::vector<std::string> args = {
        "accuracy",   clrt_test::source_path("scenes/cgfs-demo.json"), clrt_test::source_path("scenes/glass.json"),
        "--variants", "naive,robust,robust+subsample-interpolate",     "--json"};
    args.insert(args.end(), size.begin(), size.end());
    const RunResult one = clrt_test::run_clrt(args);
    REQUIRE(one.status == 0);
    const RunResult three = run_mpi(3, args);
    INFO("stdout: " << three.out << "\nstderr: " << three.err);
    REQUIRE(three.status == 0);
    const auto a = nlohmann::json::parse(one.out), b = nlohmann::json::parse(three.out);
    CHECK(b["mpi_ranks"] == 3);
    REQUIRE(b["rows"].size() == 6);
    CHECK(b["rows"][5]["variant"] == "robust+subsample-interpolate");
    CHECK(b["rows"][5]["kernel_ms"].size() == 2);
    CHECK(untimed(a, kAccuracyTimed) == untimed(b, kAccuracyTimed));
  }
  SECTION("the table says how many ranks timed it, and each rank's share") {
    std::vector<std::string> args = {"sweep", clrt_test::source_path("scenes/cgfs-demo.json"), "--depths", "0:1"};
    args.insert(args.end(), size.begin(), size.end());
    const RunResult r = run_mpi(3, args);
    INFO("stdout: " << r.out << "\nstderr: " << r.err);
    REQUIRE(r.status == 0);
    CHECK_THAT(r.out, StartsWith("3 MPI ranks: each (depth, device) timed on the rank that ran it"));
    for (int rank = 0; rank < 3; ++rank) CHECK_THAT(r.out, Contains("  rank " + std::to_string(rank) + " ("));
  }
}

TEST_CASE("mpirun sweep and accuracy: a failure is one error line, exit 2, and no output file",
          "[dist][grid][mpi-cli]") {
  if (!have_mpirun()) {
    WARN("skipped: mpirun not on PATH or clrt built without MPI");
    return;
  }
  TempDir dir;
  SECTION("a bad scene: found by rank 0 before any cell") {
    const RunResult r = run_mpi(3, {"accuracy", clrt_test::source_path("scenes/cgfs-demo.json"),
                                    dir.write("bad.json", "{"), "--csv", dir / "a.csv"});
    INFO("stdout: " << r.out << "\nstderr: " << r.err);
    CHECK(r.status == 2);
    const auto lines = clrt_lines(r.err);
    REQUIRE(lines.size() == 1);
    CHECK_THAT(lines[0], StartsWith("clrt: error: " + dir / "bad.json"));
    CHECK(dir.entries() == std::vector<std::string>{"bad.json"});  // no CSV
  }
  SECTION("every rank fails at its first bench cell (a work-group size no device allows)") {
    const RunResult r =
        run_mpi(3, {"sweep", clrt_test::source_path("scenes/cgfs-demo.json"), "--depths", "0:4", "--width", "24",
                    "--height", "24", "--repeat", "1", "--local", "4096x4096", "--csv", dir / "s.csv"});
    INFO("stdout: " << r.out << "\nstderr: " << r.err);
    CHECK(r.status == 2);
    const auto lines = clrt_lines(r.err);
    REQUIRE(lines.size() == 1);
    CHECK_THAT(lines[0], StartsWith("clrt: error: rank "));
    CHECK_THAT(lines[0], Contains("4096x4096"));
    CHECK(dir.entries().empty());  // no CSV
  }
}

}  // namespace test_grid
