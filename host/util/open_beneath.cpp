// open_beneath.cpp - a path walked beneath a directory, one component at a
// time, never through a link (open_beneath.hpp).
#include "util/open_beneath.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <vector>

namespace clrt {

int open_beneath(int root_fd, const std::string& relative, std::string& why) {
  std::vector<std::string> parts;
  for (size_t b = 0; b <= relative.size();) {
    size_t e = relative.find('/', b);
    if (e == std::string::npos) e = relative.size();
    const std::string part = relative.substr(b, e - b);
    if (part == "..") {
      why = "leaves the scene's folder (\"..\")";
      return -1;
    }
    if (!part.empty() && part != ".") parts.push_back(part);
    b = e + 1;
  }
  if (parts.empty() || relative[0] == '/') {
    why = "is not a file name beneath the scene's folder";
    return -1;
  }
  int dir = ::dup(root_fd);
  if (dir < 0) {
    why = std::strerror(errno);
    return -1;
  }
  std::string walked;
  for (size_t i = 0; i < parts.size(); ++i) {
    const bool last = i + 1 == parts.size();
    const int flags = O_RDONLY | O_NOFOLLOW | O_CLOEXEC | O_NOCTTY | (last ? O_NONBLOCK : O_DIRECTORY);
    const int next = ::openat(dir, parts[i].c_str(), flags);
    int e = errno;
    struct stat st {};
    // O_DIRECTORY|O_NOFOLLOW on a link fails with ENOTDIR, as on a file.
    if (next < 0 && e == ENOTDIR && ::fstatat(dir, parts[i].c_str(), &st, AT_SYMLINK_NOFOLLOW) == 0 &&
        S_ISLNK(st.st_mode))
      e = ELOOP;
    ::close(dir);
    walked += (walked.empty() ? "" : "/") + parts[i];
    if (next < 0) {
      // ELOOP: the component is a link (O_NOFOLLOW); ENOTDIR: a component
      // before the last is not a folder.
      const std::string at = last ? "" : " (\"" + walked + "\")";
      if (e == ELOOP)
        why = (last ? std::string("is a symbolic link") : "passes through a symbolic link" + at) +
              ": a scene's files must lie in its folder or below it, and links are not followed";
      else if (e == ENOTDIR && !last)
        why = "passes through something that is not a folder" + at;
      else
        why = std::strerror(e) + at;
      return -1;
    }
    dir = next;
  }
  return dir;
}

}  // namespace clrt
