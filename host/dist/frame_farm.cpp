// frame_farm.cpp - master-worker tiles over the ranks of a job.
#include "dist/frame_farm.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <exception>
#include <mutex>
#include <thread>

#include "cl/cl.hpp"
#include "dist/farm.hpp"
#include "dist/job.hpp"
#include "dist/wire.hpp"
#include "util/error.hpp"
#include "util/timer.hpp"

namespace clrt::dist {

int next_tile_rows(int left, int ranks, int width, int tile_rows, int max_rows) {
  if (left <= 0) return 0;
  int n;
  if (tile_rows > 0) {
    n = tile_rows;
  } else {
    const int min_rows = int(std::max<long long>(1, (kMinTilePixels + width - 1) / std::max(1, width)));
    n = std::max((left + 2 * ranks - 1) / (2 * ranks), min_rows);
  }
  return std::max(1, std::min({n, left, std::max(1, max_rows)}));
}

namespace {

Bytes encode_range(int y0, int y1) {
  Writer w;
  w.put<int32_t>(y0), w.put<int32_t>(y1);
  return std::move(w.bytes);
}

// Renders [y0, y1) and adds it to `share`.
void render_tile(Renderer& r, Image& img, int y0, int y1, RankShare& share) {
  const auto t0 = Clock::now();
  r.render_rows(img, y0, y1);
  const double ms = ms_since(t0);
  share.busy_ms += ms;
  share.tiles.push_back(TileTime{y0, y1, ms});
  share.kernel_ms += r.stats().kernel_ms;
  share.units += 1;
  share.rows += y1 - y0;
}

// A rank other than 0: tiles until none are left.
Image work_tiles(Communicator& comm, const std::function<Renderer&()>& prepare, const FarmSettings& settings) {
  Renderer* r = nullptr;
  Image img;  // (outlives run_worker's flush: rows are sent from it)
  WorkerJob job;
  job.prepare = [&](RankShare& share) {
    // The build and each tile run beside this thread's heartbeats.
    keep_alive(comm, [&] { r = &prepare(); });
    share.devices = r->device_names();
  };
  job.unit = [&](const Message& m, RankShare& share) {
    Reader in(m.data);
    const int y0 = in.get<int32_t>(), y1 = in.get<int32_t>();
    if (y1 <= y0) return false;  // no tiles left
    keep_alive(comm, [&] { render_tile(*r, img, y0, y1, share); });
    const auto sent = Clock::now();
    // Straight from the image: the rows stay untouched until the frame
    // ends (run_worker's flush), and the next tile writes other rows.
    comm.send_pieces(0, kTagRows + y0, row_pieces(img, y0, y1));
    share.send_ms += ms_since(sent);
    // The tests' stalled link: this rank stops taking part in MPI in the
    // middle of that rows message (over TCP its bytes then stop flowing)
    // and waits to be ended.
    if (comm.rank() == settings.test_stall_rank)
      for (;;) std::this_thread::sleep_for(std::chrono::seconds(1));
    return true;
  };
  run_worker(comm, job);
  return Image{};
}

// Rank 0's tiles: handed to its own render thread and to the other ranks.
class TileQueue {
 public:
  TileQueue(const FarmSettings& s, int ranks)
      : settings_(s), ranks_(ranks), max_rows_(rows_per_message(s.width, s.height, s.contents)) {}
  bool take(int& y0, int& y1) {
    std::lock_guard<std::mutex> lock(mutex_);
    const int n =
        closed_ ? 0 : next_tile_rows(settings_.height - next_, ranks_, settings_.width, settings_.tile_rows, max_rows_);
    if (n == 0) return false;
    y0 = next_, y1 = next_ + n, next_ = y1, tiles_ += 1;
    return true;
  }
  bool empty() {
    std::lock_guard<std::mutex> lock(mutex_);
    return closed_ || next_ >= settings_.height;
  }
  void close() {
    std::lock_guard<std::mutex> lock(mutex_);
    closed_ = true;
  }
  int tiles() {
    std::lock_guard<std::mutex> lock(mutex_);
    return tiles_;
  }

