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
#include "dist/farm.hpp"
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

// A result message: the FrameRun, the kind, a byte count and the bytes.
Bytes encode_frame_result(const FrameRun& run, uint8_t kind, const void* data, size_t size) {
  Writer w;
  put_run(w, run);
  w.put<uint8_t>(kind);
  w.put<uint64_t>(size);
  w.put_raw(data, size);
  return std::move(w.bytes);
}

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

// A rank other than 0: frames until none are left.
void work_frames(Communicator& comm, const FrameQueueSettings& settings, const RenderFrameFn& render) {
  const int band = rows_per_message(settings.width, settings.height, settings.contents, settings.max_message_bytes);
  int index = -1;
  WorkerJob job;
  job.unit = [&](const Message& m, RankShare& share) {
    Reader in(m.data);
    index = in.get<int32_t>();
    if (index < 0) return false;  // no frames left
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
      comm.send(0, kTagResult, encode_frame_result(run, kFile, file.data(), file.size()));
      return true;
    }
    for (int y0 = 0; y0 < settings.height; y0 += band) {
      const Bytes rows = encode_rows(img, y0, std::min(settings.height, y0 + band));
      comm.send(0, kTagResult, encode_frame_result(run, kRows, rows.data(), rows.size()));
    }
    return true;
  };
  job.context = [&] { return index >= 0 ? frame_label(index) : std::string(); };
  run_worker(comm, job);
}

// The frames on their way to rank 0 in bands, by index.
class Arrivals {
 public:
  explicit Arrivals(const FrameQueueSettings& settings) : settings_(settings) {}
  // Adds a band of frame run.index: true once the frame is whole, which
  // then moves to `whole`.
  bool add(const FrameRun& run, const Bytes& band, Image& whole) {
    Arriving& a = arriving_[run.index];
    if (a.img.pixels() == 0) a.img = Image(settings_.width, settings_.height, settings_.contents);
    int y0 = 0, y1 = 0;
    decode_rows(band, a.img, y0, y1);
    a.rows += y1 - y0;
    if (a.rows < settings_.height) return false;
    whole = std::move(a.img);
    arriving_.erase(run.index);
    return true;
  }

 private:
  struct Arriving {
    Image img;
    int rows = 0;
  };
  const FrameQueueSettings& settings_;
  std::map<int, Arriving> arriving_;
};

// Rank 0's frames for the other ranks: for a rank, frames up to `most` in
// its hands (one rendering, one queued behind it while more frames are
// left than ranks: near the end a queued frame would wait while another
// rank idles), or the news that there are none left once it has none.
class Handout {
 public:
  Handout(Communicator& comm, UnitQueue& queue, const SceneSource& scenes)
      : comm_(comm),
        queue_(queue),
        scenes_(scenes),
        outstanding_(size_t(comm.size()), 0),
        told_done_(size_t(comm.size()), false) {}
  void give(int rank, int most) {
    int& held = outstanding_[size_t(rank)];
    int index = 0;
    while (held < most && (held == 0 || queue_.left() > comm_.size()) && queue_.take(index)) {
      comm_.send(rank, kTagWork, encode_work(index, encode_scene(*scenes_(size_t(index)))));
      ++held;
    }
    if (held == 0 && !told_done_[size_t(rank)]) {
      comm_.send(rank, kTagWork, encode_work(-1, {}));
      told_done_[size_t(rank)] = true;
    }
  }
  // A frame from `rank` has arrived whole: its next one goes out.
  void arrived(int rank) {
    --outstanding_[size_t(rank)];
    give(rank, 2);
  }

 private:
  Communicator& comm_;
  UnitQueue& queue_;
  const SceneSource& scenes_;
  std::vector<int> outstanding_;
  std::vector<bool> told_done_;
};

// A frame rank 0's own thread finished: its pixels, or its file where the
// queue encodes.
struct Finished {
  Image img;
  FrameRun run;
  std::string file;
};

