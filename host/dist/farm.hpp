// farm.hpp - the master-worker loop that spreads units of work (a frame's
// tiles, a run's frames, an evaluation grid's cells) over the ranks of a
// job, written once: rank 0 hands units out as ranks ask for them, works on
// units itself on a thread of its own, gathers the results and watches the
// ranks' silence; every other rank takes units until told there are none,
// and reports its share. A failure anywhere stops every rank (dist/job.hpp)
// and is one error line on rank 0. dist/frame_farm, frame_queue and grid are
// the jobs: what a unit is, how it travels, and when to wait how long.
#pragma once
#include <exception>
#include <functional>
#include <mutex>
#include <string>
#include <utility>
#include <vector>

#include "dist/communicator.hpp"
#include "image/image.hpp"

namespace clrt::dist {

// One tile a rank rendered: its rows and the wall time it took there.
struct TileTime {
  int y0 = 0, y1 = 0;
  double ms = 0;
};

// What one rank did in a frame (or a run of frames, or a grid).
struct RankShare {
  int rank = 0;
  std::string host;
  std::string devices;  // its devices' names
  int units = 0;        // tiles (or frames, or grid cells) it rendered
  long long rows = 0;   // image rows it rendered
  double busy_ms = 0;   // wall time spent rendering them
  double kernel_ms = 0;
  double send_ms = 0;           // farm_frame, ranks other than 0: encoding and sending its rows
  std::vector<TileTime> tiles;  // farm_frame: each tile it rendered, in order
};

// A rank's share as it travels to rank 0 (kTagReport: every field).
Bytes encode_share(const RankShare& share);
RankShare decode_share(const Bytes& bytes, int rank);

// A message carries at most this many bytes of pixels (a tile, or a band of
// a frame): MPI counts in int, and rank 0 holds a message whole.
constexpr long long kMaxTileBytes = 256LL << 20;

// Rows per result message for frames `width` wide holding `contents`: the
// whole frame where it fits `max_bytes`, else bands that do (one row at least).
int rows_per_message(int width, int height, const FrameContents& contents, long long max_bytes = kMaxTileBytes);

// A rank other than 0: its side of a farm.
struct WorkerJob {
  // Before the first unit (a renderer's build), or nothing.
  std::function<void(RankShare& share)> prepare{};
  // One unit from rank 0's kTagWork message: does it (inside keep_alive(),
  // so rank 0 hears from this rank meanwhile), adds it to `share` and sends
  // its result; false when the message says no units are left.
  std::function<bool(const Message& work, RankShare& share)> unit;
  // Text before a failure's ("frame 3: "), or nothing.
  std::function<std::string()> context{};
};

// Takes units until none are left, then sends rank 0 this rank's share.
// A failure is reported to rank 0 (with this rank's name and host), which
// stops the job: JobAborted then, as when rank 0 stops it for another.
void run_worker(Communicator& comm, const WorkerJob& job);

// Rank 0: its side of a farm. Every function but `local` runs on the
// calling thread (the only one that calls MPI).
struct MasterJob {
  // Rank 0's own units, on a thread of its own (it must not call MPI):
  // takes units from the queue the job shares with `give` until none are
  // left, adding them to `own`.
  std::function<void(RankShare& own)> local;
  // Text before the local thread's failure ("frame 3: "), or nothing.
  std::function<std::string()> local_context{};
  // Hands out the first units (whatever each rank should hold at start).
  std::function<void()> start;
  // Delivers what the local thread has finished, if it leaves results for
  // this thread: true when there were any (the loop then looks again before
  // it polls).
  std::function<bool()> deliver_local{};
  // A message other than a report, an error or a heartbeat: a unit's
  // result (the job hands that rank its next unit). `receive_ms`: the poll
  // that completed it.
  std::function<void(const Message& m, double receive_ms)> result;
  // Before each wait for a message (progress), or nothing.
  std::function<void()> idle{};
  // How far the job got, for the line about a silent rank ("12 of 40
  // frames were done").
  std::function<std::string()> progress_note;
  // Whether every unit has been handed out: the job ends within a unit's
  // time, and waits then poll briskly instead of backing off. Nothing:
  // always back off.
  std::function<bool()> all_handed_out{};
  // After a failure: hand out no more units (the local thread's stop too).
  std::function<void()> close;
  // After a failure, how long to wait for the ranks to stop before ending
  // the job (a rank stops between units: at least the longest unit).
  std::function<double()> stop_patience_s{};
  // An exception on this thread (a write that failed, a malformed message)
  // is rethrown as it is, its own error line and exit status; otherwise it
  // is rank 0's failure, a DeviceError "rank 0 (HOST): ...".
  bool own_failure_as_is = false;
};

// Runs the farm to its end: the ranks' shares, in rank order (rank 0's from
// `local`). On a failure anywhere, after every rank has stopped: throws the
// failing rank's error line as a DeviceError (or this thread's exception as
// it is, with own_failure_as_is). A rank silent for longer than
// silence_bound_s() ends the job at once (fail_silent()).
std::vector<RankShare> run_master(Communicator& comm, const MasterJob& job);

// The units of a farm that are numbered 0..count-1, handed out in order by
// rank 0's MPI thread and taken by its local thread.
class UnitQueue {
 public:
  explicit UnitQueue(int count) : count_(count) {}
  bool take(int& unit) {
    std::lock_guard<std::mutex> lock(mutex_);
    if (closed_ || next_ >= count_) return false;
    unit = next_++;
    return true;
  }
  // Units not yet handed out (0 once closed).
  int left() {
    std::lock_guard<std::mutex> lock(mutex_);
    return closed_ ? 0 : count_ - next_;
  }
  void close() {
    std::lock_guard<std::mutex> lock(mutex_);
    closed_ = true;
  }

 private:
  std::mutex mutex_;
  int count_, next_ = 0;
  bool closed_ = false;
};

// What rank 0's local thread finished, waiting for its MPI thread.
template <class T>
class LocalResults {
 public:
  void put(T&& result) {
    std::lock_guard<std::mutex> lock(mutex_);
    results_.push_back(std::move(result));
  }
  std::vector<T> take_all() {
    std::lock_guard<std::mutex> lock(mutex_);
    std::vector<T> out;
    out.swap(results_);
    return out;
  }

 private:
  std::mutex mutex_;
  std::vector<T> results_;
};

}  // namespace clrt::dist
