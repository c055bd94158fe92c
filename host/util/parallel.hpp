// parallel.hpp - the host's threads, started in one place: a loop over a
// range split among the machine's cores (passes over millions of
// primitives: the hierarchy's items, the first touch of huge pages), and one
// thread per device. Every thread started is joined before these return (a
// std::thread destroyed unjoined ends the process), also when the system
// refuses a new one.
#pragma once
#include <cstddef>
#include <functional>

namespace clrt {

// Calls work(begin, end) on contiguous chunks that cover [0, count) once,
// one chunk per thread: up to `threads` (0: one per hardware thread), none
// smaller than min_chunk, the calling thread taking the first. Where a
// thread cannot be started its chunk runs on the calling thread instead.
// Returns once every chunk is done; then rethrows the first exception any
// chunk threw.
void parallel_chunks(size_t count, size_t min_chunk, const std::function<void(size_t, size_t)>& work, int threads = 0);

// Calls work(i) for each i in [0, count), each on a thread of its own (not
// the calling one), and waits for all of them; then rethrows the first
// exception any call threw. Where the system cannot start a thread, those
// started are joined and a UserError says so (no call is left half-run).
void run_on_threads(size_t count, const std::function<void(size_t)>& work);

}  // namespace clrt
