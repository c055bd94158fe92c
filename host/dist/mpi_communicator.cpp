// mpi_communicator.cpp - the world of an mpirun job, over Open MPI (built
// with CLRT_MPI=ON). Sends are MPI_Isend of a copy kept until delivered, so
// two ranks sending large messages to each other never deadlock. Receives
// never block: every envelope that arrives is matched (MPI_Improbe) and its
// message received with MPI_Imrecv, one at a time per sender and in order,
// and polled with MPI_Test; a caller that waits sleeps between polls instead
// of spinning in MPI_Recv. So a sender whose link stalls in the middle of a
// message holds up nobody else's messages (before, rank 0's one MPI thread
// sat in MPI_Recv, spinning, and no rank got work).
#include <mpi.h>

#include <chrono>
#include <climits>
#include <cstdio>
#include <cstring>
#include <deque>
#include <list>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <thread>

#include "dist/communicator.hpp"
#include "dist/host_name.hpp"
#include "dist/single_process.hpp"
#include "util/error.hpp"

namespace clrt::dist {

namespace {

// MPI's error code as text ("MPI_ERR_TRUNCATE: message truncated").
std::string mpi_error_text(int code) {
  char text[MPI_MAX_ERROR_STRING] = {};
  int length = 0;
  MPI_Error_string(code, text, &length);
  return std::string(text, size_t(length));
}

void check(int code, const char* what) {
  if (code != MPI_SUCCESS) throw DeviceError(std::string("MPI: ") + what + ": " + mpi_error_text(code));
}

// Several pieces of memory as one MPI datatype (absolute addresses, sent
// from or received into MPI_BOTTOM); freed with the object (MPI keeps it
// alive for operations still pending).
struct Pieces {
  MPI_Datatype type = MPI_DATATYPE_NULL;
  explicit Pieces(const std::vector<Span>& pieces) {
    std::vector<int> lengths;
    std::vector<MPI_Aint> addresses;
    for (const Span& p : pieces) {
      if (p.bytes > size_t(INT_MAX)) throw std::length_error("MPI message piece over 2 GiB");
      MPI_Aint address = 0;
      check(MPI_Get_address(p.data, &address), "MPI_Get_address");
      lengths.push_back(int(p.bytes));
      addresses.push_back(address);
    }
    check(MPI_Type_create_hindexed(int(pieces.size()), lengths.data(), addresses.data(), MPI_BYTE, &type),
          "MPI_Type_create_hindexed");
    check(MPI_Type_commit(&type), "MPI_Type_commit");
  }
  ~Pieces() { MPI_Type_free(&type); }
  Pieces(const Pieces&) = delete;
  Pieces& operator=(const Pieces&) = delete;
};

class MpiWorld final : public Communicator {
 public:
  MpiWorld() {
    check(MPI_Comm_rank(MPI_COMM_WORLD, &rank_), "MPI_Comm_rank");
    check(MPI_Comm_size(MPI_COMM_WORLD, &size_), "MPI_Comm_size");
    // Errors come back as codes (check() turns them into exceptions) instead
    // of aborting the job from inside the library.
    MPI_Comm_set_errhandler(MPI_COMM_WORLD, MPI_ERRORS_RETURN);
    // Every rank's host, once: a rank that stops answering cannot say where
    // it runs any more.
    char name[MPI_MAX_PROCESSOR_NAME] = {};
    int length = 0;
    check(MPI_Get_processor_name(name, &length), "MPI_Get_processor_name");
    std::vector<char> all(size_t(size_) * MPI_MAX_PROCESSOR_NAME);
    check(MPI_Allgather(name, MPI_MAX_PROCESSOR_NAME, MPI_CHAR, all.data(), MPI_MAX_PROCESSOR_NAME, MPI_CHAR,
                        MPI_COMM_WORLD),
          "MPI_Allgather");
    for (int r = 0; r < size_; ++r) {
      const char* at = all.data() + size_t(r) * MPI_MAX_PROCESSOR_NAME;
      hosts_.emplace_back(at, strnlen(at, MPI_MAX_PROCESSOR_NAME));
    }
  }
  ~MpiWorld() override {
    // Undelivered sends at exit: the job is ending on an error (flush() ran
    // otherwise); cancel them so MPI_Finalize does not wait on them.
    for (auto& s : sends_) {
      MPI_Cancel(&s.request);
      MPI_Request_free(&s.request);
    }
  }
  int rank() const override { return rank_; }
  int size() const override { return size_; }
  std::string host() const override { return host_name(); }
  std::string host_of(int rank) const override {
    return rank >= 0 && rank < int(hosts_.size()) ? hosts_[size_t(rank)] : "unknown host";
  }