// Rank 0: hands out frames, renders frames itself, gathers and delivers
// them.
void gather_frames(Communicator& comm, size_t count, const SceneSource& scenes, const FrameQueueSettings& settings,
                   const RenderFrameFn& render, const FrameDoneFn& done, FrameQueueStats* stats) {
  const auto t0 = Clock::now();
  const int ranks = comm.size();
  const int frames = int(count);
  UnitQueue queue(frames);
  Handout handout(comm, queue, scenes);
  Arrivals arrivals(settings);
  LocalResults<Finished> finished;
  int local_index = -1;

  int frames_done = 0;
  double longest_ms = 0;
  long long bytes = 0;
  const auto deliver = [&](const Image& img, const std::string& file, const FrameRun& run) {
    longest_ms = std::max(longest_ms, run.ms);
    if (settings.encode)
      settings.file_done(file, run);
    else
      done(img, run);
    ++frames_done;
    if (settings.progress) settings.progress(frames_done, frames, "frames");
  };

  MasterJob job;
  job.local = [&](RankShare& own) {
    while (queue.take(local_index)) {
      FrameRun run;
      run.index = local_index, run.rank = 0, run.host = own.host;
      const std::shared_ptr<const Scene> scene = scenes(size_t(local_index));
      Image img = render_frame(render, *scene, run, settings, /*check=*/true);
      std::string file;
      if (settings.encode) file = settings.encode(img, *scene, run), img = Image{};
      add_frame(own, run, settings.height);
      finished.put(Finished{std::move(img), run, std::move(file)});
    }
  };
  job.local_context = [&] { return frame_label(local_index); };
  job.start = [&] {
    for (int r = 1; r < ranks; ++r) handout.give(r, 1);
    for (int r = 1; r < ranks; ++r) handout.give(r, 2);
    if (settings.progress) settings.progress(0, frames, "frames");
  };
  job.deliver_local = [&] {
    const std::vector<Finished> mine = finished.take_all();
    for (const Finished& f : mine) deliver(f.img, f.file, f.run);
    return !mine.empty();
  };
  job.result = [&](const Message& m, double) {
    if (m.tag != kTagResult) return;
    Reader in(m.data);
    const FrameRun run = get_run(in, m.source);
    const uint8_t kind = in.get<uint8_t>();
    const Bytes payload = get_bytes(in);
    if (run.index < 0 || run.index >= frames) throw DeviceError("MPI: a frame out of the job in a message");
    if (kind != (settings.encode ? kFile : kRows)) throw DeviceError("MPI: a frame of the wrong kind in a message");
    bytes += (long long)m.data.size();
    Image whole;
    if (kind == kRows && !arrivals.add(run, payload, whole)) return;
    handout.arrived(m.source);
    deliver(whole, kind == kFile ? std::string(payload.begin(), payload.end()) : std::string(), run);
  };
  job.progress_note = [&] {
    return std::to_string(frames_done) + " of " + std::to_string(frames) + " frames were done";
  };
  job.close = [&] { queue.close(); };
  // A rank is told to stop between frames: give it the longest frame yet
  // to finish the one it renders.
  job.stop_patience_s = [&] { return 30 + 2 * longest_ms / 1000; };
  // done()'s exception (a write that failed) keeps its own error and exit
  // status.
  job.own_failure_as_is = true;
  std::vector<RankShare> shares = run_master(comm, job);
  if (stats) {
    stats->ranks = std::move(shares);
    stats->frames = frames;
    stats->wall_ms = ms_since(t0);
    stats->bytes_received = bytes;
  }
}

}  // namespace

void farm_frames(Communicator& comm, const std::vector<Scene>& scenes, const FrameQueueSettings& settings,
                 const RenderFrameFn& render, const FrameDoneFn& done, FrameQueueStats* stats) {
  // Each frame's scene is the vector's own (an aliasing pointer, no copy).
  const SceneSource source = [&scenes](size_t i) {
    return std::shared_ptr<const Scene>(std::shared_ptr<const Scene>(), &scenes[i]);
  };
  farm_frames(comm, scenes.size(), source, settings, render, done, stats);
}

void farm_frames(Communicator& comm, size_t count, const SceneSource& scenes, const FrameQueueSettings& settings,
                 const RenderFrameFn& render, const FrameDoneFn& done, FrameQueueStats* stats) {
  if (comm.rank() != 0) return work_frames(comm, settings, render);
  if (comm.distributed()) return gather_frames(comm, count, scenes, settings, render, done, stats);
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
