// kernel_source.hpp - kernel text: embedded into the binary at build time, or
// read from --kernel-dir for development. `#include "x"` lines are resolved
// here, so the text handed to clBuildProgram is self-contained (and hashable
// as a cache key).
#pragma once
#include <string>
#include <vector>

namespace clrt {

struct EmbeddedFile {
  const char* name;
  const char* text;
};
const std::vector<EmbeddedFile>& embedded_kernel_files();  // generated

// Returns the fully expanded source of `main_file` (e.g. "trace.cl"): every
// `#include "name"` line, at any depth, is replaced by that file (each file
// once), between #line directives naming the original files. With a
// non-empty kernel_dir the files come from that directory instead. A file
// that cannot be found, or an unreadable `#include "` line, is a UserError
// naming the file and where it was included from; `#include <name>` lines
// are left to the compiler.
std::string load_kernel_source(const std::string& main_file, const std::string& kernel_dir = "");

}  // namespace clrt
