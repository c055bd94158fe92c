// mpi_model.hpp - the model of docs/developer/distributed.md: the frame time of one
// frame farmed over P nodes (dist::farm_frame) with fixed tiles of r rows,
// from per-tile costs measured by clrt_mpi_bench and an assumed network.
// Pure functions (tests/dist/test_mpi_bench_model.cpp); no timing here.
//
//   n      = ceil(H / r) tiles of b = r W pixel_bytes bytes
//   t_tile = C r / H + tile_fixed + latency + b / link     (a node's time per tile: render, then send)
//   T_c    = ceil(n / P) t_tile                             (every node busy; the last round may be partial)
//   m      = n - ceil(n / P)                                (tiles rank 0 receives; it renders its share too)
//   T_0    = m (handle + b / store + b / link)              (rank 0's one MPI thread, message after message)
//   T(P)   = max(T_c, T_0) + latency                        (the first tile's request)
//   T(1)   = C                                              (no farm: the plain single-process render)
#pragma once
#include <algorithm>
#include <cmath>

namespace clrt::model {

struct FarmModel {
  // A node (measured, or assumed: a GPU's speed).
  double frame_ms = 0;       // C: one node renders the whole frame alone
  double tile_fixed_ms = 0;  // per tile on the rendering node besides its pixels (launch, map, encode)
  // The frame.
  int width = 1920, height = 1080;
  double pixel_bytes = 4;  // 8-bit RGBA
  // Rank 0 (measured).
  double handle_ms = 0;      // its MPI thread per rows message (probe, receive call, bookkeeping)
  double store_mbps = 1e12;  // copying received rows into the frame, MB/s (1 MB = 1e6 bytes)
  // The network (assumed).
  double latency_ms = 0;    // one-way message latency
  double link_mbps = 1e12;  // rank 0's link bandwidth, MB/s
};

struct FarmPrediction {
  int tiles = 0;
  double compute_ms = 0;  // T_c
  double root_ms = 0;     // T_0
  double frame_ms = 0;    // T(P)
  double speedup = 1;     // T(1) / T(P)
  bool root_bound = false;
};

inline FarmPrediction predict(const FarmModel& m, int nodes, int tile_rows) {
  FarmPrediction p;
  const int r = std::clamp(tile_rows, 1, m.height);
  p.tiles = (m.height + r - 1) / r;
  if (nodes <= 1) {
    p.tiles = 1;
    p.compute_ms = p.frame_ms = m.frame_ms;
    return p;
  }
  const double bytes = double(r) * m.width * m.pixel_bytes;
  const double tile_ms = m.frame_ms * r / m.height + m.tile_fixed_ms + m.latency_ms + bytes / (m.link_mbps * 1e3);
  const int rounds = (p.tiles + nodes - 1) / nodes;
  p.compute_ms = rounds * tile_ms;
  const int received = p.tiles - rounds;
  p.root_ms = received * (m.handle_ms + bytes / (m.store_mbps * 1e3) + bytes / (m.link_mbps * 1e3));
  p.root_bound = p.root_ms > p.compute_ms;
  p.frame_ms = std::max(p.compute_ms, p.root_ms) + m.latency_ms;
  p.speedup = m.frame_ms / p.frame_ms;
  return p;
}

// The tile height (1..H rows) with the shortest predicted frame on `nodes`
// nodes; of equal ones, the tallest (fewest messages).
inline int best_tile_rows(const FarmModel& m, int nodes) {
  int best = m.height;
  double best_ms = predict(m, nodes, best).frame_ms;
  for (int r = m.height - 1; r >= 1; --r) {
    const double ms = predict(m, nodes, r).frame_ms;
    if (ms < best_ms * (1 - 1e-12)) best = r, best_ms = ms;
  }
  return best;
}

// The shortest tile (rows) at which rank 0's serial work does not exceed
// the nodes' rendering (T_0 <= T_c); 0 when no tile height achieves it.
inline int shortest_root_safe_tile_rows(const FarmModel& m, int nodes) {
  for (int r = 1; r <= m.height; ++r)
    if (!predict(m, nodes, r).root_bound) return r;
  return 0;
}

}  // namespace clrt::model
