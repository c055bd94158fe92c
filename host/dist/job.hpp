// job.hpp - what every distributed command does around its work: rank 0
// checks the input and shares it (or shares the failure, so no rank waits
// forever), errors travel to rank 0, and a rank told to stop stops.
#pragma once
#include <exception>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

#include "dist/communicator.hpp"
#include "scene/scene.hpp"

namespace clrt::dist {

// A rank other than 0 ends because the job failed elsewhere: rank 0 prints
// the one error line; this rank exits with status 2, printing nothing.
struct JobAborted : std::runtime_error {
  JobAborted() : std::runtime_error("the job was stopped by rank 0") {}
};

// Message tags of every protocol in dist/ (one place, so none collide).
enum Tag : int {
  kTagWork = 1,     // rank 0 -> rank: a unit of work (tile, frame, grid cell), or none left
  kTagResult = 2,   // rank -> rank 0: a unit's result
  kTagError = 3,    // rank -> rank 0: this rank failed (text)
  kTagReport = 4,   // rank -> rank 0: this rank's share, at the end
  kTagStop = 5,     // rank 0 -> rank: stop now, the job failed
  kTagStopped = 6,  // rank -> rank 0: stopped
  kTagAlive = 7,    // rank -> rank 0: still at work (a heartbeat while it computes; keep_alive())
  // rank -> rank 0: a tile's rows, straight from the image's memory
  // (frame_farm.cpp); the tag is kTagRows + the tile's first row (MPI
  // guarantees tags up to 32767; rows stay below kMaxImageEdge = 16384).
  kTagRows = 64,
};

// Rank 0 runs `make` (which may throw: bad input is found there, before any
// work is sent) and every rank gets its bytes; when `make` throws, every
// other rank gets the failure and throws JobAborted, and rank 0 rethrows.
// In a world of one: make().
Bytes share_from_root(Communicator& comm, const std::function<Bytes()>& make);

// A rank other than 0: the next unit of work rank 0 sends (a kTagWork
// message); rank 0's stop instead is answered and ends in JobAborted.
Message receive_work(Communicator& comm);

// share_from_root() for a scene: rank 0 runs `load` (which may throw, and
// may check other input first), every rank returns the same scene, exact.
Scene share_scene(Communicator& comm, const std::function<Scene()>& load);

// A rank other than 0 after an exception: tells rank 0 (what, with this
// rank and host), waits for its stop, and throws JobAborted. Rank 0: none.
[[noreturn]] void report_failure_to_root(Communicator& comm, const std::string& what);

// Rank 0 after a failure (its own or a rank's): tells every rank in
// `running` to stop and waits for them, up to `patience_s`. A rank that
// does not answer in time (hung in a device call) ends the job: `print`
// writes the error line, then MPI_Abort(2). Otherwise the caller reports.
void stop_ranks(Communicator& comm, const std::vector<int>& running, const std::function<void()>& print,
                double patience_s = 30);

// One line for any exception a rank's work throws (OpenCL errors described).
std::string exception_text(const std::exception_ptr& e);

// A rank other than 0: runs `work` on a thread of its own while this thread
// (the one that calls MPI) sends rank 0 a heartbeat (kTagAlive) every
// quarter of silence_bound_s(), at most every 5 s; returns when it is done,
// or rethrows what it threw. A long kernel build or tile is then no
// silence to rank 0's watch (Liveness); a rank that hangs, or whose link
// stalls, is.
void keep_alive(Communicator& comm, const std::function<void()>& work);

// Rank 0's watch over the ranks that owe it a message: each message from a
// rank resets its clock; silent() names the first that has been quiet for
// longer than silence_bound_s().
class Liveness {
 public:
  explicit Liveness(Communicator& comm);
  void heard(int rank);
  // "" or the error line's text ("rank 2 (h3): no message for 60 s ...")
  // for the first rank r with owes(r) that has been silent too long.
  std::string silent(const std::function<bool(int rank)>& owes) const;

 private:
  Communicator& comm_;
  std::vector<double> last_s_;  // steady-clock seconds of each rank's last message
};

// Rank 0's one error line for a failed job: "clrt: error: LINE" on stderr.
void print_error_line(const std::string& line);

// Rank 0 when a rank has gone silent: the one error line, then MPI_Abort
// (2): a rank that answers nothing cannot take part in MPI_Finalize, and
// mpirun ends every rank.
[[noreturn]] void fail_silent(Communicator& comm, const std::string& line);

// "rank 2 (node07): " for messages.
std::string rank_label(int rank, const std::string& host);

}  // namespace clrt::dist
