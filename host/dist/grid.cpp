// grid.cpp - master-worker cells over the ranks of a job.
#include "dist/grid.hpp"

#include <atomic>
#include <chrono>
#include <cstdio>
#include <exception>
#include <mutex>
#include <thread>
#include <utility>

#include "cl/cl.hpp"
#include "dist/farm.hpp"
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

// A rank other than 0: cells until none are left.
void work_cells(Communicator& comm, const CellFn& compute) {
  WorkerJob job;
  job.unit = [&](const Message& m, RankShare& share) {
    Reader in(m.data);
    const int cell = in.get<int32_t>();
    if (cell < 0) return false;  // no cells left
    Bytes result;
    keep_alive(comm, [&] { result = timed_cell(compute, cell, share); });
    comm.send(0, kTagResult, encode_result(cell, result));
    return true;
  };
  run_worker(comm, job);
}

// Rank 0: hands out cells in index order, computes cells itself, gathers
// the results.
void gather_cells(Communicator& comm, int cells, const CellFn& compute, const GatherFn& gather,
                  const GridSettings& settings, GridStats* stats) {
  const auto t0 = Clock::now();
  const int ranks = comm.size();
  UnitQueue queue(cells);
  LocalResults<std::pair<int, Bytes>> own_results;
  std::vector<bool> told_done(static_cast<size_t>(ranks), false);
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
  int gathered = 0;
  long long bytes = 0;
  const auto take_in = [&](int cell, Bytes&& result) {
    if (cell < 0 || cell >= cells) throw DeviceError("MPI: a result for cell " + std::to_string(cell));
    gather(cell, std::move(result));
    ++gathered;
    if (settings.progress) settings.progress(gathered, cells, settings.cell_name ? settings.cell_name(cell) : "");
  };

  MasterJob job;
  job.local = [&](RankShare& own) {
    int cell = 0;
    while (queue.take(cell)) own_results.put({cell, timed_cell(compute, cell, own)});
  };
  job.start = [&] {
    if (settings.progress) settings.progress(0, cells, "");
    for (int r = 1; r < ranks; ++r) give(r);
  };
  job.deliver_local = [&] {
    std::vector<std::pair<int, Bytes>> mine = own_results.take_all();
    for (auto& [cell, result] : mine) take_in(cell, std::move(result));
    return !mine.empty();
  };
  job.result = [&](const Message& m, double) {
    if (m.tag != kTagResult) return;
    bytes += (long long)m.data.size();
    Reader in(m.data);
    const int cell = in.get<int32_t>();
    give(m.source);  // the next cell first: the rank works while this one is gathered
    take_in(cell, Bytes(m.data.begin() + sizeof(int32_t), m.data.end()));
  };
  job.progress_note = [&] { return std::to_string(gathered) + " of " + std::to_string(cells) + " cells were done"; };
  job.close = [&] { queue.close(); };
  job.stop_patience_s = [&] { return settings.stop_patience_s; };
  std::vector<RankShare> shares = run_master(comm, job);
  if (gathered != cells)
    throw DeviceError("MPI: " + std::to_string(gathered) + " of " + std::to_string(cells) + " cells gathered");
  if (stats) {
    stats->ranks = std::move(shares);
    stats->cells = cells;
    stats->wall_ms = ms_since(t0);
    stats->bytes_received = bytes;
  }
}

}  // namespace

void run_grid(Communicator& comm, int cells, const CellFn& compute, const GatherFn& gather,
              const GridSettings& settings, GridStats* stats) {
  if (comm.rank() != 0) return work_cells(comm, compute);
  if (comm.distributed()) return gather_cells(comm, cells, compute, gather, settings, stats);
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
