// kernel_source.cpp - embedded/--kernel-dir kernel files and include expansion.
#include "cl/kernel_source.hpp"

#include <fstream>
#include <set>
#include <sstream>

#include "util/error.hpp"

namespace clrt {
namespace {

std::string read_one(const std::string& name, const std::string& dir) {
  if (!dir.empty()) {
    std::ifstream in(dir + "/" + name, std::ios::binary);
    if (!in) throw UserError(dir + "/" + name + ": cannot open kernel file (--kernel-dir)");
    std::ostringstream ss;
    ss << in.rdbuf();
    return ss.str();
  }
  for (const auto& f : embedded_kernel_files())
    if (name == f.name) return f.text;
  throw UserError("kernel file \"" + name + "\" is not embedded in this binary");
}

void expand(const std::string& name, const std::string& dir, std::set<std::string>& seen, std::string& out) {
  if (!seen.insert(name).second) return;  // include each file once
  std::istringstream in(read_one(name, dir));
  std::string line;
  int lineno = 0;
  out += "#line 1 \"" + name + "\"\n";
  while (std::getline(in, line)) {
    ++lineno;
    auto first = line.find_first_not_of(" \t");
    if (first != std::string::npos && line.compare(first, 8, "#include") == 0) {
      auto q1 = line.find('"', first), q2 = line.rfind('"');
      if (q1 != std::string::npos && q2 > q1) {
        expand(line.substr(q1 + 1, q2 - q1 - 1), dir, seen, out);
        out += "#line " + std::to_string(lineno + 1) + " \"" + name + "\"\n";
        continue;
      }
    }
    out += line;
    out += '\n';
  }
}

}  // namespace

std::string load_kernel_source(const std::string& main_file, const std::string& kernel_dir) {
  std::set<std::string> seen;
  std::string out;
  expand(main_file, kernel_dir, seen, out);
  return out;
}

}  // namespace clrt
