// kernel_source.cpp - embedded/--kernel-dir kernel files and include expansion.
#include "cl/kernel_source.hpp"

#include <fstream>
#include <set>
#include <sstream>

#include "util/error.hpp"

namespace clrt {
namespace {

// Where an #include line sits, for error messages ("" for the main file).
std::string included_from(const std::string& includer, int line) {
  return includer.empty() ? "" : ", included from " + includer + " line " + std::to_string(line);
}

std::string read_one(const std::string& name, const std::string& dir, const std::string& includer, int line) {
  if (!dir.empty()) {
    std::ifstream in(dir + "/" + name, std::ios::binary);
    if (!in)
      throw UserError(dir + "/" + name + ": cannot open kernel file (--kernel-dir)" + included_from(includer, line));
    std::ostringstream ss;
    ss << in.rdbuf();
    return ss.str();
  }
  for (const auto& f : embedded_kernel_files())
    if (name == f.name) return f.text;
  throw UserError("kernel file \"" + name + "\" is not embedded in this binary" + included_from(includer, line));
}

// The file name of an `#include "name"` line, "" for any other line.
// `#include <name>` is left to the compiler: clrt_layout.h has one in its
// host-only branch, which the OpenCL compiler skips.
std::string include_target(const std::string& line, const std::string& file, int lineno) {
  const auto hash = line.find_first_not_of(" \t");
  if (hash == std::string::npos || line[hash] != '#') return "";
  const auto directive = line.find_first_not_of(" \t", hash + 1);  // "# include" is an include too
  if (directive == std::string::npos || line.compare(directive, 7, "include") != 0) return "";
  const auto open = line.find_first_not_of(" \t", directive + 7);
  if (open != std::string::npos && line[open] == '<') return "";
  const auto close = open == std::string::npos || line[open] != '"' ? std::string::npos : line.find('"', open + 1);
  if (close == std::string::npos || close == open + 1)
    throw UserError(file + " line " + std::to_string(lineno) + ": cannot read this #include (kernel files include " +
                    "other kernel files as #include \"name\"): " + line.substr(hash));
  return line.substr(open + 1, close - open - 1);
}

// Appends `name` with its includes expanded in place; each file is expanded
// once (later includes of it add nothing, like #pragma once), and #line
// directives keep the compiler's diagnostics pointing at the original files.
void expand(const std::string& name, const std::string& dir, const std::string& includer, int include_line,
            std::set<std::string>& seen, std::string& out) {
  if (!seen.insert(name).second) return;
  std::istringstream in(read_one(name, dir, includer, include_line));
  std::string line;
  int lineno = 0;
  out += "#line 1 \"" + name + "\"\n";
  while (std::getline(in, line)) {
    ++lineno;
    const std::string target = include_target(line, name, lineno);
    if (!target.empty()) {
      expand(target, dir, name, lineno, seen, out);
      out += "#line " + std::to_string(lineno + 1) + " \"" + name + "\"\n";
      continue;
    }
    out += line;
    out += '\n';
  }
}

}  // namespace

std::string load_kernel_source(const std::string& main_file, const std::string& kernel_dir) {
  std::set<std::string> seen;
  std::string out;
  expand(main_file, kernel_dir, "", 0, seen, out);
  return out;
}

}  // namespace clrt
