// parallel.cpp - parallel_chunks() and run_on_threads(): a std::thread per
// chunk or call, every one joined before returning.
#include "util/parallel.hpp"

#include <algorithm>
#include <exception>
#include <mutex>
#include <string>
#include <system_error>
#include <thread>
#include <vector>

#include "util/error.hpp"

namespace clrt {

void parallel_chunks(size_t count, size_t min_chunk, const std::function<void(size_t, size_t)>& work, int threads) {
  if (count == 0) return;
  size_t workers = threads > 0 ? size_t(threads) : size_t(std::max(1u, std::thread::hardware_concurrency()));
  workers = std::max<size_t>(1, std::min(workers, count / std::max<size_t>(1, min_chunk)));
  const size_t step = (count + workers - 1) / workers;
  std::exception_ptr failure;
  std::mutex failure_lock;
  auto run = [&](size_t begin) noexcept {
    try {
      work(begin, std::min(count, begin + step));
    } catch (...) {
      const std::lock_guard<std::mutex> hold(failure_lock);
      if (!failure) failure = std::current_exception();
    }
  };
  std::vector<std::thread> started;
  std::vector<size_t> left_over;
  try {
    started.reserve(workers);
    left_over.reserve(workers);
  } catch (...) {
    workers = 1;  // no room even for the list: every chunk here
  }
  for (size_t begin = step; begin < count && workers > 1; begin += step) {
    try {
      started.emplace_back(run, begin);
    } catch (const std::system_error&) {
      left_over.push_back(begin);  // (reserved: cannot allocate, so cannot throw)
    }
  }
  run(0);
  if (workers == 1)
    for (size_t begin = step; begin < count; begin += step) run(begin);
  for (size_t begin : left_over) run(begin);
  for (std::thread& t : started) t.join();
  if (failure) std::rethrow_exception(failure);
}

void run_on_threads(size_t count, const std::function<void(size_t)>& work) {
  std::vector<std::exception_ptr> errors(count);
  std::vector<std::thread> started;
  started.reserve(count);
  std::string refused;
  for (size_t i = 0; i < count && refused.empty(); ++i) {
    try {
      started.emplace_back([&errors, &work, i]() noexcept {
        try {
          work(i);
        } catch (...) {
          errors[i] = std::current_exception();
        }
      });
    } catch (const std::system_error& e) {
      refused = e.what();
    }
  }
  for (std::thread& t : started) t.join();
  if (!refused.empty()) throw UserError("could not start a thread (" + refused + ")");
  for (const std::exception_ptr& e : errors)
    if (e) std::rethrow_exception(e);
}

}  // namespace clrt
