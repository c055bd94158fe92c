// program_cache_guard.cpp - the crash guard around a cached binary's first
// load: a marker with the loading process's pid, and the entry marked bad
// for good when that process died in the driver.
#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <string>

#include "cl/program_cache.hpp"
#include "cl/program_cache_files.hpp"

namespace clrt {
namespace {

using cache_files::EntryDir, cache_files::name_taken, cache_files::open_own_file, cache_files::read_all;

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
  // A marker read just before its process finished normally (it removes the
  // marker, then may exit before the check above) names a process that is
  // gone too: only a marker still there with the same pid is a crash's
  // (found under load: six processes loading one entry, one exiting).
  if (read_marker_pid(dir.fd, marker) != other) return false;
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

}  // namespace clrt
