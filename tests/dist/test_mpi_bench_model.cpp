// test_mpi_bench_model.cpp - the farm's performance model
// (bench/mpi_model.hpp, docs/developer/distributed.md): its arithmetic, not any time.
#include <catch2/catch.hpp>

#include "../../bench/mpi_model.hpp"

// (clrt_tests is a unity build: each file's code is in a namespace of its own.)
namespace test_mpi_bench_model {

using namespace clrt::model;

namespace {

// A round model: 1000 ms frame of 1000 rows 1000 pixels wide, 4 bytes a
// pixel (4 MB), nothing else costing anything unless a case sets it.
FarmModel round_model() {
  FarmModel m;
  m.frame_ms = 1000;
  m.width = 1000, m.height = 1000;
  m.pixel_bytes = 4;
  return m;
}

}  // namespace

TEST_CASE("farm model: one node is the plain render", "[model]") {
  const FarmModel m = round_model();
  const FarmPrediction p = predict(m, 1, 10);
  CHECK(p.tiles == 1);
  CHECK(p.frame_ms == 1000);
  CHECK(p.speedup == 1);
  CHECK_FALSE(p.root_bound);
}

TEST_CASE("farm model: free messages scale until tiles run out", "[model]") {
  const FarmModel m = round_model();
  // 100 tiles of 10 rows (10 ms each) over 4 nodes: 25 rounds.
  FarmPrediction p = predict(m, 4, 10);
  CHECK(p.tiles == 100);
  CHECK(p.compute_ms == Approx(250));
  CHECK(p.speedup == Approx(4));
  // 256 nodes, 100 tiles: one round, 156 nodes idle.
  p = predict(m, 256, 10);
  CHECK(p.compute_ms == Approx(10));
  CHECK(p.speedup == Approx(100));
  // A partial last round: 100 tiles over 64 nodes take 2 rounds.
  CHECK(predict(m, 64, 10).compute_ms == Approx(20));
}

TEST_CASE("farm model: rank 0's serial work bounds the frame", "[model]") {
  FarmModel m = round_model();
  m.handle_ms = 1;      // per message
  m.link_mbps = 1000;   // 1 GB/s: the 4 MB frame takes 4 ms through rank 0's link
  m.store_mbps = 1e12;  // free copy
  const FarmPrediction p = predict(m, 64, 10);
  // 100 tiles, 2 rounds: rank 0 renders 2, receives 98 of 40 kB each.
  CHECK(p.root_ms == Approx(98 * (1 + 0.04)));
  // A node's tile: 10 ms of pixels + 0.04 ms on the link.
  CHECK(p.compute_ms == Approx(2 * 10.04));
  CHECK(p.root_bound);
  CHECK(p.frame_ms == Approx(p.root_ms));
  // Taller tiles: fewer messages, until rank 0 keeps up.
  const int safe = shortest_root_safe_tile_rows(m, 64);
  REQUIRE(safe > 10);
  CHECK_FALSE(predict(m, 64, safe).root_bound);
  CHECK(predict(m, 64, safe - 1).root_bound);
  // The best tile height is at least as good as that one, and better than 10 rows.
  const int best = best_tile_rows(m, 64);
  CHECK(predict(m, 64, best).frame_ms <= predict(m, 64, safe).frame_ms);
  CHECK(predict(m, 64, best).frame_ms < p.frame_ms);
}

TEST_CASE("farm model: latency is paid per tile and once per frame", "[model]") {
  FarmModel m = round_model();
  m.latency_ms = 0.5;
  const FarmPrediction p = predict(m, 2, 500);
  // 2 tiles, 1 round of (500 ms + 0.5 ms), plus the first request.
  CHECK(p.compute_ms == Approx(500.5));
  CHECK(p.frame_ms == Approx(501));
}

TEST_CASE("farm model: a slow link into rank 0 makes the farm slower than one node", "[model]") {
  FarmModel m = round_model();
  m.link_mbps = 1;  // 4 s for the frame's 4 MB
  const FarmPrediction p = predict(m, 16, 10);
  // 100 tiles, 7 rounds; rank 0 receives 93 tiles of 40 ms on the link each.
  CHECK(p.root_ms == Approx(93 * 40));
  CHECK(p.root_bound);
  CHECK(p.speedup < 1);
}

}  // namespace test_mpi_bench_model
