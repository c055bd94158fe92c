// output_file.cpp - checked, atomic, symlink-safe output.
#include "util/output_file.hpp"

#include <fcntl.h>
#include <sys/random.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <filesystem>

#include "util/error.hpp"

namespace clrt {
namespace fs = std::filesystem;

namespace {

// ---- what a signal must remove ---------------------------------------------
// Fixed buffers, so the handler touches no allocator: the temp file being
// written (slot 0) and a private scratch directory with its one file
// (slots 1 and 2, see ScratchFile).
constexpr int kSlots = 3;
char g_paths[kSlots][4096];
std::atomic<bool> g_set[kSlots];

void register_path(int slot, const std::string& p) {
  if (p.size() >= sizeof g_paths[slot]) return;  // longer than PATH_MAX: open() refused it already
  std::memcpy(g_paths[slot], p.c_str(), p.size() + 1);
  g_set[slot].store(true);
}
void unregister_path(int slot) {
  g_set[slot].store(false);
}
void register_temp(const std::string& p) {
  register_path(0, p);
}
void unregister_temp() {
  unregister_path(0);
}

// set_signal_report(): whether this process prints the line, and what it adds.
std::atomic<bool> g_signal_prints{true};
char g_signal_note[256] = "";

void on_signal(int sig) {
  if (g_set[0].load()) ::unlink(g_paths[0]);
  if (g_set[2].load()) ::unlink(g_paths[2]);
  if (g_set[1].load()) ::rmdir(g_paths[1]);
  if (!g_signal_prints.load()) ::_exit(128 + sig);
  const char* name = sig == SIGINT ? "SIGINT" : sig == SIGTERM ? "SIGTERM" : sig == SIGHUP ? "SIGHUP" : "SIGPIPE";
  char line[384] = "clrt: error: interrupted by ";
  std::strcat(line, name);
  std::strcat(line, g_signal_note);
  std::strcat(line, "\n");
  ssize_t ignored = ::write(STDERR_FILENO, line, std::strlen(line));
  (void)ignored;
  ::_exit(128 + sig);
}

fs::path directory_of(const fs::path& target) {
  return target.parent_path().empty() ? fs::path(".") : target.parent_path();
}

[[noreturn]] void fail(const std::string& path, const std::string& what, const std::string& why) {
  throw UserError(path + ": cannot write " + what + ": " + why);
}

std::string errno_text(int e) {
  return std::strerror(e);
}

// Creates an empty temp file exclusively in `dir` (random name; O_EXCL so an
// existing name - a planted symlink - makes it fail and retry, never follow).
int create_temp(const fs::path& dir, std::string& name_out) {
  std::string tmpl = (dir / ".clrt-XXXXXX").string();
  int fd = ::mkostemp(&tmpl[0], O_CLOEXEC);
  if (fd >= 0) name_out = tmpl;
  return fd;
}

mode_t current_umask() {
  mode_t m = ::umask(022);
  ::umask(m);
  return m;
}

bool write_all(int fd, const std::string& bytes, int& err) {
  size_t done = 0;
  while (done < bytes.size()) {
    ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      err = n < 0 ? errno : EIO;
      return false;
    }
    done += size_t(n);
  }
  return true;
}

std::string random_suffix() {
  unsigned char bytes[8] = {};
  if (::getrandom(bytes, sizeof bytes, 0) != ssize_t(sizeof bytes)) {
    // No entropy source: the time and pid still make a name unlikely to be
    // planted, and O_EXCL makes a planted one fail, never be followed.
    static std::atomic<unsigned> serial{0};
    const uint64_t v = uint64_t(::getpid()) << 32 ^ uint64_t(std::time(nullptr)) ^ serial++;
    std::memcpy(bytes, &v, sizeof bytes);
  }
  static const char hex[] = "0123456789abcdef";
  std::string out;
  for (unsigned char b : bytes) out += hex[b >> 4], out += hex[b & 15];
  return out;
}

}  // namespace

