// farm.cpp - the master-worker loop of dist/, on rank 0 and on the others.
#include "dist/farm.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <thread>

#include "dist/job.hpp"
#include "dist/wire.hpp"
#include "util/error.hpp"
#include "util/timer.hpp"

namespace clrt::dist {

Bytes encode_share(const RankShare& s) {
  Writer w;
  w.put_text(s.host), w.put_text(s.devices);
  w.put<int32_t>(s.units), w.put<int64_t>(s.rows), w.put(s.busy_ms), w.put(s.kernel_ms), w.put(s.send_ms);
  w.put<uint64_t>(s.tiles.size());
  for (const TileTime& t : s.tiles) w.put<int32_t>(t.y0), w.put<int32_t>(t.y1), w.put(t.ms);
  return std::move(w.bytes);
}

RankShare decode_share(const Bytes& b, int rank) {
  Reader r(b);
  RankShare s;
  s.rank = rank;
  s.host = r.get_text(), s.devices = r.get_text();
  s.units = r.get<int32_t>(), s.rows = r.get<int64_t>(), s.busy_ms = r.get<double>(), s.kernel_ms = r.get<double>();
  s.send_ms = r.get<double>();
  s.tiles.resize(size_t(r.get_count(2 * sizeof(int32_t) + sizeof(double))));
  for (TileTime& t : s.tiles) t.y0 = r.get<int32_t>(), t.y1 = r.get<int32_t>(), t.ms = r.get<double>();
  return s;
}

int rows_per_message(int width, int height, const FrameContents& contents, long long max_bytes) {
  const long long row = static_cast<long long>(row_pixel_bytes(contents)) * std::max(1, width);
  return int(std::max<long long>(1, std::min<long long>(std::max(1, height), max_bytes / row)));
}

void run_worker(Communicator& comm, const WorkerJob& job) {
  RankShare share;
  share.rank = comm.rank();
  share.host = comm.host();
  std::exception_ptr failure;
  try {
    if (job.prepare) job.prepare(share);
    for (;;)
      if (!job.unit(receive_work(comm), share)) break;
    comm.send(0, kTagReport, encode_share(share));
    comm.flush();
    return;
  } catch (const JobAborted&) {
    throw;
  } catch (...) {
    failure = std::current_exception();
  }
  report_failure_to_root(comm, (job.context ? job.context() : std::string()) + exception_text(failure));
}

namespace {

// Rank 0's own units on a thread of its own; joined however the farm ends.
class LocalThread {
 public:
  LocalThread(const MasterJob& job, RankShare& own)
      : thread_([this, &job, &own] {
          try {
            job.local(own);
          } catch (...) {
            failure_ = std::current_exception();
          }
          done_ = true;  // (after failure_: the atomic publishes it)
        }) {}
  ~LocalThread() { join(); }
  void join() {
    if (thread_.joinable()) thread_.join();
  }
  bool done() const { return done_; }
  // Its failure, once done() (else none).
  std::exception_ptr failure() const { return done_ ? failure_ : nullptr; }

 private:
  std::exception_ptr failure_;
  std::atomic<bool> done_{false};
  std::thread thread_;  // (last: it starts once the members above exist)
};

// How long to sleep before the next poll: 20 us after a message, doubling
// to 1 ms while none comes (each wake-up takes rank 0's core from its local
// thread; the ranks have a unit in hand meanwhile).
class Backoff {
 public:
  void reset() { pause_ = kShortest; }
  void wait(bool brisk) {
    std::this_thread::sleep_for(pause_);
    pause_ = brisk ? kShortest : std::min(pause_ * 2, kLongest);
  }

 private:
  static constexpr std::chrono::microseconds kShortest{20}, kLongest{1000};
  std::chrono::microseconds pause_ = kShortest;
};

}  // namespace

std::vector<RankShare> run_master(Communicator& comm, const MasterJob& job) {
  const int ranks = comm.size();
  std::vector<RankShare> shares(static_cast<size_t>(ranks));
  for (int r = 0; r < ranks; ++r) shares[size_t(r)].rank = r;
  shares[0].host = comm.host();
  std::vector<bool> reported(static_cast<size_t>(ranks), false);
  int waiting = ranks - 1;  // ranks that have not reported
  std::string remote_failure;
  std::exception_ptr own_failure;  // this thread's: a result it could not take in
  // Rank 0 works too, on a thread of its own: this thread answers the
  // other ranks (MPI_THREAD_FUNNELED: only it calls MPI).
  LocalThread local(job, shares[0]);
  const auto failed = [&] { return !remote_failure.empty() || own_failure || local.failure(); };
  try {
    job.start();
  } catch (...) {
    own_failure = std::current_exception();
  }
  Liveness live(comm);
  Backoff backoff;
  while (!failed()) {
    try {
      const bool local_done = local.done();  // (before the look: what it left is then seen)
      if (job.deliver_local && job.deliver_local()) continue;
      if (local_done && waiting == 0) break;
      const auto polled = Clock::now();
      Message m;
      if (!comm.try_receive(m)) {
        if (job.idle) job.idle();
        const std::string silent = live.silent([&](int r) { return !reported[size_t(r)]; });
        if (!silent.empty()) fail_silent(comm, silent + "; " + job.progress_note());
        backoff.wait(job.all_handed_out && job.all_handed_out());
        continue;
      }
      backoff.reset();
      live.heard(m.source);
      if (m.tag == kTagReport) {
        shares[size_t(m.source)] = decode_share(m.data, m.source);
        reported[size_t(m.source)] = true;
        --waiting;
      } else if (m.tag == kTagError) {
        Reader in(m.data);
        remote_failure = in.get_text();
      } else if (m.tag != kTagAlive) {
        job.result(m, ms_since(polled));
      }
    } catch (...) {
      own_failure = std::current_exception();
    }
  }
  if (!failed()) {
    local.join();
    return shares;
  }
  // The stop-and-rethrow tail: every rank still at work is told to stop,
  // and the failure is thrown once they have.
  job.close();
  std::vector<int> running;
  for (int r = 1; r < ranks; ++r)
    if (!reported[size_t(r)]) running.push_back(r);
  std::string line;
  if (!remote_failure.empty())
    line = remote_failure;
  else if (own_failure && job.own_failure_as_is)
    line = exception_text(own_failure);
  else if (own_failure)
    line = rank_label(0, comm.host()) + ": " + exception_text(own_failure);
  else
    line = rank_label(0, comm.host()) + ": " + (job.local_context ? job.local_context() : std::string()) +
           exception_text(local.failure());
  stop_ranks(
      comm, running, [&] { print_error_line(line); }, job.stop_patience_s ? job.stop_patience_s() : 30);
  local.join();
  if (own_failure && remote_failure.empty() && job.own_failure_as_is) std::rethrow_exception(own_failure);
  throw DeviceError(line);
}

}  // namespace clrt::dist
