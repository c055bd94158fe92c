// content_hash.hpp - FNV-1a over 64-bit words, fed in pieces: a key for
// "the same data" (the lanes probe's memory, the packed triangles' digest),
// not a checksum against tampering.
#pragma once
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <vector>

namespace clrt {

struct ContentHash {
  uint64_t value = 1469598103934665603ull;
  // Each piece's bytes as words, its tail and length as one more: equal
  // sequences of pieces give equal values.
  void add(const void* data, size_t bytes) {
    const auto* p = static_cast<const unsigned char*>(data);
    size_t i = 0;
    for (; i + 8 <= bytes; i += 8) {
      uint64_t word;
      std::memcpy(&word, p + i, 8);
      value = (value ^ word) * 1099511628211ull;
    }
    uint64_t tail = 0;
    if (bytes > i) std::memcpy(&tail, p + i, bytes - i);  // (an empty vector's data() may be null)
    value = (value ^ tail ^ bytes) * 1099511628211ull;
  }
  template <class T>
  void add(const std::vector<T>& v) {
    add(v.data(), v.size() * sizeof(T));
  }
};

}  // namespace clrt
