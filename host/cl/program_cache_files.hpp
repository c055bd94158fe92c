// program_cache_files.hpp - what the program cache's own files share (not
// for other callers): the entries' directory, opened once and named
// relative to, and the careful ways a file in it is read.
#pragma once
#include <sys/stat.h>

#include <cstdint>
#include <string>

#include "cl/program_cache.hpp"

namespace clrt::cache_files {

// 64-bit FNV-1a: the key's file name and the entry's checksum.
uint64_t fnv1a(const void* data, size_t n, uint64_t h = 1469598103934665603ULL);

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
  ~EntryDir();
  static ProgramCacheLocation locate(bool create, int* fd_out);
};

// Opens `name` beneath `dirfd` for reading when it is a regular file of this
// user: never through a link, never blocking (a FIFO or device there is
// refused, not waited on). -1 otherwise.
int open_own_file(int dirfd, const std::string& name, struct stat& st);

// Whether anything - a file, a link, a FIFO - has the name (a mark that is
// present in any form counts: the safe answer for ".bad").
bool name_taken(int dirfd, const std::string& name);

// The whole of an open file of st.st_size bytes, at most max_bytes.
bool read_all(int fd, std::string& data, uint64_t max_bytes, const struct stat& st);

}  // namespace clrt::cache_files
