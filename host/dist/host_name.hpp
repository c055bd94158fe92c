// host_name.hpp - this machine's name, for per-rank reports.
#pragma once
#include <unistd.h>

#include <string>

namespace clrt::dist {

inline std::string host_name() {
  char name[256] = {};
  if (::gethostname(name, sizeof name - 1) != 0) return "unknown host";
  return name;
}

}  // namespace clrt::dist
