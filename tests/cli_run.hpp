// cli_run.hpp - run the built clrt binary as a subprocess in a scratch
// directory and capture its exit status, stdout and stderr.
#pragma once
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "util/build_features.hpp"

namespace clrt_test {

// The image the CLI tests write where its format does not matter: PNG, or
// PPM in a lean build (CLRT_LEAN=ON writes and reads PPM and PFM only).
inline const std::string kImageExt = clrt::kLeanBuild ? ".ppm" : ".png";
inline std::string image_name(const std::string& stem) {
  return stem + kImageExt;
}
// Whether `bytes` begin as such an image does (what `-o -` writes).
inline bool starts_as_image(const std::string& bytes) {
  return bytes.rfind(clrt::kLeanBuild ? "P6\n" : "\x89PNG", 0) == 0;
}

// A fresh directory under the system temp dir, removed with its contents.
class TempDir {
 public:
  TempDir() {
    std::string tmpl = (std::filesystem::temp_directory_path() / "clrt_test_XXXXXX").string();
    if (!::mkdtemp(&tmpl[0])) throw std::runtime_error("mkdtemp failed");
    path_ = tmpl;
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;

  std::string operator/(const std::string& name) const { return (path_ / name).string(); }
  const std::filesystem::path& path() const { return path_; }
  // Writes `text` to `name` in this directory and returns its path.
  std::string write(const std::string& name, const std::string& text) const {
    std::ofstream(path_ / name, std::ios::binary) << text;
    return (path_ / name).string();
  }
  // Names of the entries in this directory, sorted.
  std::vector<std::string> entries() const {
    std::vector<std::string> out;
    for (auto& e : std::filesystem::directory_iterator(path_)) out.push_back(e.path().filename().string());
    std::sort(out.begin(), out.end());
    return out;
  }

 private:
  std::filesystem::path path_;
};

struct RunResult {
  int status = -1;  // exit status, or -1 if the process did not exit normally
  std::string out, err;
  // stderr is exactly one line.
  bool one_line_error() const { return !err.empty() && err.back() == '\n' && err.find('\n') == err.size() - 1; }
  // The last line of stderr (without its newline).
  std::string last_error_line() const {
    std::string e = err;
    while (!e.empty() && e.back() == '\n') e.pop_back();
    return e.substr(e.rfind('\n') == std::string::npos ? 0 : e.rfind('\n') + 1);
  }
};

inline std::string shell_quote(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

inline std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// Runs a shell command line; stdout/stderr go to files in a scratch
// directory (not the output directory the tests inspect).
inline RunResult run_command_line(const std::string& line) {
  static TempDir scratch;
  const std::string cmd =
      line + " >" + shell_quote(scratch / "out") + " 2>" + shell_quote(scratch / "err") + " </dev/null";
  int st = std::system(cmd.c_str());
  RunResult r;
  r.status = (st != -1 && WIFEXITED(st)) ? WEXITSTATUS(st) : -1;
  r.out = slurp(scratch / "out");
  r.err = slurp(scratch / "err");
  return r;
}

// `clrt ARGS...`, quoted, as a shell command line.
inline std::string clrt_command(const std::vector<std::string>& args) {
  std::string cmd = shell_quote(CLRT_BINARY);
  for (const auto& a : args) cmd += " " + shell_quote(a);
  return cmd;
}

// Runs `clrt ARGS...` with `env` (e.g. "OCL_ICD_VENDORS=/x") prepended.
inline RunResult run_clrt(const std::vector<std::string>& args, const std::string& env = "") {
  return run_command_line((env.empty() ? "" : env + " ") + clrt_command(args));
}

}  // namespace clrt_test
