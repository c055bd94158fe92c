// single_process.hpp - the world of one process: rank 0 of 1. A message to
// oneself would never be answered, so sending is a logic error (dist/ never
// sends in a world of one).
#pragma once
#include <cstdlib>
#include <stdexcept>

#include "dist/communicator.hpp"
#include "dist/host_name.hpp"

namespace clrt::dist {

class SingleProcess final : public Communicator {
 public:
  int rank() const override { return 0; }
  int size() const override { return 1; }
  std::string host() const override { return host_name(); }
  std::string host_of(int) const override { return host_name(); }
  void send(int, int, const Bytes&) override { throw std::logic_error("send in a world of one process"); }
  Message receive(int, int) override { throw std::logic_error("receive in a world of one process"); }
  bool try_receive(Message&, int, int) override { return false; }
  void send_pieces(int, int, const std::vector<Span>&) override {
    throw std::logic_error("send in a world of one process");
  }
  void set_receive_into(ReceiveInto) override {}
  void broadcast(Bytes&, int) override {}
  void flush() override {}
  [[noreturn]] void abort(int code) override { std::_Exit(code); }
};

}  // namespace clrt::dist
