// test_frames_mpi.cpp - many frames over the ranks of a job
// (dist/frame_queue.hpp, `clrt render S1 S2 ... -o f_##.ppm`).
//
// [mpi] cases run as one process (ctest) and, under `mpirun -np 3
// clrt_tests "[mpi]"`, on every rank together: each frame is delivered once
// with the pixels of one process's render, in bands too, and a failure on
// any rank (or in rank 0's writing) ends every rank.
//
// [mpi-cli] cases run `mpirun --oversubscribe -np 3 clrt render S1 ... S5 -o
// f_##.ppm` and check each frame's pixels against a single-process render of
// its scene (the files' metadata differ: the device says which rank
// rendered it), each rank's share in the report, and that a failure on the
// ranks is one error line, exit 2, and no frame. Skipped where mpirun is not
// on PATH or clrt was built without MPI.
#include <catch2/catch.hpp>
#include <cstdlib>
#include <filesystem>
#include <memory>

#include "cli_run.hpp"
#include "dist/communicator.hpp"
#include "dist/frame_queue.hpp"
#include "dist/job.hpp"
#include "flat_scene.hpp"
#include "image/image_file.hpp"
#include "mpi_run.hpp"
#include "scene/builtin_scene.hpp"
#include "test_util.hpp"
#include "util/error.hpp"

// (clrt_tests is a unity build: each file's code is in a namespace of its own.)
namespace test_frames_mpi {

using Catch::Matchers::Contains;
using Catch::Matchers::StartsWith;
using clrt_test::RunResult;
using clrt_test::TempDir;
namespace fs = std::filesystem;

namespace {

using clrt_test::clrt_lines;
using clrt_test::run_mpi;
bool have_mpirun() {
  return clrt_test::can_run_mpi();
}

std::vector<uint8_t> pixels(const std::string& path) {
  return clrt::to_u8(clrt::read_image(path, 1 << 14, 1LL << 26));
}

// Square: the scenes' viewports are, so no warning joins the output.
const std::vector<std::string> kSize = {"--width", "40", "--height", "40"};

// Five scenes: the repository's four small ones and one written here.
std::vector<std::string> five_scenes(const TempDir& dir) {
  return {clrt_test::source_path("scenes/cgfs-demo.json"), clrt_test::source_path("scenes/glass.json"),
          clrt_test::source_path("scenes/cgfs-camera.json"), clrt_test::source_path("scenes/cgfs-book-ch4.json"),
          dir.write("two.json", R"({"spheres": [{"center": [0, 0, 3], "radius": 1, "color": [255, 0, 0]},
                                                {"center": [1, 1, 5], "radius": 1, "color": [0, 0, 255],
                                                 "reflective": 0.5}],
                                   "lights": [{"type": "ambient", "intensity": 0.3},
                                              {"type": "point", "intensity": 0.7, "position": [2, 2, 0]}]})")};
}

}  // namespace

TEST_CASE("mpirun -np 3 render of five scenes: every frame equals a single-process render",
          "[frames][mpi-cli][cli][opencl]") {
  if (!have_mpirun()) {
    WARN("skipped: mpirun not on PATH or clrt built without MPI");
    return;
  }
  TempDir dir, frames;
  const auto scenes = five_scenes(dir);
  std::vector<std::string> args = {"render"};
  args.insert(args.end(), scenes.begin(), scenes.end());
  args.insert(args.end(), {"-o", frames / "f_##.ppm"});
  args.insert(args.end(), kSize.begin(), kSize.end());
  const RunResult r = run_mpi(3, args);
  INFO("stdout: " << r.out << "\nstderr: " << r.err);
  REQUIRE(r.status == 0);
  CHECK(frames.entries() == std::vector<std::string>{"f_00.ppm", "f_01.ppm", "f_02.ppm", "f_03.ppm", "f_04.ppm"});
  CHECK_THAT(r.out, Contains("5 frames, 40x40 on 3 MPI ranks: "));
  for (int rank = 0; rank < 3; ++rank) CHECK_THAT(r.out, Contains("  rank " + std::to_string(rank) + " "));
  for (size_t i = 0; i < scenes.size(); ++i) {
    const std::string frame = frames / ("f_0" + std::to_string(i) + ".ppm");
    INFO(frame);
    CHECK_THAT(r.out, Contains(frame + ": " + scenes[i] + ", 40x40 depth "));
    CHECK_THAT(clrt_test::slurp(frame), Contains("# clrt:scene=" + scenes[i] + "\n"));
    const std::string single = dir / "single.ppm";
    std::vector<std::string> one = {"render", scenes[i], "-o", single};
    one.insert(one.end(), kSize.begin(), kSize.end());
    REQUIRE(clrt_test::run_clrt(one).status == 0);
    CHECK(pixels(frame) == pixels(single));
  }
}

