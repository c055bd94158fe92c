// cmd_cache.cpp - `clrt cache info` and `clrt cache clear`: the program
// binary cache (cl/program_cache.hpp) seen and emptied from the command line.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "app/options.hpp"
#include "cl/program_cache.hpp"
#include "util/error.hpp"

namespace clrt {

namespace {

// "3.4 MiB (3565158 bytes)".
std::string size_text(uint64_t bytes) {
  char buf[64];
  if (bytes >= (uint64_t(1) << 20))
    std::snprintf(buf, sizeof buf, "%.1f MiB (%llu bytes)", double(bytes) / double(1 << 20),
                  static_cast<unsigned long long>(bytes));
  else
    std::snprintf(buf, sizeof buf, "%llu bytes", static_cast<unsigned long long>(bytes));
  return buf;
}

std::string cache_dir_or_throw() {
  const std::string dir = program_cache_dir();
  if (dir.empty()) throw UserError("no program cache directory: set CLRT_CACHE_DIR, XDG_CACHE_HOME or HOME");
  return dir;
}

}  // namespace

void add_cache_command(CLI::App& app) {
  auto* cmd = app.add_subcommand("cache", "Show or empty the program binary cache");
  cmd->require_subcommand(1);

  auto* info = cmd->add_subcommand("info", "Cache directory, entry count, total size and size limit");
  info->callback([] {
    const std::string dir = cache_dir_or_throw();
    const uint64_t limit = program_cache_limit(/*strict=*/true);
    const ProgramCacheStats s = cache_stats(dir);
    const char* env = std::getenv("CLRT_CACHE_MAX_SIZE");
    std::printf("path     %s%s\n", dir.c_str(), s.exists ? "" : " (does not exist yet)");
    std::printf("entries  %zu\n", s.entries);
    std::printf("size     %s\n", size_text(s.bytes).c_str());
    std::printf("limit    %s, %s\n", size_text(limit).c_str(),
                env && *env ? "from CLRT_CACHE_MAX_SIZE" : "the default (CLRT_CACHE_MAX_SIZE changes it)");
    if (s.bad_markers) std::printf("bad      %zu key(s) never cached again (a load crashed)\n", s.bad_markers);
    if (s.other) std::printf("other    %zu file(s) that are not entries (left alone)\n", s.other);
  });

  auto* clear = cmd->add_subcommand("clear", "Delete every cache entry (and the marks of keys never cached again)");
  clear->callback([] {
    const std::string dir = cache_dir_or_throw();
    const ProgramCacheCleared c = cache_clear(dir);
    std::printf(
        "removed %zu entr%s (%s)%s from %s\n", c.entries, c.entries == 1 ? "y" : "ies", size_text(c.bytes).c_str(),
        c.bad_markers ? (" and " + std::to_string(c.bad_markers) + " bad-key mark(s)").c_str() : "", dir.c_str());
    const ProgramCacheStats left = cache_stats(dir);
    if (left.entries)
      throw UserError(dir + ": " + std::to_string(left.entries) + " cache entr" + (left.entries == 1 ? "y" : "ies") +
                      " could not be removed");
  });
}

}  // namespace clrt
