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

// Returns the fully expanded source of `main_file` (e.g. "trace.cl"). With a
// non-empty kernel_dir the files come from that directory instead.
std::string load_kernel_source(const std::string& main_file, const std::string& kernel_dir = "");

}  // namespace clrt
