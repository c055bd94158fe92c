// program_cache.cpp - the program cache's entries: their file format
// (magic, key text, binary, checksum), and loading and storing them.
#include "cl/program_cache.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cstdint>
#include <filesystem>
#include <mutex>

#include "cl/program_cache_files.hpp"
#include "util/log.hpp"
#include "util/output_file.hpp"

namespace clrt {
namespace {

using cache_files::EntryDir, cache_files::fnv1a, cache_files::name_taken, cache_files::open_own_file,
    cache_files::read_all;
namespace fs = std::filesystem;

constexpr char kMagic[8] = {'C', 'L', 'R', 'T', 'B', 'I', 'N', '1'};
constexpr uint64_t kMaxEntryBytes = 1ull << 30;  // larger files are not entries

void put_u64(std::string& out, uint64_t v) {
  for (int i = 0; i < 8; ++i) out += static_cast<char>((v >> (8 * i)) & 0xff);
}

bool get_u64(const std::string& in, size_t& pos, uint64_t& v) {
  if (pos + 8 > in.size()) return false;
  v = 0;
  for (int i = 0; i < 8; ++i) v |= uint64_t(static_cast<unsigned char>(in[pos + i])) << (8 * i);
  pos += 8;
  return true;
}

bool parse_entry(const std::string& data, std::string& key_text, std::vector<unsigned char>& binary) {
  if (data.size() < sizeof kMagic || data.compare(0, sizeof kMagic, kMagic, sizeof kMagic) != 0) return false;
  size_t pos = sizeof kMagic;
  uint64_t klen = 0, blen = 0, sum = 0;
  if (!get_u64(data, pos, klen) || klen > data.size() - pos) return false;
  key_text = data.substr(pos, klen);
  pos += klen;
  if (!get_u64(data, pos, blen) || blen == 0 || blen > data.size() - pos) return false;
  binary.assign(data.begin() + pos, data.begin() + pos + blen);
  pos += blen;
  return get_u64(data, pos, sum) && pos == data.size() && sum == fnv1a(binary.data(), binary.size());
}

bool read_entry_at(int dirfd, const std::string& name, std::string& key_text, std::vector<unsigned char>& binary) {
  struct stat st {};
  const int fd = open_own_file(dirfd, name, st);
  if (fd < 0) return false;
  std::string data;
  const bool ok = read_all(fd, data, kMaxEntryBytes, st);
  ::close(fd);
  return ok && parse_entry(data, key_text, binary);
}

std::string entry_body(const std::string& key_text, const std::vector<unsigned char>& binary) {
  std::string body(kMagic, sizeof kMagic);
  put_u64(body, key_text.size());
  body += key_text;
  put_u64(body, binary.size());
  body.append(reinterpret_cast<const char*>(binary.data()), binary.size());
  put_u64(body, fnv1a(binary.data(), binary.size()));
  return body;
}

// Runs `f(dirfd, name)` on the parent directory of `path` (the path-based
// forms, for tests): the last component is never followed.
template <class F>
bool at_path(const std::string& path, F f) {
  const fs::path p(path);
  const std::string dir = p.parent_path().empty() ? "." : p.parent_path().string();
  const int dirfd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (dirfd < 0) return false;
  const bool ok = f(dirfd, dir, p.filename().string());
  ::close(dirfd);
  return ok;
}

}  // namespace

bool cache_read_entry(const std::string& path, std::string& key_text, std::vector<unsigned char>& binary) {
  return at_path(path, [&](int dirfd, const std::string&, const std::string& name) {
    return read_entry_at(dirfd, name, key_text, binary);
  });
}

bool cache_write_entry(const std::string& path, const std::string& key_text, const std::vector<unsigned char>& binary) {
  return at_path(path, [&](int dirfd, const std::string& dir, const std::string& name) {
    return write_file_at(dirfd, dir, name, entry_body(key_text, binary), 0600, false).empty();
  });
}

std::optional<std::vector<unsigned char>> cache_load(const ProgramCacheKey& key) {
  EntryDir dir(false);
  if (dir.fd < 0) return std::nullopt;
  const std::string name = key.hash() + ".bin";
  std::string text;
  std::vector<unsigned char> bin;
  if (!read_entry_at(dir.fd, name, text, bin)) return std::nullopt;
  if (text != key.text()) return std::nullopt;  // a hash collision or another key
  // Used: the entry becomes the newest, the last the size limit evicts.
  ::utimensat(dir.fd, name.c_str(), nullptr, AT_SYMLINK_NOFOLLOW);
  return bin;
}

bool cache_store(const ProgramCacheKey& key, const std::vector<unsigned char>& binary) {
  static std::once_flag warned;
  if (binary.empty()) return false;
  EntryDir dir(true);
  const std::string name = key.hash() + ".bin";
  std::string why = dir.where.problem;
  if (dir.fd >= 0) {
    if (name_taken(dir.fd, name + ".bad")) return false;  // never again for this key (cache_begin_load)
    const uint64_t limit = program_cache_limit();
    if (binary.size() > limit) return false;  // it would be the first to go
    // No fsync: a torn entry fails its checksum and is rebuilt.
    why = write_file_at(dir.fd, dir.where.path, name, entry_body(key.text(), binary), 0600, false);
    if (why.empty()) {
      cache_evict(dir.where.path, limit);
      return true;
    }
  } else if (why.empty()) {
    why = "cannot create " + dir.where.configured;
  }
  std::call_once(warned, [&] {
    log_message(LogLevel::Warning, "program cache: cannot store in " +
                                       (dir.where.path.empty() ? dir.where.configured : dir.where.path) + ": " + why);
  });
  return false;
}

}  // namespace clrt