  void send(int dest, int tag, const Bytes& data) override {
    if (data.size() > size_t(INT_MAX)) throw std::length_error("MPI message over 2 GiB");
    sends_.push_back(Pending{data, MPI_REQUEST_NULL, dest});
    Pending& p = sends_.back();
    check(MPI_Isend(p.data.data(), int(p.data.size()), MPI_BYTE, dest, tag, MPI_COMM_WORLD, &p.request), "MPI_Isend");
    progress();
  }

  void send_pieces(int dest, int tag, const std::vector<Span>& pieces) override {
    sends_.push_back(Pending{{}, MPI_REQUEST_NULL, dest});
    Pending& p = sends_.back();
    if (pieces.size() == 1) {
      if (pieces[0].bytes > size_t(INT_MAX)) throw std::length_error("MPI message over 2 GiB");
      check(MPI_Isend(pieces[0].data, int(pieces[0].bytes), MPI_BYTE, dest, tag, MPI_COMM_WORLD, &p.request),
            "MPI_Isend");
    } else {
      Pieces type(pieces);
      check(MPI_Isend(MPI_BOTTOM, 1, type.type, dest, tag, MPI_COMM_WORLD, &p.request), "MPI_Isend");
    }
    progress();
  }

  void set_receive_into(ReceiveInto into) override { into_ = std::move(into); }

  bool try_receive(Message& out, int source, int tag) override {
    pump();
    for (auto it = ready_.begin(); it != ready_.end(); ++it) {
      if ((source != kAnySource && it->source != source) || (tag != kAnyTag && it->tag != tag)) continue;
      out = std::move(*it);
      ready_.erase(it);
      return true;
    }
    return false;
  }

  Message receive(int source, int tag) override {
    Message m;
    // 20 us first (a reply usually follows fast), growing to 1 ms: latency
    // stays far below a tile's time and an idle rank costs ~0.1% of a core.
    auto pause = std::chrono::microseconds(20);
    while (!try_receive(m, source, tag)) {
      std::this_thread::sleep_for(pause);
      pause = std::min(pause * 2, std::chrono::microseconds(1000));
    }
    return m;
  }

  void broadcast(Bytes& data, int root) override {
    unsigned long long n = data.size();
    check(MPI_Bcast(&n, 1, MPI_UNSIGNED_LONG_LONG, root, MPI_COMM_WORLD), "MPI_Bcast");
    if (n > (unsigned long long)INT_MAX) throw std::length_error("MPI broadcast over 2 GiB");
    data.resize(size_t(n));
    check(MPI_Bcast(data.data(), int(n), MPI_BYTE, root, MPI_COMM_WORLD), "MPI_Bcast");
  }

  void flush() override {
    auto pause = std::chrono::microseconds(20);
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(silence_bound_s());
    while (progress() > 0) {
      if (std::chrono::steady_clock::now() > deadline)
        throw DeviceError("MPI: a message to rank " + std::to_string(sends_.front().dest) + " (" +
                          host_of(sends_.front().dest) + ") was not delivered in " + seconds_text(silence_bound_s()) +
                          " (--mpi-timeout): its link or the rank stalled");
      std::this_thread::sleep_for(pause);
      pause = std::min(pause * 2, std::chrono::microseconds(1000));
    }
  }

  [[noreturn]] void abort(int code) override {
    MPI_Abort(MPI_COMM_WORLD, code);
    std::_Exit(code);
  }

 private:
  struct Pending {
    Bytes data;
    MPI_Request request;
    int dest = 0;
  };
  // A message whose envelope has arrived (matched: no other receive can
  // take it), waiting for its sender's earlier message to be received.
  struct Matched {
    MPI_Message handle = MPI_MESSAGE_NULL;
    int tag = 0;
    size_t bytes = 0;
  };
  // The message being received from one sender.
  struct Receiving {
    MPI_Request request = MPI_REQUEST_NULL;
    Message message;
    std::unique_ptr<Pieces> type;  // in place, several pieces
  };

