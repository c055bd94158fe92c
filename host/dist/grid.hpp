// grid.hpp - the independent cells of an evaluation grid (a sweep's depths
// x devices, accuracy's scenes x variants) spread over the ranks of a job,
// master-worker like dist/frame_farm.hpp: rank 0 hands out cell indices one
// at a time as ranks finish - cells differ in cost by orders of magnitude
// (depth 0 against depth 10, naive against fp64), so a static split would
// wait for the slowest rank - computes cells itself on a thread of its own,
// and gathers each cell's result, as bytes, by index.
#pragma once
#include <functional>
#include <string>
#include <vector>

#include "dist/communicator.hpp"
#include "dist/frame_farm.hpp"
#include "util/progress.hpp"

namespace clrt::dist {

// A cell's result as bytes. On rank 0 it runs on a thread other than the
// one that called run_grid (which answers the other ranks), so it must not
// call MPI; on the other ranks, on the calling thread.
using CellFn = std::function<Bytes(int cell)>;
// Rank 0 only, on the thread that called run_grid: cell's result, once per
// cell, in the order they arrive (not the order of the cells).
using GatherFn = std::function<void(int cell, Bytes&& result)>;

struct GridSettings {
  // Rank 0: cells gathered of all; `what` names the last one (cell_name).
  ProgressFn progress{};
  std::function<std::string(int cell)> cell_name{};
  // After a failure, how long rank 0 waits for the ranks to stop before it
  // ends the job (dist/job.hpp's stop_ranks): a rank stops between cells,
  // and a cell may take a while.
  double stop_patience_s = 60;
};

struct GridStats {
  std::vector<RankShare> ranks;  // rank 0: one per rank, in rank order (units: cells; rows: 0)
  int cells = 0;
  double wall_ms = 0;
  long long bytes_received = 0;  // results sent to rank 0 by the other ranks
};

// Collective: every rank calls it with the same `cells`. Cells are handed
// out in index order. A failure on any rank - in `compute`, or in `gather`
// on rank 0 - stops every rank: rank 0 throws the failing rank's error (one
// line, with the rank and host), the others JobAborted. In a world of one:
// gather(i, compute(i)) for each i in order, on the calling thread.
void run_grid(Communicator& comm, int cells, const CellFn& compute, const GatherFn& gather,
              const GridSettings& settings = {}, GridStats* stats = nullptr);

// "16 cells on 3 MPI ranks: 5012.3 ms, 176.03 MiB of results gathered",
// then one line per rank: "  rank 1 (host): 4 cells, busy 1234.5 ms".
std::string grid_share_lines(const GridStats& stats, const char* unit = "cells");

}  // namespace clrt::dist
