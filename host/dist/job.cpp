// job.cpp - sharing input from rank 0, and failing as one job.
#include "dist/job.hpp"

#include <chrono>
#include <exception>
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

}  // namespace clrt::dist
