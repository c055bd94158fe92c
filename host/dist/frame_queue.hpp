// frame_queue.hpp - many frames (one scene each) across the ranks of a job,
// master-worker by whole frames: rank 0 holds every scene and hands frames
// out in order as ranks ask for them (a rank renders one while its next one
// is on its way, while enough frames are left), renders frames itself on a
// thread of its own, and gathers each finished frame's pixels, handing it
// to the caller (who writes it) as it arrives. A frame is rendered whole by
// one rank, with its own renderer (its own --device), so its pixels are
// those of a single-process render of the same scene (tests/dist/).
#pragma once
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "dist/communicator.hpp"
#include "dist/frame_farm.hpp"
#include "image/image.hpp"
#include "scene/scene.hpp"
#include "util/progress.hpp"

namespace clrt::dist {

// How one frame was rendered: `render` fills the device side, the queue
// the rest.
struct FrameRun {
  int index = 0;  // the frame (its scene's place in the list)
  int rank = 0;
  std::string host;
  std::string devices;  // what rendered it (device names, or the reference)
  double ms = 0;        // wall time of render() for this frame on its rank
  double kernel_ms = 0, build_ms = 0;
  bool build_cached = false;
  int launches = 0, host_timed_launches = 0;
};

// Renders `scene` with this rank's renderer (constructed at its first frame
// and kept: its program and context are reused) into an image of the
// queue's size and contents, and fills run's device side. Called from one
// thread at a time: on rank 0 a thread of its own, elsewhere the main one.
using RenderFrameFn = std::function<Image(const Scene& scene, FrameRun& run)>;
// Rank 0's main thread, as each frame has arrived whole (in the order they
// finish, not their index order): writes it. An exception here (a write
// that failed) stops the job like a rank's failure, and is rethrown. (With
// FrameQueueSettings::encode, file_done is called instead.)
using FrameDoneFn = std::function<void(const Image& frame, const FrameRun& run)>;

// Encodes a frame just rendered into its file's bytes, on the rank that
// rendered it (from its render thread: rank 0's own thread for its frames).
using EncodeFrameFn = std::function<std::string(const Image& frame, const Scene& scene, const FrameRun& run)>;
// Rank 0's main thread, as each encoded frame has arrived: writes it.
using FileDoneFn = std::function<void(const std::string& file, const FrameRun& run)>;

struct FrameQueueSettings {
  int width = 0, height = 0;
  FrameContents contents;  // what each frame holds (and travels)
  ProgressFn progress{};   // rank 0: frames done of all
  // A frame travels in messages of at most this many bytes (bands of rows;
  // at least one row each).
  long long max_message_bytes = kMaxTileBytes;
  // Where set, each frame is encoded where it was rendered and travels as its
  // file (one message), and file_done gets it instead of `done` the pixels:
  // rank 0 only writes bytes, so encoding (~35 ms a 640x480 PNG, against
  // 8-10 ms of rendering) runs on every rank at once instead of one after
  // another on rank 0.
  EncodeFrameFn encode{};
  FileDoneFn file_done{};
};

struct FrameQueueStats {
  std::vector<RankShare> ranks;  // rank 0: one per rank, in rank order (units: frames)
  int frames = 0;
  double wall_ms = 0;            // the first frame handed out to the last one done
  long long bytes_received = 0;  // frames sent to rank 0
};

// Collective: every rank calls it. `scenes`: every frame's scene on rank 0
// (ignored elsewhere). In a world of one: each frame rendered and done in
// turn on this thread, exceptions as they are. Across ranks a failure
// anywhere - a rank's render, or `done` - stops every rank: rank 0 throws
// (a rank's error as a DeviceError "rank R (HOST): frame I: ...", its own
// `done`'s exception as it is), the others JobAborted. Frames done before
// the failure stay done. `stats` on rank 0.
void farm_frames(Communicator& comm, const std::vector<Scene>& scenes, const FrameQueueSettings& settings,
                 const RenderFrameFn& render, const FrameDoneFn& done, FrameQueueStats* stats);
// The same for `count` frames whose scenes rank 0 gets from `scenes(i)` as
// each frame is handed out (from rank 0's MPI thread and its render thread,
// so it must be safe to call from both): a run of large scenes need not be
// held all at once.
using SceneSource = std::function<std::shared_ptr<const Scene>(size_t index)>;
void farm_frames(Communicator& comm, size_t count, const SceneSource& scenes, const FrameQueueSettings& settings,
                 const RenderFrameFn& render, const FrameDoneFn& done, FrameQueueStats* stats);

}  // namespace clrt::dist