TEST_CASE("mpirun render of several scenes: a failure on the ranks is one error line and no frame",
          "[frames][mpi-cli][cli][opencl]") {
  if (!have_mpirun()) {
    WARN("skipped: mpirun not on PATH or clrt built without MPI");
    return;
  }
  TempDir dir, frames;
  const auto scenes = five_scenes(dir);
  SECTION("a bad scene: found by rank 0 before any frame") {
    std::vector<std::string> args = {"render", scenes[0], dir.write("bad.json", "{"), "-o", frames / "f_#.ppm"};
    const RunResult r = run_mpi(3, args);
    INFO("stdout: " << r.out << "\nstderr: " << r.err);
    CHECK(r.status == 2);
    const auto lines = clrt_lines(r.err);
    REQUIRE(lines.size() == 1);
    CHECK_THAT(lines[0], StartsWith("clrt: error: " + dir / "bad.json"));
  }
  SECTION("every rank fails at its first frame (a work-group size no device allows)") {
    std::vector<std::string> args = {"render"};
    args.insert(args.end(), scenes.begin(), scenes.end());
    args.insert(args.end(), {"-o", frames / "f_#.ppm", "--local", "4096x4096"});
    args.insert(args.end(), kSize.begin(), kSize.end());
    const RunResult r = run_mpi(3, args);
    INFO("stdout: " << r.out << "\nstderr: " << r.err);
    CHECK(r.status == 2);
    const auto lines = clrt_lines(r.err);
    REQUIRE(lines.size() == 1);
    CHECK_THAT(lines[0], StartsWith("clrt: error: rank "));
    CHECK_THAT(lines[0], Contains(": frame "));
    CHECK_THAT(lines[0], Contains("--local 4096x4096"));
  }
  CHECK(frames.entries().empty());
}

namespace {

// Eight frames: the demo and the flat scene, each frame's background its own.
std::vector<clrt::Scene> eight_scenes() {
  std::vector<clrt::Scene> scenes;
  for (int i = 0; i < 8; ++i) {
    clrt::Scene s = i % 2 ? clrt_test::flat_scene() : clrt::builtin_demo_scene();
    s.background = clrt::Vec3{double(20 * i), 40, double(200 - 20 * i)};
    scenes.push_back(s);
  }
  return scenes;
}

// Every rank at the same point (a broadcast) before a farm: a rank done with
// the previous one cannot send into it (as `clrt render`'s share_from_root).
void in_step(clrt::dist::Communicator& comm) {
  clrt::dist::share_from_root(comm, [] { return clrt::dist::Bytes{}; });
}

// This rank's renderer, made at its first frame (as `clrt render` does).
struct RankRenderer {
  clrt::RenderSettings settings;
  int width = 0, height = 0;
  std::unique_ptr<clrt::Renderer> r;
  int fail_on_rank = -1;  // this rank throws at each frame
  clrt::Image operator()(const clrt::Scene& scene, clrt::dist::FrameRun& run) {
    if (clrt::dist::world().rank() == fail_on_rank) throw clrt::UserError("no such device on this rank");
    if (!r) r = std::make_unique<clrt::Renderer>(std::vector<clrt::DeviceInfo>{clrt_test::test_device()}, settings);
    r->prepare(scene, width, height, scene.recursion_depth);
    run.devices = r->device_names();
    return r->render();
  }
};

}  // namespace

TEST_CASE("rows per message: the whole frame where it fits, else bands of at least one row", "[frames][dist]") {
  using clrt::dist::rows_per_message;
  const clrt::FrameContents rgba8{clrt::PixelFormat::Rgba8, false}, full{clrt::PixelFormat::Float, true};
  CHECK(rows_per_message(1920, 1080, rgba8) == 1080);
  CHECK(rows_per_message(16384, 4096, full) == int((256LL << 20) / (16384 * 32)));
  CHECK(rows_per_message(100, 50, rgba8, 4000) == 10);
  CHECK(rows_per_message(100, 50, rgba8, 10) == 1);
}

