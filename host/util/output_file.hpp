// output_file.hpp - writing output files safely. Every output clrt writes
// (images, CSV, plots) is produced in memory first and handed to
// write_output(), the one place that touches the file system:
//
// - a regular file (new, or existing and replaced) is written through a temp
//   file created exclusively (O_CREAT|O_EXCL, random name, mode 0600 until it
//   is complete) in the target's directory, every write, fsync and close
//   checked, then renamed over the target: a failure (full disk, I/O error,
//   signal) never leaves a partial OUT or a temp file, and a name planted by
//   someone else (a symlink) is never followed;
// - a symlink OUT is followed: its target is written as above;
// - a character device, FIFO or socket (/dev/stdout, /dev/full, a pipe) and
//   "-" (standard output) are written in place, errors checked.
//
// check_output() runs the same decisions before any work, so a path that
// cannot be written fails in milliseconds, not after a long render.
#pragma once
#include <cstdio>
#include <string>
#include <vector>

namespace clrt {

enum class OutputKind {
  File,    // a regular file, new or existing: written atomically
  Stream,  // a device, FIFO or socket: written in place
  Stdout,  // "-"
};

struct OutputTarget {
  std::string path;      // as given (for messages)
  std::string resolved;  // what is written: `path`, or a symlink's target
  OutputKind kind = OutputKind::File;
};

// Classifies `path` (following a symlink OUT to its target) without touching
// the file system beyond stat: UserError naming `path` when it is empty, a
// directory, a block device, or in a directory that does not exist.
OutputTarget resolve_output(const std::string& path, const std::string& what = "output");

// Throws UserError naming `path` unless it can be written: non-empty, an
// existing directory that accepts new files (probed by creating and removing
// a temp file; permission bits say nothing for root), not a directory, and -
// in a sticky directory such as /tmp - not another user's existing file that
// rename() could not replace. `what` names the output in messages
// ("output", "CSV", "plot", ...).
OutputTarget check_output(const std::string& path, const std::string& what = "output");
inline void check_writable(const std::string& path, const std::string& what = "output") {
  (void)check_output(path, what);
}

// Writes `bytes` to `path` as described above; UserError naming `path` and
// the system's reason on any failure, with nothing left behind.
void write_output(const std::string& path, const std::string& bytes, const std::string& what = "output");
inline void write_text_atomic(const std::string& path, const std::string& text, const std::string& what = "output") {
  write_output(path, text, what);
}

// The atomic write itself, beneath the open directory `dirfd` (whose path,
// `dir_path`, names the temp file for the signal handler): `bytes` go to a
// temp file created there exclusively (random name, O_CREAT|O_EXCL|
// O_NOFOLLOW, mode 0600), every write checked, fsync'ed when `sync`, given
// `mode`, then renamed to `name` (rename replaces whatever has that name -
// a planted link included - and never follows it). Returns "" when done,
// else the system's reason, with nothing left behind. Never throws.
std::string write_file_at(int dirfd, const std::string& dir_path, const std::string& name, const std::string& bytes,
                          unsigned mode, bool sync);

// The outputs of one command, checked together before any work: UserError
// when two are one file - the same name, names that reach one file through
// links (f_1.png -> f_0.png), or "-" (standard output) twice - naming both.
struct NamedOutput {
  std::string path, what;  // what: "CSV", "plot", "frame 3", ...
};
void check_distinct_outputs(const std::vector<NamedOutput>& outputs);

// Where a command prints its report (tables, "wrote ..." lines): standard
// output, unless one of its outputs is "-" (claim_stdout()), then standard
// error, so that standard output holds that output alone.
void claim_stdout();
std::FILE* report_stream();
inline void claim_stdout_if_dash(const std::string& path) {
  if (path == "-") claim_stdout();
}

// A file named `name` in a new private directory (mode 0700, random name)
// under $TMPDIR or /tmp, for encoders that can only write to a path: nobody
// else can plant anything there. Both are removed by the destructor, and by
// the signal handler below.
class ScratchFile {
 public:
  explicit ScratchFile(const std::string& name);
  ~ScratchFile();
  ScratchFile(const ScratchFile&) = delete;
  ScratchFile& operator=(const ScratchFile&) = delete;
  const std::string& path() const { return path_; }
  std::string read() const;  // the file's bytes (UserError on failure)

 private:
  std::string dir_, path_;
};

// SIGINT, SIGTERM, SIGHUP and SIGPIPE: remove the temp file being written
// (if any), print one `clrt: error: interrupted by SIG...` line and exit
// 128 + the signal number (130 for SIGINT, 143 for SIGTERM). Called once by
// main().
void install_signal_cleanup();
// What that line says: `note` is appended to it (e.g. why mpirun ended the
// job); print = false: no line (the other ranks of an MPI job, whose rank 0
// prints it), the same cleanup and exit status.
void set_signal_report(bool print, const std::string& note);

}  // namespace clrt
