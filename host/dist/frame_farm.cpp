// frame_farm.cpp - master-worker tiles over the ranks of a job.
#include "dist/frame_farm.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <exception>
#include <mutex>
#include <thread>

#include "cl/cl.hpp"
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

Image work(Communicator& comm, const std::function<Renderer&()>& prepare, const FarmSettings& settings) {
  RankShare share;
  share.host = comm.host();
  std::exception_ptr failure;
  try {
    // The build and each tile run beside this thread's heartbeats.
    Renderer* r = nullptr;
    keep_alive(comm, [&] { r = &prepare(); });
    share.devices = r->device_names();
    Image img;
    for (;;) {
      const Message m = receive_work(comm);
      Reader in(m.data);
      const int y0 = in.get<int32_t>(), y1 = in.get<int32_t>();
      if (y1 <= y0) break;  // no tiles left
      keep_alive(comm, [&] { render_tile(*r, img, y0, y1, share); });
      const auto sent = Clock::now();
      // Straight from the image: the rows stay untouched until the frame
      // ends (flush() below), and the next tile writes other rows.
      comm.send_pieces(0, kTagRows + y0, row_pieces(img, y0, y1));
      share.send_ms += ms_since(sent);
      // The tests' stalled link: this rank stops taking part in MPI in the
      // middle of that rows message (over TCP its bytes then stop flowing)
      // and waits to be ended.
      if (comm.rank() == settings.test_stall_rank)
        for (;;) std::this_thread::sleep_for(std::chrono::seconds(1));
    }
    comm.send(0, kTagReport, encode_share(share));
    comm.flush();
    return Image{};
  } catch (const JobAborted&) {
    throw;
  } catch (...) {
    failure = std::current_exception();
  }
  report_failure_to_root(comm, exception_text(failure));
}

// Rank 0's tiles: handed to its own render thread and to the other ranks.
class TileQueue {
 public:
  TileQueue(const FarmSettings& s, int ranks)
      : settings_(s),
        ranks_(ranks),
        max_rows_(int(std::min<long long>(
            s.height, kMaxTileBytes / (static_cast<long long>(row_pixel_bytes(s.contents)) * s.width)))) {}
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

Image master(Communicator& comm, const std::function<Renderer&()>& prepare, const FarmSettings& settings,
             FarmStats* stats) {
  const auto t0 = Clock::now();
  const int ranks = comm.size();
  Image img(settings.width, settings.height, settings.contents);
  TileQueue queue(settings, ranks);
  std::atomic<long long> rows_done{0};
  std::vector<RankShare> shares(static_cast<size_t>(ranks));
  for (int r = 0; r < ranks; ++r) shares[size_t(r)].rank = r;
  shares[0].host = comm.host();
  // Rank 0 renders too, on a thread of its own: this thread answers the
  // other ranks (MPI_THREAD_FUNNELED: only it calls MPI).
  std::exception_ptr local_failure;
  std::atomic<bool> local_done{false};
  std::thread local([&] {
    try {
      Renderer& r = prepare();
      shares[0].devices = r.device_names();
      int y0 = 0, y1 = 0;
      while (queue.take(y0, y1)) {
        render_tile(r, img, y0, y1, shares[0]);
        rows_done += y1 - y0;
      }
    } catch (...) {
      local_failure = std::current_exception();
    }
    local_done = true;
  });

  std::vector<bool> told_done(static_cast<size_t>(ranks), false), reported(static_cast<size_t>(ranks), false);
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
  // Two tiles each: a rank renders one while the next is on its way.
  for (int k = 0; k < 2; ++k)
    for (int r = 1; r < ranks; ++r) give(r);

  int waiting = ranks - 1;  // ranks that have not reported
  std::string remote_failure;
  long long bytes = 0;
  double gather_ms = 0;
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
  Liveness live(comm);
  // Polls: 20 us after a message, doubling to 1 ms while none comes (each
  // wake-up takes rank 0's core from its render thread; workers have a
  // tile in hand meanwhile), and 20 us again once every tile is out.
  const auto poll = std::chrono::microseconds(20), poll_max = std::chrono::microseconds(1000);
  auto pause = poll;
  if (settings.progress) settings.progress(0, settings.height, "rows");
  long long shown = 0;
  while ((waiting > 0 || !local_done) && remote_failure.empty() && !local_failure) {
    const auto polled = Clock::now();
    Message m;
    if (!comm.try_receive(m)) {
      if (settings.progress && rows_done != shown) settings.progress(int(shown = rows_done), settings.height, "rows");
      const std::string silent = live.silent([&](int r) { return !reported[size_t(r)]; });
      if (!silent.empty())
        fail_silent(comm, silent + "; " + std::to_string(rows_done) + " of " + std::to_string(settings.height) +
                              " rows had arrived");
      std::this_thread::sleep_for(pause);
      // Every tile handed out: the frame ends within one tile's time, and
      // each wake-up's delay would add to it; before that, back off.
      pause = queue.empty() ? poll : std::min(pause * 2, poll_max);
      continue;
    }
    pause = poll;
    live.heard(m.source);
    if (m.tag >= kTagRows && m.in_place) {
      gather_ms += ms_since(polled);
      bytes += (long long)m.bytes;
      rows_done += (long long)(m.bytes / row_bytes);
      give(m.source);
      continue;
    }
    if (m.tag == kTagReport) {
      shares[size_t(m.source)] = decode_share(m.data, m.source);
      reported[size_t(m.source)] = true;
      --waiting;
    } else if (m.tag == kTagError) {
      Reader in(m.data);
      remote_failure = in.get_text();
    }
  }
  if (!remote_failure.empty() || local_failure) {
    queue.close();
    std::vector<int> running;
    for (int r = 1; r < ranks; ++r)
      if (!reported[size_t(r)]) running.push_back(r);
    const std::string line =
        !remote_failure.empty() ? remote_failure : rank_label(0, comm.host()) + ": " + exception_text(local_failure);
    stop_ranks(comm, running, [&] { std::fprintf(stderr, "clrt: error: %s\n", line.c_str()); });
    local.join();
    throw DeviceError(line);
  }
  local.join();
  if (settings.progress) settings.progress(settings.height, settings.height, "rows");
  if (stats) {
    stats->ranks = shares;
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
  if (comm.rank() != 0) return work(comm, prepare, settings);
  if (comm.distributed()) return master(comm, prepare, settings, stats);
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