  // Matches every envelope that has arrived, starts the next receive of
  // each sender whose previous one is done, and moves finished messages to
  // ready_. One receive at a time per sender keeps each sender's messages
  // in order; senders do not wait for each other.
  void pump() {
    progress();
    for (;;) {
      int flag = 0, count = 0;
      MPI_Message handle = MPI_MESSAGE_NULL;
      MPI_Status status;
      check(MPI_Improbe(MPI_ANY_SOURCE, MPI_ANY_TAG, MPI_COMM_WORLD, &flag, &handle, &status), "MPI_Improbe");
      if (!flag) break;
      check(MPI_Get_count(&status, MPI_BYTE, &count), "MPI_Get_count");
      matched_[status.MPI_SOURCE].push_back(Matched{handle, status.MPI_TAG, size_t(count)});
    }
    for (auto it = matched_.begin(); it != matched_.end();) {
      const int source = it->first;
      std::deque<Matched>& waiting = it->second;
      for (;;) {
        if (auto r = receiving_.find(source); r != receiving_.end()) {
          int done = 0;
          check(MPI_Test(&r->second.request, &done, MPI_STATUS_IGNORE), "MPI_Test");
          if (!done) break;
          ready_.push_back(std::move(r->second.message));
          receiving_.erase(r);
        }
        if (waiting.empty()) break;
        start(source, waiting.front());
        waiting.pop_front();
      }
      it = waiting.empty() && !receiving_.count(source) ? matched_.erase(it) : std::next(it);
    }
  }

  void start(int source, Matched& m) {
    Receiving& r = receiving_[source];
    r.message.source = source;
    r.message.tag = m.tag;
    r.message.bytes = m.bytes;
    if (m.bytes > size_t(INT_MAX)) throw std::length_error("MPI message over 2 GiB");
    std::vector<Span> pieces = into_ ? into_(source, m.tag, m.bytes) : std::vector<Span>{};
    if (!pieces.empty()) {
      size_t total = 0;
      for (const Span& p : pieces) total += p.bytes;
      if (total != m.bytes) throw std::logic_error("a message's memory does not have its size");
      r.message.in_place = true;
      if (pieces.size() == 1) {
        check(MPI_Imrecv(pieces[0].data, int(m.bytes), MPI_BYTE, &m.handle, &r.request), "MPI_Imrecv");
      } else {
        r.type = std::make_unique<Pieces>(pieces);
        check(MPI_Imrecv(MPI_BOTTOM, 1, r.type->type, &m.handle, &r.request), "MPI_Imrecv");
      }
      return;
    }
    r.message.data.resize(m.bytes);
    check(MPI_Imrecv(r.message.data.data(), int(m.bytes), MPI_BYTE, &m.handle, &r.request), "MPI_Imrecv");
  }

  static std::string seconds_text(double s) {
    char text[32];
    std::snprintf(text, sizeof text, "%g s", s);
    return text;
  }
  // Frees delivered sends; returns how many are still pending.
  size_t progress() {
    stop_if_orphaned();  // every poll passes here: a rank whose launcher died stops
    for (auto it = sends_.begin(); it != sends_.end();) {
      int done = 0;
      check(MPI_Test(&it->request, &done, MPI_STATUS_IGNORE), "MPI_Test");
      it = done ? sends_.erase(it) : std::next(it);
    }
    return sends_.size();
  }

  int rank_ = 0, size_ = 1;
  std::vector<std::string> hosts_;
  std::list<Pending> sends_;  // a list: their buffers must not move
  ReceiveInto into_;
  std::map<int, std::deque<Matched>> matched_;  // by sender
  std::map<int, Receiving> receiving_;         // by sender
  std::deque<Message> ready_;                   // received whole, in the order they were
};

std::unique_ptr<Communicator>& current() {
  static std::unique_ptr<Communicator> world;
  return world;
}

}  // namespace

Communicator& world() {
  auto& w = current();
  if (!w) w = std::make_unique<SingleProcess>();
  return *w;
}

Session::Session(int& argc, char**& argv) {
  if (!launched_by_mpi()) return;
  int provided = 0;
  if (MPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided) != MPI_SUCCESS)
    throw DeviceError("MPI_Init_thread failed");
  current() = std::make_unique<MpiWorld>();
}

Session::~Session() {
  int initialized = 0, finalized = 0;
  MPI_Initialized(&initialized);
  MPI_Finalized(&finalized);
  if (!initialized || finalized) return;
  current().reset();
  MPI_Finalize();
}

bool built_with_mpi() {
  return true;
}

std::string mpi_version() {
  char text[MPI_MAX_LIBRARY_VERSION_STRING] = {};
  int length = 0;
  MPI_Get_library_version(text, &length);
  std::string v(text, size_t(length));
  const size_t end = v.find_first_of(",\n");
  return end == std::string::npos ? v : v.substr(0, end);
}

}  // namespace clrt::dist
