// job.cpp - sharing input from rank 0, and failing as one job.
#include "dist/job.hpp"

#include <algorithm>
#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

#include "cl/cl.hpp"
#include "dist/wire.hpp"

namespace clrt::dist {

std::string exception_text(const std::exception_ptr& e) {
  try {
    std::rethrow_exception(e);
  } catch (const cl::Error& x) {
    return describe(x);
  } catch (const std::exception& x) {
    return x.what();
  } catch (...) {
    return "unknown error";
  }
}

std::string rank_label(int rank, const std::string& host) {
  return "rank " + std::to_string(rank) + " (" + host + ")";
}

Bytes share_from_root(Communicator& comm, const std::function<Bytes()>& make) {
  if (!comm.distributed()) return make();
  // First byte: 1 = the payload follows, 0 = rank 0 failed.
  Bytes message;
  std::exception_ptr failure;
  if (comm.rank() == 0) {
    try {
      Bytes payload = make();
      message.reserve(payload.size() + 1);
      message.push_back(1);
      message.insert(message.end(), payload.begin(), payload.end());
    } catch (...) {
      failure = std::current_exception();
      message.assign(1, 0);
    }
  }
  comm.broadcast(message, 0);
  if (failure) std::rethrow_exception(failure);
  if (message.empty() || message[0] != 1) throw JobAborted();
  return Bytes(message.begin() + 1, message.end());
}

Scene share_scene(Communicator& comm, const std::function<Scene()>& load) {
  Scene scene;
  const Bytes bytes = share_from_root(comm, [&] {
    scene = load();
    return encode_scene(scene);
  });
  return comm.rank() == 0 ? scene : decode_scene(bytes);
}

Message receive_work(Communicator& comm) {
  for (;;) {
    Message m = comm.receive(0, kAnyTag);
    if (m.tag == kTagStop) {
      comm.send(0, kTagStopped, {});
      comm.flush();
      throw JobAborted();
    }
    if (m.tag == kTagWork) return m;
  }
}

void report_failure_to_root(Communicator& comm, const std::string& what) {
  Writer w;
  w.put_text(rank_label(comm.rank(), comm.host()) + ": " + what);
  comm.send(0, kTagError, w.bytes);
  // Whatever else arrives (work, rows' acknowledgements) is dropped until
  // rank 0's stop.
  for (;;) {
    const Message m = comm.receive(0, kAnyTag);
    if (m.tag == kTagStop) break;
  }
  comm.send(0, kTagStopped, {});
  comm.flush();
  throw JobAborted();
}

void stop_ranks(Communicator& comm, const std::vector<int>& running, const std::function<void()>& print,
                double patience_s) {
  for (int r : running) comm.send(r, kTagStop, {});
  std::vector<int> waiting = running;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(patience_s);
  while (!waiting.empty()) {
    Message m;
    if (comm.try_receive(m)) {
      // A rank that failed too answers the stop after its error message;
      // results in flight are dropped. A rank whose report was in flight
      // had finished (it listens no more): that is its answer.
      if (m.tag == kTagStopped || m.tag == kTagReport)
        for (size_t i = 0; i < waiting.size(); ++i)
          if (waiting[i] == m.source) waiting.erase(waiting.begin() + long(i));
      continue;
    }
    if (std::chrono::steady_clock::now() > deadline) {
      print();
      comm.abort(2);
    }
    std::this_thread::sleep_for(std::chrono::microseconds(200));
  }
  comm.flush();
}

namespace {

double now_s() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

}  // namespace

void keep_alive(Communicator& comm, const std::function<void()>& work) {
  std::mutex mutex;
  std::condition_variable finished;
  bool done = false;
  std::exception_ptr failure;
  std::thread worker([&] {
    try {
      work();
    } catch (...) {
      failure = std::current_exception();
    }
    std::lock_guard<std::mutex> lock(mutex);
    done = true;
    finished.notify_one();
  });
  const auto beat = std::chrono::duration<double>(std::min(5.0, silence_bound_s() / 4));
  std::unique_lock<std::mutex> lock(mutex);
  while (!finished.wait_for(lock, beat, [&] { return done; })) {
    lock.unlock();
    try {
      comm.send(0, kTagAlive, {});
    } catch (...) {  // (the work's own end says what went wrong)
    }
    lock.lock();
  }
  lock.unlock();
  worker.join();
  if (failure) std::rethrow_exception(failure);
}

Liveness::Liveness(Communicator& comm) : comm_(comm), last_s_(size_t(comm.size()), now_s()) {}

void Liveness::heard(int rank) {
  if (rank >= 0 && rank < int(last_s_.size())) last_s_[size_t(rank)] = now_s();
}

std::string Liveness::silent(const std::function<bool(int)>& owes) const {
  const double bound = silence_bound_s(), now = now_s();
  for (int r = 1; r < int(last_s_.size()); ++r) {
    if (!owes(r) || now - last_s_[size_t(r)] <= bound) continue;
    char text[160];
    std::snprintf(text, sizeof text,
                  "no message for %g s (--mpi-timeout): the rank or its link stalled (a rank at work sends one "
                  "every %g s)",
                  bound, std::min(5.0, bound / 4));
    return rank_label(r, comm_.host_of(r)) + ": " + text;
  }
  return "";
}

void print_error_line(const std::string& line) {
  std::fprintf(stderr, "clrt: error: %s\n", line.c_str());
  std::fflush(stderr);
}

void fail_silent(Communicator& comm, const std::string& line) {
  print_error_line(line);
  comm.abort(2);
  std::_Exit(2);  // (abort() does not return; the compiler cannot see it through the interface)
}

}  // namespace clrt::dist
