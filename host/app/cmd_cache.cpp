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

ProgramCacheLocation location_or_throw() {
  ProgramCacheLocation loc = program_cache_location();
  if (loc.configured.empty()) throw UserError(loc.problem);
  return loc;
}

}  // namespace

void add_cache_command(CLI::App& app) {
  auto* cmd = app.add_subcommand("cache", "Show or empty the program binary cache");
  cmd->require_subcommand(1);

  auto* info = cmd->add_subcommand("info", "Cache directory, entry count, total size and size limit");
  info->callback([] {
    const ProgramCacheLocation loc = location_or_throw();
    const uint64_t limit = program_cache_limit(/*strict=*/true);
    const std::string dir = loc.path.empty() ? loc.configured : loc.path;
    const ProgramCacheStats s = loc.problem.empty() ? cache_stats(dir) : ProgramCacheStats{};
    const char* env = std::getenv("CLRT_CACHE_MAX_SIZE");
    const std::string state = !loc.problem.empty() ? " (unusable: " + loc.problem + "; nothing is cached)"
                              : !s.exists          ? " (does not exist yet)"
                                                   : "";
    std::printf("path     %s%s\n", dir.c_str(), state.c_str());
    if (loc.shared)
      std::printf("shared   %s may be written by others: this user's entries are in its subdirectory above\n",
                  loc.configured.c_str());
    std::printf("entries  %zu\n", s.entries);
    std::printf("size     %s\n", size_text(s.bytes).c_str());
    std::printf("limit    %s, %s\n", size_text(limit).c_str(),
                env && *env ? "from CLRT_CACHE_MAX_SIZE" : "the default (CLRT_CACHE_MAX_SIZE changes it)");
    if (s.bad_markers) std::printf("bad      %zu key(s) never cached again (a load crashed)\n", s.bad_markers);
    if (s.other) std::printf("other    %zu file(s) that are not entries (left alone)\n", s.other);
  });

  auto* clear = cmd->add_subcommand("clear", "Delete every cache entry (and the marks of keys never cached again)");
  clear->callback([] {
    const ProgramCacheLocation loc = location_or_throw();
    if (!loc.problem.empty()) throw UserError((loc.path.empty() ? loc.configured : loc.path) + ": " + loc.problem);
    const std::string dir = loc.path;
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
