// program_cache_key.cpp - a cached program's key: its canonical text and
// the hash that names its entry.
#include <cstdio>
#include <string>

#include "cl/program_cache.hpp"
#include "cl/program_cache_files.hpp"

namespace clrt {

namespace cache_files {

uint64_t fnv1a(const void* data, size_t n, uint64_t h) {
  const auto* p = static_cast<const unsigned char*>(data);
  for (size_t i = 0; i < n; ++i) {
    h ^= p[i];
    h *= 1099511628211ULL;
  }
  return h;
}

}  // namespace cache_files

namespace {

// Length-prefixed fields: no two different keys serialize to the same text.
void field(std::string& out, const char* name, const std::string& v) {
  out += name;
  out += ' ';
  out += std::to_string(v.size());
  out += '\n';
  out += v;
  out += '\n';
}

}  // namespace

std::string ProgramCacheKey::text() const {
  std::string t;
  field(t, "source", source);
  field(t, "options", options);
  field(t, "device", device);
  field(t, "driver", driver);
  field(t, "platform", platform);
  return t;
}

std::string ProgramCacheKey::hash() const {
  std::string t = text();
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(cache_files::fnv1a(t.data(), t.size())));
  return buf;
}

}  // namespace clrt
