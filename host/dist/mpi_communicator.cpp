// mpi_communicator.cpp - the world of an mpirun job, over Open MPI (built
// with CLRT_MPI=ON). Sends are MPI_Isend of a copy kept until delivered, so
// two ranks sending large messages to each other never deadlock; receives
// probe and sleep instead of spinning in MPI_Recv.
#include <mpi.h>

#include <chrono>
#include <climits>
#include <list>
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

  void send(int dest, int tag, const Bytes& data) override {
    if (data.size() > size_t(INT_MAX)) throw std::length_error("MPI message over 2 GiB");
    sends_.push_back(Pending{data, MPI_REQUEST_NULL});
    Pending& p = sends_.back();
    check(MPI_Isend(p.data.data(), int(p.data.size()), MPI_BYTE, dest, tag, MPI_COMM_WORLD, &p.request), "MPI_Isend");
    progress();
  }

  void send_pieces(int dest, int tag, const std::vector<Span>& pieces) override {
    sends_.push_back(Pending{{}, MPI_REQUEST_NULL});
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

  bool probe(int source, int tag, int& from, int& tag_out, size_t& bytes) override {
    progress();
    int flag = 0, count = 0;
    MPI_Status status;
    check(MPI_Iprobe(source == kAnySource ? MPI_ANY_SOURCE : source, tag == kAnyTag ? MPI_ANY_TAG : tag, MPI_COMM_WORLD,
                     &flag, &status),
          "MPI_Iprobe");
    if (!flag) return false;
    check(MPI_Get_count(&status, MPI_BYTE, &count), "MPI_Get_count");
    from = status.MPI_SOURCE, tag_out = status.MPI_TAG, bytes = size_t(count);
    return true;
  }

  void receive_pieces(int source, int tag, const std::vector<Span>& pieces) override {
    if (pieces.size() == 1) {
      if (pieces[0].bytes > size_t(INT_MAX)) throw std::length_error("MPI message over 2 GiB");
      check(MPI_Recv(pieces[0].data, int(pieces[0].bytes), MPI_BYTE, source, tag, MPI_COMM_WORLD, MPI_STATUS_IGNORE),
            "MPI_Recv");
      return;
    }
    Pieces type(pieces);
    check(MPI_Recv(MPI_BOTTOM, 1, type.type, source, tag, MPI_COMM_WORLD, MPI_STATUS_IGNORE), "MPI_Recv");
  }

  bool try_receive(Message& out, int source, int tag) override {
    progress();
    int flag = 0;
    MPI_Status status;
    check(MPI_Iprobe(source == kAnySource ? MPI_ANY_SOURCE : source, tag == kAnyTag ? MPI_ANY_TAG : tag, MPI_COMM_WORLD,
                     &flag, &status),
          "MPI_Iprobe");
    if (!flag) return false;
    int count = 0;
    check(MPI_Get_count(&status, MPI_BYTE, &count), "MPI_Get_count");
    out.source = status.MPI_SOURCE;
    out.tag = status.MPI_TAG;
    out.data.resize(size_t(count));
    check(MPI_Recv(out.data.data(), count, MPI_BYTE, status.MPI_SOURCE, status.MPI_TAG, MPI_COMM_WORLD,
                   MPI_STATUS_IGNORE),
          "MPI_Recv");
    return true;
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
    while (progress() > 0) {
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
  };
  // Frees delivered sends; returns how many are still pending.
  size_t progress() {
    for (auto it = sends_.begin(); it != sends_.end();) {
      int done = 0;
      check(MPI_Test(&it->request, &done, MPI_STATUS_IGNORE), "MPI_Test");
      it = done ? sends_.erase(it) : std::next(it);
    }
    return sends_.size();
  }

  int rank_ = 0, size_ = 1;
  std::list<Pending> sends_;  // a list: their buffers must not move
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
