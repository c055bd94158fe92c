// program_cache.cpp - binary cache entries: hashed key, atomic writes, checks.
#include "cl/program_cache.hpp"

#include <fcntl.h>
#include <signal.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "util/log.hpp"

namespace clrt {
namespace {

namespace fs = std::filesystem;

constexpr char kMagic[8] = {'C', 'L', 'R', 'T', 'B', 'I', 'N', '1'};

uint64_t fnv1a(const void* data, size_t n, uint64_t h = 1469598103934665603ULL) {
  const auto* p = static_cast<const unsigned char*>(data);
  for (size_t i = 0; i < n; ++i) {
    h ^= p[i];
    h *= 1099511628211ULL;
  }
  return h;
}

// Length-prefixed fields: no two different keys serialize to the same text.
void field(std::string& out, const char* name, const std::string& v) {
  out += name;
  out += ' ';
  out += std::to_string(v.size());
  out += '\n';
  out += v;
  out += '\n';
}

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
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(fnv1a(t.data(), t.size())));
  return buf;
}

std::string program_cache_dir() {
  if (const char* d = std::getenv("CLRT_CACHE_DIR"); d && *d) return d;
  if (const char* x = std::getenv("XDG_CACHE_HOME"); x && *x) return std::string(x) + "/clrt";
  if (const char* h = std::getenv("HOME"); h && *h) return std::string(h) + "/.cache/clrt";
  return "";
}

std::string cache_entry_path(const ProgramCacheKey& key) {
  std::string dir = program_cache_dir();
  return dir.empty() ? "" : dir + "/" + key.hash() + ".bin";
}

bool cache_read_entry(const std::string& path, std::string& key_text, std::vector<unsigned char>& binary) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return false;
  std::ostringstream ss;
  ss << in.rdbuf();
  const std::string data = ss.str();
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

std::optional<std::vector<unsigned char>> cache_load(const ProgramCacheKey& key) {
  std::string path = cache_entry_path(key), text;
  std::vector<unsigned char> bin;
  if (path.empty() || !cache_read_entry(path, text, bin)) return std::nullopt;
  if (text != key.text()) return std::nullopt;  // a hash collision or another key
  return bin;
}

bool cache_write_entry(const std::string& path, const std::string& key_text, const std::vector<unsigned char>& binary) {
  std::string body(kMagic, sizeof kMagic);
  put_u64(body, key_text.size());
  body += key_text;
  put_u64(body, binary.size());
  body.append(reinterpret_cast<const char*>(binary.data()), binary.size());
  put_u64(body, fnv1a(binary.data(), binary.size()));
  // Unique temporary name in the same directory, then an atomic rename.
  static std::atomic<unsigned> serial{0};
  std::string tmp = path + ".tmp." + std::to_string(::getpid()) + "." + std::to_string(serial++);
  bool ok = false;
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (out) {
      out.write(body.data(), static_cast<std::streamsize>(body.size()));
      out.close();
      ok = static_cast<bool>(out);
    }
  }
  std::error_code ec;
  if (ok) {
    fs::rename(tmp, path, ec);
    ok = !ec;
  }
  if (!ok) fs::remove(tmp, ec);
  return ok;
}

bool cache_store(const ProgramCacheKey& key, const std::vector<unsigned char>& binary) {
  static bool warned = false;
  std::string path = cache_entry_path(key);
  if (path.empty() || binary.empty()) return false;
  std::error_code ec;
  fs::create_directories(program_cache_dir(), ec);
  if (fs::exists(path + ".bad", ec)) return false;  // never again for this key (cache_begin_load)
  if (cache_write_entry(path, key.text(), binary)) return true;
  if (!warned) log_message(LogLevel::Warning, "cannot write the program cache entry " + path);
  warned = true;
  return false;
}

namespace {

bool process_alive(long pid) {
  if (pid <= 0) return false;
  return ::kill(pid_t(pid), 0) == 0 || errno == EPERM;
}

}  // namespace

bool cache_begin_load(const ProgramCacheKey& key, std::string* note) {
  const std::string path = cache_entry_path(key);
  if (path.empty()) return false;
  std::error_code ec;
  if (fs::exists(path + ".bad", ec)) return false;
  const std::string marker = path + ".loading";
  int fd = ::open(marker.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC | O_NOFOLLOW, 0644);
  if (fd >= 0) {
    const std::string pid = std::to_string(::getpid()) + "\n";
    const bool written = ::write(fd, pid.data(), pid.size()) == ssize_t(pid.size());
    ::close(fd);
    if (!written) ::unlink(marker.c_str());
    return written;
  }
  if (errno != EEXIST) return false;  // cannot mark: do not load unguarded
  long other = 0;
  {
    std::ifstream in(marker);
    in >> other;
  }
  if (process_alive(other)) return false;  // being loaded right now: build from source
  // The process that loaded this entry last did not finish: it crashed in
  // the driver. Never load this entry again.
  fs::remove(path, ec);
  std::ofstream(path + ".bad") << "a load of this entry crashed process " << other << "\n";
  fs::remove(marker, ec);
  if (note)
    *note = "discarded the cached binary " + path + ": loading it crashed an earlier run (pid " +
            std::to_string(other) + ")";
  return false;
}

void cache_end_load(const ProgramCacheKey& key, bool ok) {
  const std::string path = cache_entry_path(key);
  if (path.empty()) return;
  std::error_code ec;
  if (!ok) fs::remove(path, ec);
  fs::remove(path + ".loading", ec);
}

}  // namespace clrt
