// program_cache_dir.cpp - where the program cache's entries live: the
// configured directory, or its private subdirectory, opened once; and the
// careful reads of the files in it.
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>

#include "cl/program_cache.hpp"
#include "cl/program_cache_files.hpp"

namespace clrt {

std::string program_cache_dir() {
  if (const char* d = std::getenv("CLRT_CACHE_DIR"); d && *d) return d;
  if (const char* x = std::getenv("XDG_CACHE_HOME"); x && *x) return std::string(x) + "/clrt";
  if (const char* h = std::getenv("HOME"); h && *h) return std::string(h) + "/.cache/clrt";
  return "";
}

namespace cache_files {

namespace fs = std::filesystem;

namespace {

bool owned_private(const struct stat& st, mode_t forbidden) {
  return S_ISDIR(st.st_mode) && st.st_uid == ::geteuid() && (st.st_mode & forbidden) == 0;
}

}  // namespace

EntryDir::~EntryDir() {
  if (fd >= 0) ::close(fd);
}

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

int open_own_file(int dirfd, const std::string& name, struct stat& st) {
  const int fd = ::openat(dirfd, name.c_str(), O_RDONLY | O_NOFOLLOW | O_CLOEXEC | O_NONBLOCK | O_NOCTTY);
  if (fd < 0) return -1;
  if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode) || st.st_uid != ::geteuid()) {
    ::close(fd);
    return -1;
  }
  return fd;
}

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

}  // namespace cache_files

ProgramCacheLocation program_cache_location() {
  int fd = -1;
  ProgramCacheLocation loc = cache_files::EntryDir::locate(false, &fd);
  if (fd >= 0) ::close(fd);
  return loc;
}

std::string cache_entry_path(const ProgramCacheKey& key) {
  const ProgramCacheLocation loc = program_cache_location();
  return loc.path.empty() ? "" : loc.path + "/" + key.hash() + ".bin";
}

}  // namespace clrt
