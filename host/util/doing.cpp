// doing.cpp - the steps a std::bad_alloc is reported against (doing.hpp).
#include "util/doing.hpp"

#include <utility>

namespace clrt {
namespace {

thread_local Doing* g_current = nullptr;
thread_local std::string g_failed;

}  // namespace

Doing::Doing(std::string what) : what_(std::move(what)), outer_(g_current), exceptions_(std::uncaught_exceptions()) {
  g_current = this;
  g_failed.clear();  // a new step: what failed before was handled
}

Doing::~Doing() {
  // Left by an exception: the innermost step it leaves is the first to see
  // it (outer ones keep it).
  if (std::uncaught_exceptions() > exceptions_ && g_failed.empty()) {
    try {
      g_failed = what_;
    } catch (...) {  // no memory even for the name: main() says "out of memory" alone
    }
  }
  g_current = outer_;
}

std::string failed_step() {
  return g_failed;
}

}  // namespace clrt