std::string write_file_at(int dirfd, const std::string& dir_path, const std::string& name, const std::string& bytes,
                          unsigned mode, bool sync) {
  std::string tmp;
  int fd = -1;
  for (int attempt = 0; attempt < 16 && fd < 0; ++attempt) {
    tmp = ".clrt-" + random_suffix();
    fd = ::openat(dirfd, tmp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0600);
    if (fd < 0 && errno != EEXIST) return "cannot create a file in " + dir_path + ": " + errno_text(errno);
  }
  if (fd < 0) return "cannot create a file in " + dir_path + ": " + errno_text(EEXIST);
  register_temp(dir_path + "/" + tmp);
  int err = 0;
  bool ok = write_all(fd, bytes, err);
  if (ok && ::fchmod(fd, mode_t(mode)) != 0) ok = false, err = errno;
  // fsync and close report what write() could not (delayed allocation on a
  // full disk, NFS write-back).
  if (ok && sync && ::fsync(fd) != 0 && errno != EINVAL && errno != EROFS) ok = false, err = errno;
  if (::close(fd) != 0 && ok) ok = false, err = errno;
  std::string why;
  if (!ok)
    why = errno_text(err);
  else if (::renameat(dirfd, tmp.c_str(), dirfd, name.c_str()) != 0)
    why = "rename failed: " + errno_text(errno);
  if (!why.empty()) ::unlinkat(dirfd, tmp.c_str(), 0);
  unregister_temp();
  return why;
}

namespace {

std::atomic<bool> g_stdout_claimed{false};

// What makes two outputs one file: "-" for standard output; else the file
// a name reaches (links followed): its device and inode when it exists,
// else its folder's real path and its name.
std::string output_identity(const std::string& path) {
  if (path == "-") return "-";
  const OutputTarget t = resolve_output(path);
  struct stat st {};
  if (::stat(t.resolved.c_str(), &st) == 0)
    return "inode " + std::to_string(st.st_dev) + ":" + std::to_string(st.st_ino);
  std::error_code ec;
  const fs::path target(t.resolved);
  const fs::path dir = fs::weakly_canonical(directory_of(target), ec);
  return "path " + (ec ? directory_of(target) : dir).string() + "/" + target.filename().string();
}

}  // namespace

void check_distinct_outputs(const std::vector<NamedOutput>& outputs) {
  std::vector<std::string> ids;
  for (size_t i = 0; i < outputs.size(); ++i) {
    ids.push_back(output_identity(outputs[i].path));
    for (size_t j = 0; j < i; ++j)
      if (ids[j] == ids[i])
        throw UserError(outputs[i].path + ": the " + outputs[i].what + " and the " + outputs[j].what +
                        (outputs[i].path == outputs[j].path ? " are the same file"
                                                            : " (" + outputs[j].path + ") are the same file") +
                        (ids[i] == "-" ? " (standard output)" : "") + ": one would be lost");
  }
}

void claim_stdout() {
  g_stdout_claimed.store(true);
}

std::FILE* report_stream() {
  return g_stdout_claimed.load() ? stderr : stdout;
}

ScratchFile::ScratchFile(const std::string& name) {
  const char* env = std::getenv("TMPDIR");
  std::string tmpl = std::string(env && *env ? env : "/tmp") + "/clrt-XXXXXX";
  if (!::mkdtemp(&tmpl[0]))
    throw UserError("cannot create a scratch directory in " + tmpl.substr(0, tmpl.size() - 12) + ": " +
                    errno_text(errno));
  dir_ = tmpl;
  path_ = dir_ + "/" + name;
  register_path(1, dir_);
  register_path(2, path_);
}

ScratchFile::~ScratchFile() {
  ::unlink(path_.c_str());
  ::rmdir(dir_.c_str());
  unregister_path(2);
  unregister_path(1);
}

std::string ScratchFile::read() const {
  int fd = ::open(path_.c_str(), O_RDONLY | O_CLOEXEC | O_NOFOLLOW);
  if (fd < 0) throw UserError(path_ + ": cannot read back: " + errno_text(errno));
  std::string out;
  char buf[1 << 16];
  for (;;) {
    ssize_t n = ::read(fd, buf, sizeof buf);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) {
      const int e = errno;
      ::close(fd);
      throw UserError(path_ + ": cannot read back: " + errno_text(e));
    }
    if (n == 0) break;
    out.append(buf, size_t(n));
  }
  ::close(fd);
  return out;
}

void set_signal_report(bool print, const std::string& note) {
  g_signal_prints.store(print);
  const size_t n = std::min(note.size(), sizeof g_signal_note - 1);
  std::memcpy(g_signal_note, note.data(), n);
  g_signal_note[n] = '\0';
}

