// test_band_scheduler.cpp - how a frame's rows are handed out (no device):
// every row exactly once, in order, guided shares with several workers.
#include <catch2/catch.hpp>
#include <thread>
#include <vector>

#include "render/band_scheduler.hpp"

// (clrt_tests is a unity build: each file's code is in a namespace of its own.)
namespace test_band_scheduler {

using namespace clrt;

namespace {

// Takes bands of `want` rows until the queue is empty; returns their heights.
std::vector<int> drain(BandQueue& queue, int want, bool guided) {
  std::vector<int> rows;
  int y0 = 0, n = 0, next = 0;
  while (queue.take(want, guided, y0, n)) {
    CHECK(y0 == next);  // contiguous, in order
    CHECK(n >= 1);
    next = y0 + n;
    rows.push_back(n);
  }
  return rows;
}

}  // namespace

TEST_CASE("one worker takes the bands it asks for, the last one short", "[band]") {
  BandQueue queue(0, 157, 1);
  const auto rows = drain(queue, 13, /*guided=*/true);  // guided has no effect alone
  REQUIRE(rows.size() == 13);                           // 157 = 12 * 13 + 1
  CHECK(rows.front() == 13);
  CHECK(rows.back() == 1);
  int y0 = 0, n = 0;
  CHECK_FALSE(queue.take(13, true, y0, n));  // and stays empty
}

TEST_CASE("guided bands: at most half an even share of what is left", "[band]") {
  BandQueue queue(0, 1000, 2);
  int y0 = 0, n = 0;
  REQUIRE(queue.take(1000, true, y0, n));
  CHECK(n == 250);  // 1000 left, 2 workers: ceil(1000 / 4)
  REQUIRE(queue.take(1000, true, y0, n));
  CHECK(y0 == 250);
  CHECK(n == 188);  // ceil(750 / 4)
  REQUIRE(queue.take(10, true, y0, n));
  CHECK(n == 10);  // a smaller request is kept
  // Unguided (fixed --band-rows): exactly what is asked.
  REQUIRE(queue.take(300, false, y0, n));
  CHECK(n == 300);
}

TEST_CASE("guided bands shrink to single rows at the end of the frame", "[band]") {
  BandQueue queue(0, 100, 4);
  const auto rows = drain(queue, 100, true);
  int total = 0;
  for (int r : rows) total += r;
  CHECK(total == 100);
  CHECK(rows.back() == 1);
}

TEST_CASE("workers on several threads take every row exactly once", "[band]") {
  const int height = 5000, workers = 4;
  BandQueue queue(0, height, workers);
  std::vector<int> owner(height, -1);
  std::vector<std::thread> threads;
  for (int w = 0; w < workers; ++w)
    threads.emplace_back([&, w] {
      int y0 = 0, n = 0;
      while (queue.take(7 + w, true, y0, n))
        for (int y = y0; y < y0 + n; ++y) owner[y] = w;  // disjoint rows: no race
    });
  for (auto& t : threads) t.join();
  for (int y = 0; y < height; ++y) REQUIRE(owner[y] >= 0);
}

TEST_CASE("device default launch limits", "[band]") {
  CHECK(launch_limit_ms(TilePolicy{}, "CPU") == 0);
  CHECK(launch_limit_ms(TilePolicy{}, "GPU") == 500);
  CHECK(launch_limit_ms(TilePolicy{}, "ACCELERATOR") == 500);
  CHECK(launch_limit_ms(TilePolicy{120, 0}, "GPU") == 120);
  CHECK(launch_limit_ms(TilePolicy{0, 0}, "GPU") == 0);
  CHECK(launch_limit_ms(TilePolicy{25, 0}, "CPU") == 25);
}

TEST_CASE("a queue over a range of rows hands out exactly that range", "[band]") {
  BandQueue queue(40, 137, 3);
  int y0 = 0, n = 0, expect = 40;
  while (queue.take(16, true, y0, n)) {
    CHECK(y0 == expect);
    expect += n;
  }
  CHECK(expect == 137);
}

}  // namespace test_band_scheduler
