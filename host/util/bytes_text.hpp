// bytes_text.hpp - a size limit as messages print it: "256 MiB" when it is a
// whole number of MiB, else "1000 bytes".
#pragma once
#include <cstddef>
#include <string>

namespace clrt {

inline std::string bytes_text(size_t bytes) {
  return bytes % (size_t(1) << 20) == 0 ? std::to_string(bytes >> 20) + " MiB" : std::to_string(bytes) + " bytes";
}

}  // namespace clrt
