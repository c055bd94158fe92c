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
#include <cstring>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <sstream>

#include "util/error.hpp"
#include "util/log.hpp"
#include "util/output_file.hpp"

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

namespace {

bool owned_private(const struct stat& st, mode_t forbidden) {
  return S_ISDIR(st.st_mode) && st.st_uid == ::geteuid() && (st.st_mode & forbidden) == 0;
}

// The open directory the entries live in (program_cache.hpp, "Directory"):
// the configured one when it is this user's and nobody else may write it,
// else its private subdirectory. Every file below is named relative to fd,
// so nothing is looked up again through a path someone could change.
struct EntryDir {
  int fd = -1;
  ProgramCacheLocation where;
  EntryDir(const EntryDir&) = delete;
  EntryDir& operator=(const EntryDir&) = delete;
  explicit EntryDir(bool create) : where(locate(create, &fd)) {}
  ~EntryDir() {
    if (fd >= 0) ::close(fd);
  }
  static ProgramCacheLocation locate(bool create, int* fd_out);
};

ProgramCacheLocation EntryDir::locate(bool create, int* fd_out) {
  ProgramCacheLocation loc;
  loc.configured = program_cache_dir();
  if (loc.configured.empty()) {
    loc.problem = "no program cache directory: set CLRT_CACHE_DIR, XDG_CACHE_HOME or HOME";
    return loc;
  }
  std::error_code ec;
  if (create) {
    const fs::path parent = fs::path(loc.configured).parent_path();
    if (!parent.empty()) fs::create_directories(parent, ec);
    ::mkdir(loc.configured.c_str(), 0700);
  }
  const int top = ::open(loc.configured.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (top < 0) {
    const int e = errno;
    if (e == ENOENT || e == ENOTDIR) {
      // Not there: created by the first store - unless something in the way
      // makes that impossible (HOME a regular file, a parent not a folder).
      struct stat st {};
      fs::path p = fs::path(loc.configured).parent_path();
      while (!p.empty() && ::stat(p.c_str(), &st) != 0 && p != p.parent_path()) p = p.parent_path();
      if (!p.empty() && ::stat(p.c_str(), &st) == 0 && !S_ISDIR(st.st_mode))
        loc.problem = "cannot be created: " + p.string() + " is not a directory";
      else if (e == ENOTDIR)
        loc.problem = "cannot be created: it is not a directory";
      else
        loc.missing = true, loc.path = loc.configured;
    } else {
      loc.problem = std::strerror(e);
    }
    return loc;
  }
  struct stat st {};
  if (::fstat(top, &st) == 0 && owned_private(st, S_IWGRP | S_IWOTH)) {
    loc.path = loc.configured;
    *fd_out = top;
    return loc;
  }
  // A directory others can write (a shared CLRT_CACHE_DIR, /tmp) or another
  // user's: anyone there could plant links or FIFOs at the entries' names,
  // so the entries go to a subdirectory only this user can use.
  const std::string name = "clrt-" + std::to_string(::geteuid());
  loc.shared = true;
  loc.path = loc.configured + "/" + name;
  if (create) ::mkdirat(top, name.c_str(), 0700);
  const int sub = ::openat(top, name.c_str(), O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
  const int e = errno;
  ::close(top);
  if (sub < 0) {
    loc.missing = e == ENOENT;
    if (!loc.missing) loc.problem = std::string("it is not a directory of this user (") + std::strerror(e) + ")";
    return loc;
  }
  if (::fstat(sub, &st) != 0 || !owned_private(st, S_IRWXG | S_IRWXO)) {
    ::close(sub);
    loc.problem = "it belongs to another user, or others may use it";
    return loc;
  }
  *fd_out = sub;
  return loc;
}

// Opens `name` beneath `dirfd` for reading when it is a regular file of this
// user: never through a link, never blocking (a FIFO or device there is
// refused, not waited on). -1 otherwise.
int open_own_file(int dirfd, const std::string& name, struct stat& st) {
  const int fd = ::openat(dirfd, name.c_str(), O_RDONLY | O_NOFOLLOW | O_CLOEXEC | O_NONBLOCK | O_NOCTTY);
  if (fd < 0) return -1;
  if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode) || st.st_uid != ::geteuid()) {
    ::close(fd);
    return -1;
  }
  return fd;
}

// Whether anything - a file, a link, a FIFO - has the name (a mark that is
// present in any form counts: the safe answer for ".bad").
bool name_taken(int dirfd, const std::string& name) {
  struct stat st {};
  return ::fstatat(dirfd, name.c_str(), &st, AT_SYMLINK_NOFOLLOW) == 0;
}

bool read_all(int fd, std::string& data, uint64_t max_bytes, const struct stat& st) {
  if (uint64_t(st.st_size) > max_bytes) return false;
  data.resize(size_t(st.st_size));
  size_t got = 0;
  while (got < data.size()) {
    const ssize_t n = ::read(fd, &data[got], data.size() - got);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;
    got += size_t(n);
  }
  return got == data.size();
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

ProgramCacheLocation program_cache_location() {
  int fd = -1;
  ProgramCacheLocation loc = EntryDir::locate(false, &fd);
  if (fd >= 0) ::close(fd);
  return loc;
}

std::string cache_entry_path(const ProgramCacheKey& key) {
  const ProgramCacheLocation loc = program_cache_location();
  return loc.path.empty() ? "" : loc.path + "/" + key.hash() + ".bin";
}

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

namespace {

bool process_alive(long pid) {
  if (pid <= 0) return false;
  return ::kill(pid_t(pid), 0) == 0 || errno == EPERM;
}

// The pid in a load marker; 0 when it is not a small regular file of this
// user holding one.
long read_marker_pid(int dirfd, const std::string& name) {
  struct stat st {};
  const int fd = open_own_file(dirfd, name, st);
  if (fd < 0) return 0;
  std::string text;
  const bool ok = read_all(fd, text, 64, st);
  ::close(fd);
  if (!ok) return 0;
  char* end = nullptr;
  const long pid = std::strtol(text.c_str(), &end, 10);
  return end != text.c_str() && pid > 0 ? pid : 0;
}

}  // namespace

bool cache_begin_load(const ProgramCacheKey& key, std::string* note) {
  EntryDir dir(false);
  if (dir.fd < 0) return false;
  const std::string entry = key.hash() + ".bin";
  if (name_taken(dir.fd, entry + ".bad")) return false;
  const std::string marker = entry + ".loading";
  // The marker appears with its pid already in it (written to a private
  // name, then linked: link() fails with EEXIST like O_EXCL), so a process
  // that finds it never reads it empty - ranks of an MPI job on one machine
  // load the same entry at the same moment.
  const std::string pid = std::to_string(::getpid()) + "\n";
  const std::string own = marker + "." + std::to_string(::getpid());
  const int flags = O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC | O_NOFOLLOW;
  int fd = ::openat(dir.fd, own.c_str(), flags, 0600);
  if (fd < 0 && errno == EEXIST) {  // left by a killed process whose pid this one reuses
    ::unlinkat(dir.fd, own.c_str(), 0);
    fd = ::openat(dir.fd, own.c_str(), flags, 0600);
  }
  if (fd < 0) return false;  // cannot mark: do not load unguarded
  const bool written = ::write(fd, pid.data(), pid.size()) == ssize_t(pid.size());
  ::close(fd);
  const int linked = written ? ::linkat(dir.fd, own.c_str(), dir.fd, marker.c_str(), 0) : -1;
  const int link_errno = errno;
  ::unlinkat(dir.fd, own.c_str(), 0);
  if (linked == 0) return true;
  if (!written || link_errno != EEXIST) return false;
  const long other = read_marker_pid(dir.fd, marker);
  if (other <= 0) return false;            // not a marker this user wrote: build from source
  if (process_alive(other)) return false;  // being loaded right now: build from source
  // The process that loaded this entry last did not finish: it crashed in
  // the driver. Never load this entry again (the mark is created, never
  // opened through whatever may have its name).
  ::unlinkat(dir.fd, entry.c_str(), 0);
  const std::string why = "a load of this entry crashed process " + std::to_string(other) + "\n";
  const int bad = ::openat(dir.fd, (entry + ".bad").c_str(), flags, 0600);
  if (bad >= 0) {
    const ssize_t ignored = ::write(bad, why.data(), why.size());
    (void)ignored;
    ::close(bad);
  }
  ::unlinkat(dir.fd, marker.c_str(), 0);
  if (note)
    *note = "discarded the cached binary " + dir.where.path + "/" + entry +
            ": loading it crashed an earlier run (pid " + std::to_string(other) + ")";
  return false;
}

void cache_end_load(const ProgramCacheKey& key, bool ok) {
  EntryDir dir(false);
  if (dir.fd < 0) return;
  const std::string entry = key.hash() + ".bin";
  if (!ok) ::unlinkat(dir.fd, entry.c_str(), 0);
  ::unlinkat(dir.fd, (entry + ".loading").c_str(), 0);
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
