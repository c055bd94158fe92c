// program_cache.cpp - binary cache entries: hashed key, atomic writes, checks.
#include "cl/program_cache.hpp"

#include <dirent.h>
#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cctype>
#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <sstream>

#include "util/error.hpp"
#include "util/log.hpp"

namespace clrt {
namespace {

namespace fs = std::filesystem;

constexpr char kMagic[8] = {'C', 'L', 'R', 'T', 'B', 'I', 'N', '1'};
constexpr uint64_t kMaxEntryBytes = 1ull << 30;  // larger files are not entries

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
  // A regular file, never through a symbolic link (a FIFO or device named
  // like an entry would block or never end).
  const int fd = ::open(path.c_str(), O_RDONLY | O_NOFOLLOW | O_CLOEXEC | O_NONBLOCK);
  if (fd < 0) return false;
  struct stat st {};
  std::string data;
  bool ok = ::fstat(fd, &st) == 0 && S_ISREG(st.st_mode) && uint64_t(st.st_size) <= kMaxEntryBytes;
  if (ok) {
    data.resize(size_t(st.st_size));
    size_t got = 0;
    while (got < data.size()) {
      const ssize_t n = ::read(fd, &data[got], data.size() - got);
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) break;
      got += size_t(n);
    }
    ok = got == data.size();
  }
  ::close(fd);
  if (!ok) return false;
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
  // Used: the entry becomes the newest, the last the size limit evicts.
  ::utimensat(AT_FDCWD, path.c_str(), nullptr, AT_SYMLINK_NOFOLLOW);
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
  const uint64_t limit = program_cache_limit();
  if (binary.size() > limit) return false;  // it would be the first to go
  if (cache_write_entry(path, key.text(), binary)) {
    cache_evict(program_cache_dir(), limit);
    return true;
  }
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
  // The marker appears with its pid already in it (written to a private
  // name, then linked: link() fails with EEXIST like O_EXCL), so a process
  // that finds it never reads it empty - ranks of an MPI job on one machine
  // load the same entry at the same moment.
  const std::string pid = std::to_string(::getpid()) + "\n";
  const std::string own = marker + "." + std::to_string(::getpid());
  const int flags = O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC | O_NOFOLLOW;
  int fd = ::open(own.c_str(), flags, 0644);
  if (fd < 0 && errno == EEXIST) {  // left by a killed process whose pid this one reuses
    ::unlink(own.c_str());
    fd = ::open(own.c_str(), flags, 0644);
  }
  if (fd < 0) return false;  // cannot mark: do not load unguarded
  const bool written = ::write(fd, pid.data(), pid.size()) == ssize_t(pid.size());
  ::close(fd);
  const int linked = written ? ::link(own.c_str(), marker.c_str()) : -1;
  const int link_errno = errno;
  ::unlink(own.c_str());
  if (linked == 0) return true;
  if (!written || link_errno != EEXIST) return false;
  long other = 0;
  {
    std::ifstream in(marker);
    in >> other;
  }
  if (other <= 0) return false;            // unreadable (a marker of an older clrt being written): build from source
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

// ---- size limit, info, clear ----------------------------------------------

std::optional<uint64_t> parse_cache_size(const std::string& text) {
  size_t i = 0;
  uint64_t n = 0;
  if (text.empty() || !std::isdigit(static_cast<unsigned char>(text[0]))) return std::nullopt;
  for (; i < text.size() && std::isdigit(static_cast<unsigned char>(text[i])); ++i) {
    if (n > (UINT64_MAX - 9) / 10) return std::nullopt;
    n = n * 10 + uint64_t(text[i] - '0');
  }
  std::string unit;
  for (; i < text.size(); ++i) unit += char(std::tolower(static_cast<unsigned char>(text[i])));
  int shift = 0;
  if (unit.empty() || unit == "b")
    shift = 0;
  else if (unit == "k" || unit == "kb" || unit == "kib")
    shift = 10;
  else if (unit == "m" || unit == "mb" || unit == "mib")
    shift = 20;
  else if (unit == "g" || unit == "gb" || unit == "gib")
    shift = 30;
  else
    return std::nullopt;
  if (n > (UINT64_MAX >> shift)) return std::nullopt;
  return n << shift;
}

uint64_t program_cache_limit(bool strict) {
  const char* env = std::getenv("CLRT_CACHE_MAX_SIZE");
  if (!env || !*env) return kDefaultProgramCacheLimit;
  if (auto n = parse_cache_size(env)) return *n;
  std::string value(env);
  const std::string message =
      "CLRT_CACHE_MAX_SIZE: expected a size in bytes, or with K, M or G (got \"" + value.substr(0, 64) + "\")";
  if (strict) throw UserError(message);
  static std::once_flag warned;
  std::call_once(warned, [&] { log_message(LogLevel::Warning, message + "; using 256M"); });
  return kDefaultProgramCacheLimit;
}

bool is_cache_entry_name(const std::string& name) {
  if (name.size() != 20 || name.compare(16, 4, ".bin") != 0) return false;
  return std::all_of(name.begin(), name.begin() + 16,
                     [](char c) { return (c >= '0' && c <= '9') || (c >= 'a' && c <= 'f'); });
}

namespace {

bool is_bad_marker_name(const std::string& name) {
  return name.size() == 24 && name.compare(20, 4, ".bad") == 0 && is_cache_entry_name(name.substr(0, 20));
}

struct DirFile {
  std::string name;
  bool entry = false, bad_marker = false;  // a regular file with that name
  uint64_t size = 0;
  struct timespec mtime {};
};

// The directory, opened once: every later step names files relative to it
// (fstatat, unlinkat), so a directory renamed or replaced meanwhile is not
// walked into, and no call follows a link inside it.
class CacheDir {
 public:
  explicit CacheDir(const std::string& path) {
    if (path.empty()) return;
    fd_ = ::open(path.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  }
  ~CacheDir() {
    if (fd_ >= 0) ::close(fd_);
  }
  CacheDir(const CacheDir&) = delete;
  CacheDir& operator=(const CacheDir&) = delete;
  bool open() const { return fd_ >= 0; }

  std::vector<DirFile> files() const {
    std::vector<DirFile> out;
    if (fd_ < 0) return out;
    const int walk = ::dup(fd_);  // closedir closes it
    if (walk < 0) return out;
    DIR* d = ::fdopendir(walk);
    if (!d) {
      ::close(walk);
      return out;
    }
    ::rewinddir(d);
    while (const dirent* e = ::readdir(d)) {
      DirFile f;
      f.name = e->d_name;
      if (f.name == "." || f.name == "..") continue;
      struct stat st {};
      if (::fstatat(fd_, e->d_name, &st, AT_SYMLINK_NOFOLLOW) == 0 && S_ISREG(st.st_mode)) {
        f.entry = is_cache_entry_name(f.name);
        f.bad_marker = is_bad_marker_name(f.name);
        f.size = uint64_t(st.st_size);
        f.mtime = st.st_mtim;
      }
      out.push_back(std::move(f));
    }
    ::closedir(d);
    return out;
  }

  // unlinkat never follows a link: at worst it removes a link that took an
  // entry's name meanwhile, itself in the cache's namespace.
  bool remove(const std::string& name) const { return ::unlinkat(fd_, name.c_str(), 0) == 0; }

 private:
  int fd_ = -1;
};

}  // namespace

ProgramCacheStats cache_stats(const std::string& dir) {
  ProgramCacheStats s;
  CacheDir d(dir);
  s.exists = d.open();
  for (const auto& f : d.files()) {
    if (f.entry) {
      ++s.entries;
      s.bytes += f.size;
    } else if (f.bad_marker) {
      ++s.bad_markers;
    } else {
      ++s.other;
    }
  }
  return s;
}

size_t cache_evict(const std::string& dir, uint64_t limit) {
  CacheDir d(dir);
  if (!d.open()) return 0;
  std::vector<DirFile> entries;
  uint64_t total = 0;
  for (auto& f : d.files())
    if (f.entry) total += f.size, entries.push_back(std::move(f));
  if (total <= limit) return 0;
  // Oldest first; the name breaks ties, so concurrent evictions agree.
  std::sort(entries.begin(), entries.end(), [](const DirFile& a, const DirFile& b) {
    if (a.mtime.tv_sec != b.mtime.tv_sec) return a.mtime.tv_sec < b.mtime.tv_sec;
    if (a.mtime.tv_nsec != b.mtime.tv_nsec) return a.mtime.tv_nsec < b.mtime.tv_nsec;
    return a.name < b.name;
  });
  size_t removed = 0;
  for (const auto& e : entries) {
    if (total <= limit) break;
    if (d.remove(e.name)) ++removed;
    total -= e.size;  // (gone either way: another process may have removed it)
  }
  return removed;
}

ProgramCacheCleared cache_clear(const std::string& dir) {
  ProgramCacheCleared c;
  CacheDir d(dir);
  for (const auto& f : d.files()) {
    if (f.entry && d.remove(f.name)) {
      ++c.entries;
      c.bytes += f.size;
    } else if (f.bad_marker && d.remove(f.name)) {
      ++c.bad_markers;
    }
  }
  return c;
}

}  // namespace clrt
