// test_stats.cpp - timing summaries (util/stats.hpp).
#include <catch2/catch.hpp>
#include <cmath>

#include "util/stats.hpp"

// (clrt_tests is a unity build: each file's code is in a namespace of its own.)
namespace test_stats {

using namespace clrt;

TEST_CASE("timing summaries: N, median, mean, sample sd, min, max", "[timing]") {
  Stats s = summarize({4, 1, 3, 2});
  CHECK(s.n == 4);
  CHECK(s.median == 2.5);
  CHECK(s.mean == 2.5);
  CHECK(s.sd == Approx(std::sqrt(5.0 / 3.0)));  // sum of squares 5, N-1 = 3
  CHECK(s.min == 1);
  CHECK(s.max == 4);
  Stats one = summarize({7});
  CHECK(one.n == 1);
  CHECK(one.sd == 0);
  CHECK(format_stats(one) == "7.00 ms (N=1)");
  CHECK(format_stats(summarize({1, 3}), "x") == "median 2.00x, mean 2.00 ± 1.41, min 1.00, max 3.00 (N=2)");
  CHECK(summarize({}).n == 0);
}

}  // namespace test_stats
