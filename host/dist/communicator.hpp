// communicator.hpp - the processes of one clrt job and the messages between
// them: Open MPI when clrt was built with CLRT_MPI and launched by mpirun,
// else a world of one process (the plain clrt, unchanged). Every MPI call of
// clrt is behind this interface (dist/mpi_communicator.cpp); the rest of
// dist/ speaks in ranks, tags and bytes.
//
// Threads: MPI is initialized with MPI_THREAD_FUNNELED, so only the thread
// that created the Session (main()) may call these functions; a rank's own
// rendering runs on other threads (its devices' threads) meanwhile.
#pragma once
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace clrt::dist {

using Bytes = std::vector<uint8_t>;

constexpr int kAnySource = -1, kAnyTag = -1;

// Memory a message is sent from or received into, without a copy.
struct Span {
  void* data = nullptr;
  size_t bytes = 0;
};

struct Message {
  int source = 0;
  int tag = 0;
  Bytes data;
  // Received straight into the memory a ReceiveInto gave (data is empty).
  bool in_place = false;
  size_t bytes = 0;  // the message's size, in either case
};

// Where a message lands, asked as its envelope arrives: the memory to
// receive it into (the sizes must add up to `bytes`; throw when it does not
// fit), or none for a buffer of its own.
using ReceiveInto = std::function<std::vector<Span>(int source, int tag, size_t bytes)>;

class Communicator {
 public:
  virtual ~Communicator() = default;
  virtual int rank() const = 0;
  virtual int size() const = 0;
  bool distributed() const { return size() > 1; }
  // This process's host name (per-rank shares), and rank r's (gathered
  // once at start: messages about a rank that stopped answering).
  virtual std::string host() const = 0;
  virtual std::string host_of(int rank) const = 0;
  // Sends without waiting (the bytes are copied and kept until delivered);
  // undelivered sends progress while this process receives or polls.
  virtual void send(int dest, int tag, const Bytes& data) = 0;
  // The next message matching source and tag (kAny*: any), waiting for it
  // by polling with short sleeps: a waiting rank does not take a core from
  // the OpenCL threads beside it (Open MPI's blocking receive spins).
  virtual Message receive(int source = kAnySource, int tag = kAnyTag) = 0;
  // The same without waiting: false when no such message has arrived whole.
  // Never waits for the rest of a message either: every message whose
  // envelope has arrived is being received (nonblocking, one at a time per
  // sender, in order), so a sender whose link stalls in the middle of a
  // large message holds up its own messages only, not the others'.
  virtual bool try_receive(Message& out, int source = kAnySource, int tag = kAnyTag) = 0;
  // Large messages without copies: send_pieces() sends the concatenation of
  // `pieces` straight from their memory, which must stay unchanged until
  // flush(); while `into` is set, every message whose envelope arrives is
  // offered to it and received straight into the memory it gives (then
  // try_receive() returns it with in_place set). nullptr: none.
  virtual void send_pieces(int dest, int tag, const std::vector<Span>& pieces) = 0;
  virtual void set_receive_into(ReceiveInto into) = 0;
  // Root's `data` on every rank (a collective: every rank must call it).
  virtual void broadcast(Bytes& data, int root = 0) = 0;
  // Waits until every send of this process has been delivered; a
  // DeviceError naming the rank when one has not been for silence_bound_s()
  // (its link or the rank stalled).
  virtual void flush() = 0;
  // Ends every process of the job now with `code` (a last resort, for a
  // rank that stopped answering).
  [[noreturn]] virtual void abort(int code) = 0;
};

// How long rank 0 waits for a message from a rank that owes it one (its
// rows, its frame, its cell, or the heartbeat a busy rank sends every
// quarter of it) before it ends the job naming that rank and its host
// (`--mpi-timeout`, docs/guide/mpi.md). Busy ranks send heartbeats, so a
// long tile or kernel build is not silence; a link or a rank that stalls is.
constexpr double kDefaultSilenceBoundS = 60;
void set_silence_bound_s(double seconds);
double silence_bound_s();

// The job's processes. Before a Session exists (tests, other programs) or
// when clrt was not launched by mpirun: a world of one.
Communicator& world();

// Initializes MPI for main() when clrt was built with MPI and launched by
// mpirun (launched_by_mpi()); finalizes it in the destructor. Otherwise it
// does nothing (MPI is not even initialized: no singleton start-up cost).
class Session {
 public:
  Session(int& argc, char**& argv);
  ~Session();
  Session(const Session&) = delete;
  Session& operator=(const Session&) = delete;
};

// Whether the environment says this process is one rank of an mpirun job
// (OMPI_COMM_WORLD_SIZE, PMIX_RANK or PMI_SIZE set): true also in a build
// without MPI, which then refuses to run (launch_error()).
bool launched_by_mpi();
// The launch's rank from the environment (0 when not launched by mpirun),
// for messages before any MPI call.
int environment_rank();
// A rank whose launcher is gone stops (main() calls watch_launcher() first
// thing): the parent's death sends it SIGTERM (PR_SET_PDEATHSIG), whose
// handler (util/output_file.hpp) removes any temp file and exits; and since
// that is not armed when the parent died before the call, launcher_gone()
// compares the parent with the one at start (and the launching daemon that
// Open MPI's session directory names). stop_if_orphaned() raises SIGTERM
// when it is gone: the communicator calls it as it polls, rank 0 before it
// writes. No-ops outside an mpirun launch.
void watch_launcher();
bool launcher_gone();
void stop_if_orphaned();
// Whether this binary was built with MPI (CMake option CLRT_MPI).
bool built_with_mpi();
// "Open MPI v4.1.4, ..." or "built without MPI".
std::string mpi_version();

}  // namespace clrt::dist
