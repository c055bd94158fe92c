// test_parallel.cpp - parallel_chunks() covers its range once in contiguous
// chunks on any number of threads, run_on_threads() calls each index once on
// a thread of its own, and both rethrow what a call threw after all ended
// (util/parallel.hpp).
#include <atomic>
#include <catch2/catch.hpp>
#include <chrono>
#include <mutex>
#include <set>
#include <stdexcept>
#include <thread>
#include <utility>
#include <vector>

#include "util/parallel.hpp"

// (clrt_tests is a unity build: each file's code is in a namespace of its own.)
namespace test_parallel {

TEST_CASE("parallel_chunks covers the range once, in contiguous chunks of at least the minimum", "[util]") {
  for (size_t count : {size_t(0), size_t(1), size_t(7), size_t(1000), size_t(65537)})
    for (size_t min_chunk : {size_t(1), size_t(100), size_t(100000)})
      for (int threads : {0, 1, 2, 3, 16}) {
        INFO(count << " items, chunks of at least " << min_chunk << ", " << threads << " threads");
        std::vector<std::atomic<int>> visits(count);
        std::mutex lock;
        std::vector<std::pair<size_t, size_t>> chunks;
        clrt::parallel_chunks(
            count, min_chunk,
            [&](size_t begin, size_t end) {
              for (size_t i = begin; i < end; ++i) ++visits[i];
              const std::lock_guard<std::mutex> hold(lock);
              chunks.emplace_back(begin, end);
            },
            threads);
        for (size_t i = 0; i < count; ++i) REQUIRE(visits[i] == 1);
        if (threads > 0) CHECK(chunks.size() <= size_t(threads));
        if (chunks.size() > 1)
          for (const auto& [begin, end] : chunks) CHECK(end - begin >= std::min(min_chunk, count) / 2);
      }
}

TEST_CASE("parallel_chunks rethrows a chunk's exception once every chunk has ended", "[util]") {
  std::atomic<int> finished{0};
  auto work = [&](size_t begin, size_t) {
    if (begin == 0) throw std::runtime_error("first chunk");
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    ++finished;
  };
  CHECK_THROWS_WITH(clrt::parallel_chunks(4, 1, work, 4), "first chunk");
  CHECK(finished == 3);  // the other chunks ran to their end before the throw
}

TEST_CASE("run_on_threads calls each index once, none on the calling thread, and rethrows", "[util]") {
  const std::thread::id caller = std::this_thread::get_id();
  std::mutex lock;
  std::multiset<size_t> called;
  bool on_caller = false;
  clrt::run_on_threads(5, [&](size_t i) {
    const std::lock_guard<std::mutex> hold(lock);
    called.insert(i);
    on_caller = on_caller || std::this_thread::get_id() == caller;
  });
  CHECK(called == std::multiset<size_t>{0, 1, 2, 3, 4});
  CHECK_FALSE(on_caller);
  std::atomic<int> finished{0};
  CHECK_THROWS_WITH(clrt::run_on_threads(3,
                                         [&](size_t i) {
                                           if (i == 1) throw std::runtime_error("second");
                                           ++finished;
                                         }),
                    "second");
  CHECK(finished == 2);
}

}  // namespace test_parallel