void install_signal_cleanup() {
  struct sigaction sa {};
  sa.sa_handler = on_signal;
  sigemptyset(&sa.sa_mask);
  for (int sig : {SIGINT, SIGTERM, SIGHUP, SIGPIPE}) ::sigaction(sig, &sa, nullptr);
}

OutputTarget resolve_output(const std::string& path, const std::string& what) {
  if (path.empty()) throw UserError(what + " path is empty");
  OutputTarget t;
  t.path = t.resolved = path;
  if (path == "-") {
    t.kind = OutputKind::Stdout;
    return t;
  }
  std::error_code ec;
  fs::path target(path);
  // A symlink OUT is followed (like the shell's `>`): its target is what is
  // written, atomically in the target's own directory.
  // (A dangling link names the file to create.)
  for (int hops = 0; fs::is_symlink(fs::symlink_status(target, ec)); ++hops) {
    if (hops == 40) fail(path, what, "too many levels of symbolic links");
    const fs::path link = fs::read_symlink(target, ec);
    if (ec) fail(path, what, "cannot read the symbolic link: " + ec.message());
    target = link.is_absolute() ? link : directory_of(target) / link;
    t.resolved = target.string();
  }
  const fs::file_status st = fs::status(target, ec);
  if (fs::is_directory(st)) fail(path, what, "it is a directory");
  if (fs::is_character_file(st) || fs::is_fifo(st) || fs::is_socket(st) || fs::is_block_file(st)) {
    if (fs::is_block_file(st)) fail(path, what, "it is a block device");
    t.kind = OutputKind::Stream;
    return t;
  }
  const fs::path dir = directory_of(target);
  if (!fs::is_directory(dir, ec)) fail(path, what, "directory " + dir.string() + " does not exist");
  return t;
}

OutputTarget check_output(const std::string& path, const std::string& what) {
  const OutputTarget t = resolve_output(path, what);
  if (t.kind != OutputKind::File) return t;
  const fs::path target(t.resolved), dir = directory_of(target);
  std::error_code ec;
  // Create and remove a temp file: the only test that holds for root, on
  // read-only mounts and in /proc.
  std::string probe;
  int fd = create_temp(dir, probe);
  if (fd < 0) fail(path, what, "cannot create a file in " + dir.string() + ": " + errno_text(errno));
  register_temp(probe);
  ::close(fd);
  ::unlink(probe.c_str());
  unregister_temp();
  // A sticky directory (/tmp) lets rename() replace only our own files (or
  // any file in a directory we own).
  struct stat dst = {};
  struct stat fst = {};
  if (fs::exists(target, ec) && ::stat(dir.c_str(), &dst) == 0 && (dst.st_mode & S_ISVTX) &&
      ::stat(target.c_str(), &fst) == 0 && fst.st_uid != ::geteuid() && dst.st_uid != ::geteuid() && ::geteuid() != 0)
    fail(path, what, "it belongs to another user in the sticky directory " + dir.string());
  return t;
}

void write_output(const std::string& path, const std::string& bytes, const std::string& what) {
  // No probe here: creating the temp file below fails with the same reason.
  const OutputTarget t = resolve_output(path, what);
  if (t.kind == OutputKind::Stdout || t.kind == OutputKind::Stream) {
    int fd = t.kind == OutputKind::Stdout ? STDOUT_FILENO : ::open(t.resolved.c_str(), O_WRONLY | O_CLOEXEC | O_NOCTTY);
    if (fd < 0) fail(path, what, errno_text(errno));
    int err = 0;
    bool ok = write_all(fd, bytes, err);
    if (t.kind == OutputKind::Stream && ::close(fd) != 0 && ok) ok = false, err = errno;
    if (!ok) fail(path, what, errno_text(err));
    return;
  }
  const fs::path target(t.resolved), dir = directory_of(target);
  const int dirfd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (dirfd < 0) fail(path, what, "cannot open the directory " + dir.string() + ": " + errno_text(errno));
  // The final file gets the usual permissions (0666 less the umask), set
  // only once it is complete.
  const std::string why =
      write_file_at(dirfd, dir.string(), target.filename().string(), bytes, 0666 & ~current_umask(), true);
  ::close(dirfd);
  if (!why.empty()) fail(path, what, why);
}

}  // namespace clrt
