// test_frame_farm.cpp - one frame over the ranks of a job (dist/frame_farm.hpp).
// Run as one process (ctest), these check the world of one and the tile
// rule; run under `mpirun -np 3 clrt_tests "[mpi]"` (the ctest test
// mpi_tests_3_ranks) every rank runs them together: the farmed frame must be
// bit-identical to one process's render, and a failure on any rank must end
// every rank (no hang: ctest's timeout would catch one).
#include <catch2/catch.hpp>
#include <memory>

#include "dist/communicator.hpp"
#include "dist/frame_farm.hpp"
#include "dist/job.hpp"
#include "dist/wire.hpp"
#include "flat_scene.hpp"
#include "scene/builtin_scene.hpp"
#include "test_util.hpp"
#include "util/error.hpp"

// (clrt_tests is a unity build: each file's code is in a namespace of its own.)
namespace test_frame_farm {

using namespace clrt;
using namespace clrt::dist;

TEST_CASE("tiles: guided shares of what is left, never under the minimum, never past the frame", "[dist]") {
  // 1920 wide: the minimum is 32768 pixels = 18 rows (rounded up).
  CHECK(next_tile_rows(1080, 2, 1920, 0, 1080) == 270);  // 1080 / (2 x 2)
  CHECK(next_tile_rows(100, 2, 1920, 0, 1080) == 25);    // 100 / 4
  CHECK(next_tile_rows(40, 2, 1920, 0, 1080) == 18);
  CHECK(next_tile_rows(15, 2, 1920, 0, 1080) == 15);
  CHECK(next_tile_rows(0, 2, 1920, 0, 1080) == 0);
  CHECK(next_tile_rows(1080, 64, 1920, 0, 1080) == 18);
  // Fixed rows, and the message-size cap.
  CHECK(next_tile_rows(1080, 2, 1920, 16, 1080) == 16);
  CHECK(next_tile_rows(10, 2, 1920, 16, 1080) == 10);
  CHECK(next_tile_rows(1080, 2, 1920, 0, 100) == 100);
  // Every row exactly once, for a few shapes.
  for (int ranks : {1, 3, 16})
    for (int rows : {0, 5}) {
      int left = 777, tiles = 0;
      while (int n = next_tile_rows(left, ranks, 300, rows, 777)) left -= n, ++tiles;
      CHECK(left == 0);
      CHECK(tiles > 0);
    }
}

namespace {

// The frame of `scene` farmed over the world's ranks, and (rank 0) the same
// frame rendered by one Renderer in this process.
struct Farmed {
  Image farmed, single;
  FarmStats stats;
};

Farmed farm(const Scene& scene, int width, int height, FrameContents contents, int tile_rows, Sampling sampling = {}) {
  Communicator& comm = world();
  RenderSettings settings;
  settings.kernel.output = contents;
  std::unique_ptr<Renderer> r;
  const auto prepare = [&]() -> Renderer& {
    r = std::make_unique<Renderer>(std::vector<DeviceInfo>{clrt_test::test_device()}, settings);
    r->prepare(scene, width, height, scene.recursion_depth, sampling);
    return *r;
  };
  FarmSettings fs;
  fs.width = width, fs.height = height, fs.contents = contents, fs.tile_rows = tile_rows;
  Farmed out;
  out.farmed = farm_frame(comm, prepare, fs, &out.stats);
  if (comm.rank() == 0) {
    Renderer one({clrt_test::test_device()}, settings);
    one.prepare(scene, width, height, scene.recursion_depth, sampling);
    out.single = one.render();
  }
  return out;
}

}  // namespace

TEST_CASE("a frame farmed over the ranks is bit-identical to one process's", "[dist][mpi][opencl]") {
  const Scene demo = builtin_demo_scene(), flat = clrt_test::flat_scene();
  struct Case {
    const Scene* scene;
    FrameContents contents;
    int tile_rows;
    Sampling sampling;
  };
  const Case cases[] = {
      {&demo, {PixelFormat::Rgba8, false}, 0, {}},
      {&demo, {PixelFormat::Float, true}, 7, {}},
      {&flat, {PixelFormat::Float, true}, 1, Sampling(2, -1, Subsample::Off)},
      {&flat, {PixelFormat::Rgba8, false}, 13, Sampling(1, -1, Subsample::Interpolate)},
  };
  for (const Case& c : cases) {
    const Farmed f = farm(*c.scene, 97, 61, c.contents, c.tile_rows, c.sampling);
    if (world().rank() != 0) {
      CHECK(f.farmed.pixels() == 0);  // only rank 0 holds the frame
      continue;
    }
    REQUIRE(f.stats.ranks.size() == size_t(world().size()));
    long long rows = 0;
    for (const RankShare& s : f.stats.ranks) rows += s.rows;
    CHECK(rows == 61);
    if (c.tile_rows > 0 && world().distributed()) CHECK(f.stats.tiles == (61 + c.tile_rows - 1) / c.tile_rows);
    CHECK(f.farmed.rgba8 == f.single.rgba8);
    if (c.contents.pixels == PixelFormat::Float) clrt_test::require_identical(f.farmed, f.single);
  }
}

TEST_CASE("a rank that fails ends every rank, rank 0 names it", "[dist][mpi][opencl]") {
  Communicator& comm = world();
  const Scene scene = builtin_demo_scene();
  // Each rank in turn fails to prepare (a bad device on that rank, say).
  for (int failing = comm.size() - 1; failing >= 0; --failing) {
    RenderSettings settings;
    std::unique_ptr<Renderer> r;
    const auto prepare = [&]() -> Renderer& {
      if (comm.rank() == failing) throw UserError("no such device on this rank");
      r = std::make_unique<Renderer>(std::vector<DeviceInfo>{clrt_test::test_device()}, settings);
      r->prepare(scene, 64, 48, 3, {});
      return *r;
    };
    FarmSettings fs;
    fs.width = 64, fs.height = 48, fs.contents = settings.kernel.output, fs.tile_rows = 4;
    if (comm.rank() == 0) {
      try {
        farm_frame(comm, prepare, fs, nullptr);
        FAIL("the farm did not fail");
      } catch (const JobAborted&) {
        FAIL("rank 0 was aborted instead of reporting");
      } catch (const std::exception& e) {
        const std::string what = e.what();
        if (comm.distributed()) CHECK_THAT(what, Catch::Contains("rank " + std::to_string(failing) + " ("));
        CHECK_THAT(what, Catch::Contains("no such device on this rank"));
      }
    } else {
      CHECK_THROWS_AS(farm_frame(comm, prepare, fs, nullptr), JobAborted);
    }
  }
}

TEST_CASE("bad input on rank 0 reaches every rank before any work", "[dist][mpi]") {
  Communicator& comm = world();
  const auto bad = []() -> Bytes { throw UserError("bad scene"); };
  if (comm.rank() == 0)
    CHECK_THROWS_WITH(share_from_root(comm, bad), "bad scene");
  else
    CHECK_THROWS_AS(share_from_root(comm, bad), JobAborted);
  // And a good share arrives everywhere unchanged.
  const Bytes scene = encode_scene(clrt_test::flat_scene());
  const Bytes got = share_from_root(comm, [&] { return scene; });
  CHECK(got == scene);
}

}  // namespace test_frame_farm
