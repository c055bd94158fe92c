// memory_use.cpp - see memory_use.hpp.
#include "util/memory_use.hpp"

#include <cstdio>
#include <cstring>

namespace clrt {

namespace {

// The "<key>:  <n> kB" line of /proc/self/status, in bytes.
size_t status_kib(const char* key) {
  std::FILE* f = std::fopen("/proc/self/status", "r");
  if (!f) return 0;
  char line[256];
  size_t kib = 0;
  const size_t n = std::strlen(key);
  while (std::fgets(line, sizeof line, f))
    if (std::strncmp(line, key, n) == 0 && line[n] == ':') {
      unsigned long long v = 0;
      if (std::sscanf(line + n + 1, "%llu", &v) == 1) kib = size_t(v);
      break;
    }
  std::fclose(f);
  return kib * 1024;
}

}  // namespace

size_t resident_bytes() {
  return status_kib("VmRSS");
}

size_t peak_resident_bytes() {
  return status_kib("VmHWM");
}

bool reset_peak_resident() {
  std::FILE* f = std::fopen("/proc/self/clear_refs", "w");
  if (!f) return false;
  const bool written = std::fputs("5", f) >= 0;
  return std::fclose(f) == 0 && written;
}

}  // namespace clrt
