// scene_json.cpp - reading scene files: the strict streaming reader
// (scene_builder.hpp) over text, streams and files, with -D overrides; and
// `clrt validate`'s reading, which reports every problem.
#include "scene/scene_json.hpp"

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <istream>
#include <memory>
#include <optional>

#include "scene/scene_builder.hpp"
#include "util/bytes_text.hpp"
#include "util/doing.hpp"
#include "util/error.hpp"

namespace clrt {
namespace {

[[noreturn]] void too_large(const std::string& name, size_t max_bytes) {
  throw UserError(name + ": scene file is larger than " + bytes_text(max_bytes));
}

// A stream's bytes in chunks, for the parser: a NUL byte (not JSON; nlohmann
// would take it for the end of the text) or more than max_bytes throw
// UserError as soon as they are read, so that /dev/zero or a huge file
// cannot exhaust memory or time.
class LimitedReader final : public std::streambuf {
 public:
  LimitedReader(std::istream& in, const std::string& name, size_t max_bytes)
      : in_(in), name_(name), max_bytes_(max_bytes), buffer_(new char[kChunk]) {}

 protected:
  int_type underflow() override {
    if (gptr() < egptr()) return traits_type::to_int_type(*gptr());
    in_.read(buffer_.get(), kChunk);
    const auto n = static_cast<size_t>(in_.gcount());
    if (in_.bad()) throw UserError(name_ + ": cannot read scene file");
    if (n == 0) return traits_type::eof();
    if (const void* nul = std::memchr(buffer_.get(), 0, n))
      throw UserError(name_ + ": malformed JSON: NUL byte at offset " +
                      std::to_string(read_ + size_t(static_cast<const char*>(nul) - buffer_.get())));
    read_ += n;
    if (read_ > max_bytes_) too_large(name_, max_bytes_);
    setg(buffer_.get(), buffer_.get(), buffer_.get() + n);
    return traits_type::to_int_type(*gptr());
  }

 private:
  static constexpr size_t kChunk = size_t(1) << 16;
  std::istream& in_;
  const std::string& name_;
  const size_t max_bytes_;
  size_t read_ = 0;
  std::unique_ptr<char[]> buffer_;
};

// The reader over a stream: the scene, or (collect) every problem.
Scene read_stream(std::istream& in, const std::string& name, const SceneLimits& limits,
                  const std::optional<std::filesystem::path>& folder, const SceneOverrides& overrides,
                  const ProblemSink* collect) {
  LimitedReader reader(in, name, limits.bytes);
  std::istream stream(&reader);
  SceneBuilder builder(name, limits, folder, overrides, collect);
  if (!nlohmann::json::sax_parse(stream, &builder) && !builder.stopped())
    throw UserError(name + ": malformed JSON");  // not reached: errors throw
  return builder.finish();
}

// A scene file open for reading, and the folder its meshes are read from.
struct SceneFile {
  std::ifstream in;
  std::optional<std::filesystem::path> folder;
};

SceneFile open_scene(const std::string& path, const SceneLimits& limits) {
  std::error_code ec;
  const std::filesystem::file_status status = std::filesystem::status(path, ec);
  if (std::filesystem::is_directory(status)) throw UserError(path + ": cannot open scene file: is a directory");
  SceneFile file{std::ifstream(path, std::ios::binary), std::nullopt};
  if (!file.in) throw UserError(path + ": cannot open scene file: " + std::strerror(errno));
  // A regular file over the limit fails before it is read; anything else (a
  // FIFO, /dev/zero) is counted as it is read.
  if (std::filesystem::is_regular_file(status)) {
    const auto bytes = std::filesystem::file_size(path, ec);
    if (!ec && bytes > limits.bytes) too_large(path, limits.bytes);
  }
  // Mesh files are read from the scene file's folder; a scene that is not a
  // regular file (a pipe, /dev/stdin) has none: under /dev or /proc anyone
  // could have planted a file by the name it gives.
  if (std::filesystem::is_regular_file(status)) {
    const std::filesystem::path folder = std::filesystem::path(path).parent_path();
    file.folder = folder.empty() ? std::filesystem::path(".") : folder;
  }
  return file;
}

}  // namespace

Scene parse_scene(const std::string& text, const std::string& name, const SceneLimits& limits,
                  const SceneOverrides& overrides) {
  if (text.size() > limits.bytes) too_large(name, limits.bytes);
  // A NUL byte is not JSON; nothing after one may be silently dropped.
  if (const void* nul = std::memchr(text.data(), 0, text.size()))
    throw UserError(name + ": malformed JSON: NUL byte at offset " +
                    std::to_string(static_cast<const char*>(nul) - text.data()));
  SceneBuilder builder(name, limits, std::nullopt, overrides, nullptr);
  if (!nlohmann::json::sax_parse(text, &builder))
    throw UserError(name + ": malformed JSON");  // not reached: errors throw
  return builder.finish();
}

Scene parse_scene(std::istream& in, const std::string& name, const SceneLimits& limits,
                  const SceneOverrides& overrides) {
  return read_stream(in, name, limits, std::nullopt, overrides, nullptr);
}

Scene load_scene(const std::string& path, const SceneLimits& limits, const SceneOverrides& overrides) {
  const Doing doing("loading the scene " + path);
  SceneFile file = open_scene(path, limits);
  return read_stream(file.in, path, limits, file.folder, overrides, nullptr);
}

size_t validate_scene(const std::string& path, const std::function<void(const std::string&)>& problem,
                      const SceneLimits& limits, const SceneOverrides& overrides) {
  const Doing doing("checking the scene " + path);
  size_t count = 0;
  const ProblemSink sink = [&](const std::string& message) {
    ++count;
    problem(message);
  };
  try {
    SceneFile file = open_scene(path, limits);
    (void)read_stream(file.in, path, limits, file.folder, overrides, &sink);
  } catch (const UserError& e) {  // a file that cannot be read on (too large, a NUL byte, a read error)
    sink(e.what());
  }
  return count;
}

}  // namespace clrt
