// grid.cpp - master-worker cells over the ranks of a job.
#include "dist/grid.hpp"

#include <atomic>
#include <chrono>
#include <cstdio>
#include <deque>
#include <exception>
#include <mutex>
#include <thread>
#include <utility>

#include "cl/cl.hpp"
#include "dist/job.hpp"
#include "dist/wire.hpp"
#include "util/error.hpp"
#include "util/timer.hpp"

namespace clrt::dist {

namespace {

Bytes encode_cell(int cell) {
  Writer w;
  w.put<int32_t>(cell);
  return std::move(w.bytes);
}

// A cell's result message: the cell index, then its bytes.
Bytes encode_result(int cell, const Bytes& result) {
  Writer w;
  w.bytes.reserve(sizeof(int32_t) + result.size());
  w.put<int32_t>(cell);
  w.put_raw(result.data(), result.size());
  return std::move(w.bytes);
}

Bytes timed_cell(const CellFn& compute, int cell, RankShare& share) {
  const auto t0 = Clock::now();
  Bytes result = compute(cell);
  share.busy_ms += ms_since(t0);
  share.units += 1;
  return result;
}

void work(Communicator& comm, const CellFn& compute) {
  RankShare share;
  share.host = comm.host();
  std::exception_ptr failure;
  try {
    for (;;) {
      const Message m = receive_work(comm);
      Reader in(m.data);
      const int cell = in.get<int32_t>();
      if (cell < 0) break;  // no cells left
      Bytes result;
      keep_alive(comm, [&] { result = timed_cell(compute, cell, share); });
      comm.send(0, kTagResult, encode_result(cell, result));
    }
    comm.send(0, kTagReport, encode_share(share));
    comm.flush();
    return;
  } catch (const JobAborted&) {
    throw;
  } catch (...) {
    failure = std::current_exception();
  }
  report_failure_to_root(comm, exception_text(failure));
}

// Rank 0's cells: handed to its own thread and to the other ranks in index
// order; the results of its own thread wait here for the main thread.
class CellQueue {
 public:
  explicit CellQueue(int cells) : cells_(cells) {}
  bool take(int& cell) {
    std::lock_guard<std::mutex> lock(mutex_);
    if (closed_ || next_ >= cells_) return false;
    cell = next_++;
    return true;
  }
  void close() {
    std::lock_guard<std::mutex> lock(mutex_);
    closed_ = true;
  }
  void put_result(int cell, Bytes&& result) {
    std::lock_guard<std::mutex> lock(mutex_);
    results_.emplace_back(cell, std::move(result));
  }
  bool take_result(std::pair<int, Bytes>& out) {
    std::lock_guard<std::mutex> lock(mutex_);
    if (results_.empty()) return false;
    out = std::move(results_.front());
    results_.pop_front();
    return true;
  }
  // The local thread's end: its failure, if any.
  void finish(std::exception_ptr failure) {
    std::lock_guard<std::mutex> lock(mutex_);
    failure_ = std::move(failure);
    finished_ = true;
  }
  bool finished(std::exception_ptr& failure) {
    std::lock_guard<std::mutex> lock(mutex_);
    failure = failure_;
    return finished_;
  }

