// output_file.hpp - writing output files safely: check before the work that
// the path can be written, then write a temporary file in the same directory
// and rename it over the target, so a failure never leaves a partial file.
#pragma once
#include <filesystem>
#include <string>

namespace clrt {

// Throws UserError naming `path` unless it is non-empty, in an existing
// directory that accepts new files, and not itself a directory. `what` names
// the kind of output in messages ("output", "CSV", ...).
void check_writable(const std::string& path, const std::string& what = "output");

// The temporary file used for `target`: hidden, same directory (so rename()
// is atomic), same extension (so format-by-extension writers still work).
std::filesystem::path temp_path_for(const std::filesystem::path& target);

// Renames `tmp` over `target`; on failure removes `tmp` and throws UserError.
void commit_temp(const std::filesystem::path& tmp, const std::string& target, const std::string& what = "output");

// check_writable + temp file + commit_temp for text (CSV, JSON, ...).
void write_text_atomic(const std::string& path, const std::string& text, const std::string& what = "output");

}  // namespace clrt
