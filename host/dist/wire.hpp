// wire.hpp - what travels between ranks, as bytes: scenes, rows of a frame,
// texts and numbers. Every read is bounds-checked (a short or malformed
// message is a DeviceError, never a read past the end); both ends are the
// same clrt binary, so numbers travel in the host's byte order.
#pragma once
#include <cstdint>
#include <cstring>
#include <string>
#include <type_traits>
#include <vector>

#include "dist/communicator.hpp"
#include "image/image.hpp"
#include "scene/scene.hpp"

namespace clrt::dist {

class Writer {
 public:
  template <class T>
  void put(const T& v) {
    static_assert(std::is_trivially_copyable<T>::value, "plain values only");
    const auto* p = reinterpret_cast<const uint8_t*>(&v);
    bytes.insert(bytes.end(), p, p + sizeof v);
  }
  void put_raw(const void* data, size_t n) {
    const auto* p = static_cast<const uint8_t*>(data);
    bytes.insert(bytes.end(), p, p + n);
  }
  void put_text(const std::string& s) {
    put<uint64_t>(s.size());
    put_raw(s.data(), s.size());
  }
  Bytes bytes;
};

class Reader {
 public:
  explicit Reader(const Bytes& b) : bytes_(b) {}
  template <class T>
  T get() {
    static_assert(std::is_trivially_copyable<T>::value, "plain values only");
    T v;
    std::memcpy(&v, take(sizeof v), sizeof v);
    return v;
  }
  void get_raw(void* out, size_t n) { std::memcpy(out, take(n), n); }
  std::string get_text() {
    const uint64_t n = get<uint64_t>();
    const uint8_t* p = take(size_t(n));
    return std::string(reinterpret_cast<const char*>(p), size_t(n));
  }
  // Count of items of `item_bytes` each that the rest of the message can hold at most.
  uint64_t get_count(size_t item_bytes) {
    const uint64_t n = get<uint64_t>();
    if (item_bytes && n > (bytes_.size() - at_) / item_bytes) fail();
    return n;
  }
  bool done() const { return at_ == bytes_.size(); }

 private:
  const uint8_t* take(size_t n);
  [[noreturn]] void fail() const;
  const Bytes& bytes_;
  size_t at_ = 0;
};

// A scene, field by field (exact: doubles travel as bits).
Bytes encode_scene(const Scene& s);
Scene decode_scene(const Bytes& b);

// Rows [y0, y1) of `img` where they lie in its memory, one piece per buffer
// its contents hold (sent and received without copies: frame_farm.cpp).
std::vector<Span> row_pieces(Image& img, int y0, int y1);
// Bytes a pixel takes in those pieces (and in encode_rows()).
size_t row_pixel_bytes(const FrameContents& contents);

// Rows [y0, y1) of `img`: every buffer its contents hold.
Bytes encode_rows(const Image& img, int y0, int y1);
// Stores them into `img` (the frame's size and contents); returns y0 and y1.
void decode_rows(const Bytes& b, Image& img, int& y0, int& y1);

}  // namespace clrt::dist