TEST_CASE("frames farmed over the ranks: each delivered once, the pixels of one process's renders",
          "[frames][dist][mpi][opencl]") {
  clrt::dist::Communicator& comm = clrt::dist::world();
  const std::vector<clrt::Scene> scenes = eight_scenes();
  for (const clrt::FrameContents contents :
       {clrt::FrameContents{clrt::PixelFormat::Rgba8, false}, clrt::FrameContents{clrt::PixelFormat::Float, true}}) {
    RankRenderer render;
    render.settings.kernel.output = contents;
    render.width = 37, render.height = 23;
    clrt::dist::FrameQueueSettings qs;
    qs.width = 37, qs.height = 23, qs.contents = contents;
    qs.max_message_bytes = 37 * 5 * 32;  // bands of 5 rows (Float with classes), 40 of 8-bit: every frame in pieces
    std::vector<clrt::Image> got(scenes.size());
    std::vector<int> times(scenes.size(), 0);
    std::vector<int> progress;
    qs.progress = [&](int done, int total, const std::string&) {
      CHECK(total == int(scenes.size()));
      progress.push_back(done);
    };
    clrt::dist::FrameQueueStats stats;
    in_step(comm);
    clrt::dist::farm_frames(
        comm, scenes, qs, std::ref(render),
        [&](const clrt::Image& img, const clrt::dist::FrameRun& run) {
          got.at(size_t(run.index)) = img;
          ++times.at(size_t(run.index));
          CHECK(run.ms > 0);
          CHECK_FALSE(run.devices.empty());
        },
        &stats);
    if (comm.rank() != 0) {
      CHECK(times == std::vector<int>(scenes.size(), 0));  // only rank 0 gathers
      continue;
    }
    CHECK(times == std::vector<int>(scenes.size(), 1));
    CHECK(progress.front() == 0);
    CHECK(progress.back() == int(scenes.size()));
    CHECK(stats.frames == int(scenes.size()));
    REQUIRE(stats.ranks.size() == size_t(comm.size()));
    int units = 0;
    for (const auto& s : stats.ranks) units += s.units;
    CHECK(units == int(scenes.size()));
    clrt::Renderer one({clrt_test::test_device()}, render.settings);
    for (size_t i = 0; i < scenes.size(); ++i) {
      INFO("frame " << i);
      one.prepare(scenes[i], 37, 23, scenes[i].recursion_depth);
      const clrt::Image single = one.render();
      if (contents.pixels == clrt::PixelFormat::Float)
        clrt_test::require_identical(got[i], single);
      else
        CHECK(got[i].rgba8 == single.rgba8);
    }
  }
}

TEST_CASE("a rank that fails at a frame ends every rank, rank 0 names it and the frame",
          "[frames][dist][mpi][opencl]") {
  clrt::dist::Communicator& comm = clrt::dist::world();
  const std::vector<clrt::Scene> scenes = eight_scenes();
  for (int failing = comm.size() - 1; failing >= 0; --failing) {
    RankRenderer render;
    render.width = 16, render.height = 12, render.fail_on_rank = failing;
    clrt::dist::FrameQueueSettings qs;
    qs.width = 16, qs.height = 12, qs.contents = render.settings.kernel.output;
    int delivered = 0;
    const auto done = [&](const clrt::Image&, const clrt::dist::FrameRun& run) {
      ++delivered;
      CHECK(run.rank != failing);
    };
    in_step(comm);
    if (comm.rank() == 0) {
      try {
        clrt::dist::farm_frames(comm, scenes, qs, std::ref(render), done, nullptr);
        FAIL("the frames did not fail");
      } catch (const clrt::dist::JobAborted&) {
        FAIL("rank 0 was aborted instead of reporting");
      } catch (const std::exception& e) {
        const std::string what = e.what();
        if (comm.distributed()) CHECK_THAT(what, Contains("rank " + std::to_string(failing) + " ("));
        if (comm.distributed()) CHECK_THAT(what, Contains(": frame "));
        CHECK_THAT(what, Contains("no such device on this rank"));
      }
      CHECK(delivered < int(scenes.size()));
    } else {
      CHECK_THROWS_AS(clrt::dist::farm_frames(comm, scenes, qs, std::ref(render), done, nullptr),
                      clrt::dist::JobAborted);
    }
  }
}

TEST_CASE("a frame rank 0 cannot write ends every rank with that error", "[frames][dist][mpi][opencl]") {
  clrt::dist::Communicator& comm = clrt::dist::world();
  const std::vector<clrt::Scene> scenes = eight_scenes();
  RankRenderer render;
  render.width = 16, render.height = 12;
  clrt::dist::FrameQueueSettings qs;
  qs.width = 16, qs.height = 12, qs.contents = render.settings.kernel.output;
  int delivered = 0;
  const auto done = [&](const clrt::Image&, const clrt::dist::FrameRun&) {
    if (++delivered == 2) throw clrt::UserError("f_01.ppm: cannot write output: No space left on device");
  };
  in_step(comm);
  if (comm.rank() == 0) {
    CHECK_THROWS_AS(clrt::dist::farm_frames(comm, scenes, qs, std::ref(render), done, nullptr), clrt::UserError);
    CHECK(delivered == 2);  // nothing after the failure
  } else {
    CHECK_THROWS_AS(clrt::dist::farm_frames(comm, scenes, qs, std::ref(render), done, nullptr), clrt::dist::JobAborted);
  }
}

}  // namespace test_frames_mpi