 private:
  const FarmSettings& settings_;
  int ranks_, max_rows_;
  std::mutex mutex_;
  int next_ = 0, tiles_ = 0;
  bool closed_ = false;
};

// Rank 0: hands out tiles, renders tiles itself, gathers the rows.
Image gather_tiles(Communicator& comm, const std::function<Renderer&()>& prepare, const FarmSettings& settings,
                   FarmStats* stats) {
  const auto t0 = Clock::now();
  const int ranks = comm.size();
  Image img(settings.width, settings.height, settings.contents);
  TileQueue queue(settings, ranks);
  std::atomic<long long> rows_done{0};
  std::vector<bool> told_done(static_cast<size_t>(ranks), false);
  // A tile for `rank`, or (once) the news that there are none left.
  // The news goes out right behind a rank's last tile when that tile
  // empties the queue: the rank then reports as soon as it has sent its
  // rows, without waiting for rank 0's answer to them (the end of a frame
  // is where every rank but the slowest waits).
  const auto give = [&](int rank) {
    int y0 = 0, y1 = 0;
    if (queue.take(y0, y1)) comm.send(rank, kTagWork, encode_range(y0, y1));
    if (queue.empty() && !told_done[size_t(rank)]) {
      comm.send(rank, kTagWork, encode_range(0, 0));
      told_done[size_t(rank)] = true;
    }
  };
  // A tile's rows are received straight into the frame: their first row is
  // in the tag, their count in the size. Each rank's rows arrive on their
  // own (Communicator::try_receive), so a rank whose link stalls holds up
  // none of the others' tiles.
  const size_t row_bytes = row_pixel_bytes(settings.contents) * size_t(settings.width);
  comm.set_receive_into([&](int from, int tag, size_t size) -> std::vector<Span> {
    if (tag < kTagRows) return {};
    const int y0 = tag - kTagRows;
    const size_t rows = size / row_bytes;
    if (y0 >= settings.height || size % row_bytes != 0 || rows == 0 || rows > size_t(settings.height - y0))
      throw DeviceError("MPI: rank " + std::to_string(from) + " sent rows that do not fit the frame");
    return row_pieces(img, y0, y0 + int(rows));
  });
  struct Unset {
    Communicator& comm;
    ~Unset() { comm.set_receive_into(nullptr); }
  } unset{comm};

  long long bytes = 0, shown = 0;
  double gather_ms = 0;
  MasterJob job;
  job.local = [&](RankShare& own) {
    Renderer& r = prepare();
    own.devices = r.device_names();
    int y0 = 0, y1 = 0;
    while (queue.take(y0, y1)) {
      render_tile(r, img, y0, y1, own);
      rows_done += y1 - y0;
    }
  };
  job.start = [&] {
    // Two tiles each: a rank renders one while the next is on its way.
    for (int k = 0; k < 2; ++k)
      for (int r = 1; r < ranks; ++r) give(r);
    if (settings.progress) settings.progress(0, settings.height, "rows");
  };
  job.result = [&](const Message& m, double receive_ms) {
    if (m.tag < kTagRows || !m.in_place) return;
    gather_ms += receive_ms;
    bytes += (long long)m.bytes;
    rows_done += (long long)(m.bytes / row_bytes);
    give(m.source);
  };
  job.idle = [&] {
    if (settings.progress && rows_done != shown) settings.progress(int(shown = rows_done), settings.height, "rows");
  };
  job.progress_note = [&] {
    return std::to_string(rows_done) + " of " + std::to_string(settings.height) + " rows had arrived";
  };
  // Every tile handed out: the frame ends within one tile's time, and each
  // wake-up's delay would add to it.
  job.all_handed_out = [&] { return queue.empty(); };
  job.close = [&] { queue.close(); };
  job.own_failure_as_is = true;  // (rows that do not fit: the error names the rank)
  std::vector<RankShare> shares = run_master(comm, job);
  if (settings.progress) settings.progress(settings.height, settings.height, "rows");
  if (stats) {
    stats->ranks = std::move(shares);
    stats->tiles = queue.tiles();
    stats->wall_ms = ms_since(t0);
    stats->bytes_received = bytes;
    stats->gather_ms = gather_ms;
  }
  return img;
}

}  // namespace

Image farm_frame(Communicator& comm, const std::function<Renderer&()>& prepare, const FarmSettings& settings,
                 FarmStats* stats) {
  if (comm.distributed()) {
    // Every rank starts this frame after rank 0 has (a broadcast of
    // nothing): a rank that fails at once cannot send its error into rank
    // 0's previous frame (bench/ and tests farm frame after frame).
    Bytes start;
    comm.broadcast(start, 0);
  }
  if (comm.rank() != 0) return work_tiles(comm, prepare, settings);
  if (comm.distributed()) return gather_tiles(comm, prepare, settings, stats);
  // A world of one: the frame as one process renders it.
  const auto t0 = Clock::now();
  Renderer& r = prepare();
  Image img(settings.width, settings.height, settings.contents);
  RankShare share;
  share.host = comm.host();
  share.devices = r.device_names();
  render_tile(r, img, 0, settings.height, share);
  if (stats) *stats = FarmStats{{share}, 1, ms_since(t0), 0};
  return img;
}

}  // namespace clrt::dist