 private:
  std::mutex mutex_;
  int cells_, next_ = 0;
  bool closed_ = false, finished_ = false;
  std::deque<std::pair<int, Bytes>> results_;
  std::exception_ptr failure_;
};

void master(Communicator& comm, int cells, const CellFn& compute, const GatherFn& gather, const GridSettings& settings,
            GridStats* stats) {
  const auto t0 = Clock::now();
  const int ranks = comm.size();
  CellQueue queue(cells);
  std::vector<RankShare> shares(static_cast<size_t>(ranks));
  for (int r = 0; r < ranks; ++r) shares[size_t(r)].rank = r;
  shares[0].host = comm.host();
  // Rank 0 computes cells too, on a thread of its own: this thread answers
  // the other ranks (MPI_THREAD_FUNNELED: only it calls MPI) and gathers.
  std::thread local([&] {
    std::exception_ptr failure;
    try {
      int cell = 0;
      while (queue.take(cell)) queue.put_result(cell, timed_cell(compute, cell, shares[0]));
    } catch (...) {
      failure = std::current_exception();
    }
    queue.finish(failure);
  });

  std::vector<bool> told_done(static_cast<size_t>(ranks), false), reported(static_cast<size_t>(ranks), false);
  // A cell for `rank`, or (once) the news that there are none left. One at
  // a time: cells are coarse, and a rank holding a second cell at the end
  // would keep it from a rank that is idle.
  const auto give = [&](int rank) {
    int cell = 0;
    if (queue.take(cell)) {
      comm.send(rank, kTagWork, encode_cell(cell));
    } else if (!told_done[size_t(rank)]) {
      comm.send(rank, kTagWork, encode_cell(-1));
      told_done[size_t(rank)] = true;
    }
  };
  for (int r = 1; r < ranks; ++r) give(r);

  int gathered = 0;
  const auto take_in = [&](int cell, Bytes&& result) {
    if (cell < 0 || cell >= cells) throw DeviceError("MPI: a result for cell " + std::to_string(cell));
    gather(cell, std::move(result));
    ++gathered;
    if (settings.progress) settings.progress(gathered, cells, settings.cell_name ? settings.cell_name(cell) : "");
  };
  if (settings.progress) settings.progress(0, cells, "");
  int waiting = ranks - 1;  // ranks that have not reported
  std::string remote_failure;
  std::exception_ptr local_failure;
  bool local_done = false;
  long long bytes = 0;
  auto pause = std::chrono::microseconds(20);
  Liveness live(comm);
  while (remote_failure.empty() && !local_failure) {
    try {
      std::pair<int, Bytes> own;
      if (queue.take_result(own)) {
        take_in(own.first, std::move(own.second));
        continue;
      }
      if (!local_done) local_done = queue.finished(local_failure);
      if (local_failure) break;
      if (local_done && waiting == 0) {
        // (a result put between take_result above and finished())
        if (!queue.take_result(own)) break;
        take_in(own.first, std::move(own.second));
        continue;
      }
      Message m;
      if (!comm.try_receive(m)) {
        const std::string silent = live.silent([&](int r) { return !reported[size_t(r)]; });
        if (!silent.empty())
          fail_silent(comm, silent + "; " + std::to_string(gathered) + " of " + std::to_string(cells) +
                                " cells were done");
        std::this_thread::sleep_for(pause);
        pause = std::min(pause * 2, std::chrono::microseconds(1000));
        continue;
      }
      pause = std::chrono::microseconds(20);
      live.heard(m.source);
      if (m.tag == kTagResult) {
        bytes += (long long)m.data.size();
        Reader in(m.data);
        const int cell = in.get<int32_t>();
        give(m.source);  // the next cell first: the rank works while this one is gathered
        take_in(cell, Bytes(m.data.begin() + sizeof(int32_t), m.data.end()));
      } else if (m.tag == kTagReport) {
        shares[size_t(m.source)] = decode_share(m.data, m.source);
        reported[size_t(m.source)] = true;
        --waiting;
      } else if (m.tag == kTagError) {
        Reader in(m.data);
        remote_failure = in.get_text();
      }
    } catch (...) {  // gathering failed on rank 0
      local_failure = std::current_exception();
    }
  }
  if (!remote_failure.empty() || local_failure) {
    queue.close();
    std::vector<int> running;
    for (int r = 1; r < ranks; ++r)
      if (!reported[size_t(r)]) running.push_back(r);
    const std::string line =
        !remote_failure.empty() ? remote_failure : rank_label(0, comm.host()) + ": " + exception_text(local_failure);
    stop_ranks(
        comm, running, [&] { std::fprintf(stderr, "clrt: error: %s\n", line.c_str()); }, settings.stop_patience_s);
    local.join();
    throw DeviceError(line);
  }
  local.join();
  if (gathered != cells)
    throw DeviceError("MPI: " + std::to_string(gathered) + " of " + std::to_string(cells) + " cells gathered");
  if (stats) {
    stats->ranks = shares;
    stats->cells = cells;
    stats->wall_ms = ms_since(t0);
    stats->bytes_received = bytes;
  }
}

}  // namespace

void run_grid(Communicator& comm, int cells, const CellFn& compute, const GatherFn& gather,
              const GridSettings& settings, GridStats* stats) {
  if (comm.rank() != 0) return work(comm, compute);
  if (comm.distributed()) return master(comm, cells, compute, gather, settings, stats);
  // A world of one: a plain loop.
  const auto t0 = Clock::now();
  RankShare share;
  share.host = comm.host();
  if (settings.progress) settings.progress(0, cells, "");
  for (int cell = 0; cell < cells; ++cell) {
    gather(cell, timed_cell(compute, cell, share));
    if (settings.progress) settings.progress(cell + 1, cells, settings.cell_name ? settings.cell_name(cell) : "");
  }
  if (stats) *stats = GridStats{{share}, cells, ms_since(t0), 0};
}

std::string grid_share_lines(const GridStats& stats, const char* unit) {
  char head[256];
  std::snprintf(head, sizeof head, "%d %s on %zu MPI ranks: %.1f ms, %.2f MiB of results gathered\n", stats.cells, unit,
                stats.ranks.size(), stats.wall_ms, double(stats.bytes_received) / (1 << 20));
  std::string out = head;
  for (const RankShare& s : stats.ranks) {
    char line[256];
    std::snprintf(line, sizeof line, "  %s: %d %s, busy %.1f ms\n", rank_label(s.rank, s.host).c_str(), s.units, unit,
                  s.busy_ms);
    out += line;
  }
  return out;
}

}  // namespace clrt::dist
