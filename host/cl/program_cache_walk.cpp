// program_cache_walk.cpp - the program cache's directory as a whole: what
// it holds (clrt cache info), the oldest entries evicted over the size
// limit, and clrt cache clear. Only files named like entries (or their bad
// marks) are ever deleted.
#include <dirent.h>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

#include "cl/program_cache.hpp"

namespace clrt {

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
