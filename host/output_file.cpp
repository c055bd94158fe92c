// output_file.cpp - checked, atomic output files.
#include "output_file.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <fstream>

#include "error.hpp"

namespace clrt {
namespace fs = std::filesystem;

namespace {
fs::path directory_of(const fs::path& target) {
  return target.parent_path().empty() ? fs::path(".") : target.parent_path();
}
}  // namespace

fs::path temp_path_for(const fs::path& target) {
  return directory_of(target) /
         ("." + target.stem().string() + ".tmp" + std::to_string(::getpid()) + target.extension().string());
}

void check_writable(const std::string& path, const std::string& what) {
  if (path.empty()) throw UserError(what + " path is empty");
  const fs::path target(path);
  const fs::path dir = directory_of(target);
  std::error_code ec;
  if (!fs::is_directory(dir, ec))
    throw UserError(path + ": cannot write " + what + ": directory " + dir.string() + " does not exist");
  if (fs::is_directory(target, ec)) throw UserError(path + ": cannot write " + what + ": it is a directory");
  // Permission bits say nothing for root (or on read-only mounts and /proc):
  // create and remove the temp file itself to learn whether it can be written.
  const fs::path probe = temp_path_for(target);
  int fd = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
  if (fd < 0 && errno == EEXIST) return;  // a stale temp file of ours; the writer overwrites it
  if (fd < 0)
    throw UserError(path + ": cannot write " + what + ": cannot create a file in " + dir.string() + ": " +
                    std::strerror(errno));
  ::close(fd);
  fs::remove(probe, ec);
}

void commit_temp(const fs::path& tmp, const std::string& target, const std::string& what) {
  std::error_code ec;
  fs::rename(tmp, target, ec);
  if (ec) {
    const std::string why = ec.message();
    fs::remove(tmp, ec);
    throw UserError(target + ": cannot write " + what + ": rename failed: " + why);
  }
}

void write_text_atomic(const std::string& path, const std::string& text, const std::string& what) {
  check_writable(path, what);
  const fs::path tmp = temp_path_for(path);
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    out << text;
    out.flush();
    if (!out) {
      std::error_code ec;
      fs::remove(tmp, ec);
      throw UserError(path + ": cannot write " + what);
    }
  }
  commit_temp(tmp, path, what);
}

}  // namespace clrt
