// frame_queue.cpp - master-worker whole frames over the ranks of a job.
//
// Messages (tags of dist/job.hpp):
//   kTagWork   rank 0 -> rank: int32 frame index, uint64 n, n bytes of its
//              encoded scene; index -1: no frames left
//   kTagResult rank -> rank 0: int32 index, the FrameRun, uint8 kind, uint64
//              n, n bytes: kind 0, encode_rows(): one band of the frame (the
//              whole frame unless it exceeds kMaxTileBytes); kind 1, the
//              frame's encoded file (FrameQueueSettings::encode), whole
//   kTagReport rank -> rank 0: its share, after its last frame
// and the failure protocol of job.hpp (kTagError, kTagStop, kTagStopped).
#include "dist/frame_queue.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <exception>
#include <map>
#include <mutex>
#include <stdexcept>
#include <thread>

#include "cl/cl.hpp"
#include "dist/job.hpp"
#include "dist/wire.hpp"
#include "util/error.hpp"
#include "util/timer.hpp"

namespace clrt::dist {

namespace {

Bytes encode_work(int index, const Bytes& scene) {
  Writer w;
  w.put<int32_t>(index);
  w.put<uint64_t>(scene.size());
  w.put_raw(scene.data(), scene.size());
  return std::move(w.bytes);
}

void put_run(Writer& w, const FrameRun& run) {
  w.put<int32_t>(run.index);
  w.put_text(run.host), w.put_text(run.devices);
  w.put(run.ms), w.put(run.kernel_ms), w.put(run.build_ms);
  w.put<uint8_t>(run.build_cached);
  w.put<int32_t>(run.launches), w.put<int32_t>(run.host_timed_launches);
}

FrameRun get_run(Reader& r, int rank) {
  FrameRun run;
  run.rank = rank;
  run.index = r.get<int32_t>();
  run.host = r.get_text(), run.devices = r.get_text();
  run.ms = r.get<double>(), run.kernel_ms = r.get<double>(), run.build_ms = r.get<double>();
  run.build_cached = r.get<uint8_t>() != 0;
  run.launches = r.get<int32_t>(), run.host_timed_launches = r.get<int32_t>();
  return run;
}

// The rest of a message: a byte count and the bytes.
Bytes get_bytes(Reader& r) {
  Bytes b(size_t(r.get_count(1)));
  r.get_raw(b.data(), b.size());
  return b;
}

// What a result message holds after its FrameRun.
constexpr uint8_t kRows = 0, kFile = 1;

// Renders one frame and times it; across ranks the frame must be what the
// queue gathers.
Image render_frame(const RenderFrameFn& render, const Scene& scene, FrameRun& run, const FrameQueueSettings& s,
                   bool check) {
  const auto t0 = Clock::now();
  Image img = render(scene, run);
  run.ms = ms_since(t0);
  if (check && !img.holds(s.width, s.height, s.contents))
    throw std::logic_error("a rendered frame does not have the job's size and contents");
  return img;
}

void add_frame(RankShare& share, const FrameRun& run, int height) {
  share.devices = run.devices;
  share.units += 1;
  share.rows += height;
  share.busy_ms += run.ms;
  share.kernel_ms += run.kernel_ms;
}

std::string frame_label(int index) {
  return "frame " + std::to_string(index) + ": ";
}

void work(Communicator& comm, const FrameQueueSettings& settings, const RenderFrameFn& render) {
  RankShare share;
  share.rank = comm.rank();
  share.host = comm.host();
  std::exception_ptr failure;
  int index = -1;
  try {
    const int band = rows_per_message(settings.width, settings.height, settings.contents, settings.max_message_bytes);
    for (;;) {
      const Message m = receive_work(comm);
      Reader in(m.data);
      index = in.get<int32_t>();
      if (index < 0) break;  // no frames left
      const Scene scene = decode_scene(get_bytes(in));
      FrameRun run;
      run.index = index, run.rank = comm.rank(), run.host = share.host;
      Image img;
      std::string file;
      keep_alive(comm, [&] {
        img = render_frame(render, scene, run, settings, /*check=*/true);
        if (settings.encode) file = settings.encode(img, scene, run);
      });
      add_frame(share, run, settings.height);
      if (settings.encode) {
        Writer w;
        put_run(w, run);
        w.put<uint8_t>(kFile);
        w.put<uint64_t>(file.size());
        w.put_raw(file.data(), file.size());
        comm.send(0, kTagResult, w.bytes);
        continue;
      }
      for (int y0 = 0; y0 < settings.height; y0 += band) {
        Writer w;
        put_run(w, run);
        w.put<uint8_t>(kRows);
        const Bytes rows = encode_rows(img, y0, std::min(settings.height, y0 + band));
        w.put<uint64_t>(rows.size());
        w.put_raw(rows.data(), rows.size());
        comm.send(0, kTagResult, w.bytes);
      }
    }
    comm.send(0, kTagReport, encode_share(share));
    comm.flush();
    return;
  } catch (const JobAborted&) {
    throw;
  } catch (...) {
    failure = std::current_exception();
  }
  report_failure_to_root(comm, (index >= 0 ? frame_label(index) : std::string()) + exception_text(failure));
}

// A frame on its way to rank 0 in bands.
struct Arriving {
  Image img;
  FrameRun run;
  int rows = 0;
};

// A frame rank 0's own thread finished: its pixels, or its file where the
// queue encodes.
struct Finished {
  Image img;
  FrameRun run;
  std::string file;
};

void master(Communicator& comm, size_t count, const SceneSource& scenes, const FrameQueueSettings& settings,
            const RenderFrameFn& render, const FrameDoneFn& done, FrameQueueStats* stats) {
  const auto t0 = Clock::now();
  const int ranks = comm.size();
  const int frames = int(count);
  std::vector<RankShare> shares(static_cast<size_t>(ranks));
  for (int r = 0; r < ranks; ++r) shares[size_t(r)].rank = r;
  const std::string host = comm.host();
  shares[0].host = host;

  // The frames not yet handed out, taken by this thread (for the other
  // ranks) and by rank 0's render thread.
  std::mutex mutex;
  int next = 0;
  bool closed = false;
  std::vector<Finished> finished;
  const auto take = [&](int& index) {
    std::lock_guard<std::mutex> lock(mutex);
    if (closed || next >= frames) return false;
    index = next++;
    return true;
  };
  const auto left = [&] {
    std::lock_guard<std::mutex> lock(mutex);
    return closed ? 0 : frames - next;
  };

  // Rank 0 renders too, on a thread of its own: this thread answers the
  // other ranks and writes the frames (MPI_THREAD_FUNNELED: only it calls
  // MPI).
  std::exception_ptr local_failure;
  int local_index = -1;
  std::atomic<bool> local_done{false};
  std::thread local([&] {
    try {
      while (take(local_index)) {
        FrameRun run;
        run.index = local_index, run.rank = 0, run.host = host;
        const std::shared_ptr<const Scene> scene = scenes(size_t(local_index));
        Image img = render_frame(render, *scene, run, settings, /*check=*/true);
        std::string file;
        if (settings.encode) file = settings.encode(img, *scene, run), img = Image{};
        add_frame(shares[0], run, settings.height);
        std::lock_guard<std::mutex> lock(mutex);
        finished.push_back(Finished{std::move(img), run, std::move(file)});
      }
    } catch (...) {
      local_failure = std::current_exception();
    }
    local_done = true;
  });

  std::vector<int> outstanding(static_cast<size_t>(ranks), 0);
  std::vector<bool> told_done(static_cast<size_t>(ranks), false), reported(static_cast<size_t>(ranks), false);
  // Frames for `rank` up to `most` in its hands (one rendering, one queued
  // behind it while more frames are left than ranks: near the end a queued
  // frame would wait while another rank idles), or the news that there are
  // none left once it has none.
  const auto give = [&](int rank, int most) {
    int index = 0;
    while (outstanding[size_t(rank)] < most && (outstanding[size_t(rank)] == 0 || left() > ranks) && take(index)) {
      comm.send(rank, kTagWork, encode_work(index, encode_scene(*scenes(size_t(index)))));
      ++outstanding[size_t(rank)];
    }
    if (outstanding[size_t(rank)] == 0 && !told_done[size_t(rank)]) {
      comm.send(rank, kTagWork, encode_work(-1, {}));
      told_done[size_t(rank)] = true;
    }
  };
  for (int r = 1; r < ranks; ++r) give(r, 1);
  for (int r = 1; r < ranks; ++r) give(r, 2);

  int waiting = ranks - 1;  // ranks that have not reported
  int frames_done = 0;
  double longest_ms = 0;
  std::string remote_failure;
  std::exception_ptr own_failure;  // done() or a malformed message
  long long bytes = 0;
  std::map<int, Arriving> arriving;
  const auto deliver = [&](const Image& img, const std::string& file, const FrameRun& run) {
    longest_ms = std::max(longest_ms, run.ms);
    if (settings.encode)
      settings.file_done(file, run);
    else
      done(img, run);
    ++frames_done;
    if (settings.progress) settings.progress(frames_done, frames, "frames");
  };
  if (settings.progress) settings.progress(0, frames, "frames");
  auto pause = std::chrono::microseconds(20);
  const auto failed = [&] { return !remote_failure.empty() || own_failure || (local_done && local_failure); };
  Liveness live(comm);
  while ((frames_done < frames || waiting > 0) && !failed()) {
    try {
      std::vector<Finished> mine;
      {
        std::lock_guard<std::mutex> lock(mutex);
        mine.swap(finished);
      }
      for (const Finished& f : mine) deliver(f.img, f.file, f.run);
      if (!mine.empty()) continue;
      Message m;
      if (!comm.try_receive(m)) {
        const std::string silent = live.silent([&](int r) { return !reported[size_t(r)]; });
        if (!silent.empty())
          fail_silent(comm, silent + "; " + std::to_string(frames_done) + " of " + std::to_string(frames) +
                                " frames were done");
        std::this_thread::sleep_for(pause);
        pause = std::min(pause * 2, std::chrono::microseconds(1000));
        continue;
      }
      pause = std::chrono::microseconds(20);
      live.heard(m.source);
      if (m.tag == kTagResult) {
        Reader in(m.data);
        const FrameRun run = get_run(in, m.source);
        const uint8_t kind = in.get<uint8_t>();
        const Bytes rows = get_bytes(in);
        if (run.index < 0 || run.index >= frames) throw DeviceError("MPI: a frame out of the job in a message");
        if (kind != (settings.encode ? kFile : kRows)) throw DeviceError("MPI: a frame of the wrong kind in a message");
        bytes += (long long)m.data.size();
        if (kind == kFile) {
          --outstanding[size_t(m.source)];
          give(m.source, 2);
          deliver(Image{}, std::string(rows.begin(), rows.end()), run);
          continue;
        }
        Arriving& a = arriving[run.index];
        if (a.img.pixels() == 0) a.img = Image(settings.width, settings.height, settings.contents), a.run = run;
        int y0 = 0, y1 = 0;
        decode_rows(rows, a.img, y0, y1);
        a.rows += y1 - y0;
        if (a.rows < settings.height) continue;
        const Arriving whole = std::move(a);
        arriving.erase(run.index);
        --outstanding[size_t(m.source)];
        give(m.source, 2);
        deliver(whole.img, {}, whole.run);
      } else if (m.tag == kTagReport) {
        shares[size_t(m.source)] = decode_share(m.data, m.source);
        reported[size_t(m.source)] = true;
        --waiting;
      } else if (m.tag == kTagError) {
        Reader in(m.data);
        remote_failure = in.get_text();
      }
    } catch (...) {
      own_failure = std::current_exception();
    }
  }
  if (failed()) {
    {
      std::lock_guard<std::mutex> lock(mutex);
      closed = true;
    }
    std::vector<int> running;
    for (int r = 1; r < ranks; ++r)
      if (!reported[size_t(r)]) running.push_back(r);
    std::string line;
    if (!remote_failure.empty())
      line = remote_failure;
    else if (own_failure)
      line = exception_text(own_failure);
    else
      line = rank_label(0, host) + ": " + frame_label(local_index) + exception_text(local_failure);
    // A rank is told to stop between frames: give it the longest frame yet
    // to finish the one it renders.
    stop_ranks(
        comm, running, [&] { std::fprintf(stderr, "clrt: error: %s\n", line.c_str()); }, 30 + 2 * longest_ms / 1000);
    local.join();
    if (own_failure && remote_failure.empty()) std::rethrow_exception(own_failure);
    throw DeviceError(line);
  }
  local.join();
  if (stats) {
    stats->ranks = shares;
    stats->frames = frames;
    stats->wall_ms = ms_since(t0);
    stats->bytes_received = bytes;
  }
}

}  // namespace

int rows_per_message(int width, int height, const FrameContents& contents, long long max_bytes) {
  const long long row = static_cast<long long>(row_pixel_bytes(contents)) * std::max(1, width);
  return int(std::max<long long>(1, std::min<long long>(std::max(1, height), max_bytes / row)));
}

void farm_frames(Communicator& comm, const std::vector<Scene>& scenes, const FrameQueueSettings& settings,
                 const RenderFrameFn& render, const FrameDoneFn& done, FrameQueueStats* stats) {
  // Each frame's scene is the vector's own (an aliasing pointer, no copy).
  const SceneSource source = [&scenes](size_t i) { return std::shared_ptr<const Scene>(std::shared_ptr<const Scene>(), &scenes[i]); };
  farm_frames(comm, scenes.size(), source, settings, render, done, stats);
}

void farm_frames(Communicator& comm, size_t count, const SceneSource& scenes, const FrameQueueSettings& settings,
                 const RenderFrameFn& render, const FrameDoneFn& done, FrameQueueStats* stats) {
  if (comm.rank() != 0) return work(comm, settings, render);
  if (comm.distributed()) return master(comm, count, scenes, settings, render, done, stats);
  // A world of one: frame after frame on this thread.
  const auto t0 = Clock::now();
  RankShare share;
  share.host = comm.host();
  const int frames = int(count);
  if (settings.progress) settings.progress(0, frames, "frames");
  for (int i = 0; i < frames; ++i) {
    FrameRun run;
    run.index = i, run.host = share.host;
    const std::shared_ptr<const Scene> scene = scenes(size_t(i));
    const Image img = render_frame(render, *scene, run, settings, /*check=*/false);
    add_frame(share, run, settings.height);
    if (settings.encode)
      settings.file_done(settings.encode(img, *scene, run), run);
    else
      done(img, run);
    if (settings.progress) settings.progress(i + 1, frames, "frames");
  }
  if (stats) *stats = FrameQueueStats{{share}, frames, ms_since(t0), 0};
}

}  // namespace clrt::dist
