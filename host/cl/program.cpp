// program.cpp - program build through the binary cache, build log on failure.
#include "cl/program.hpp"

#include <chrono>
#include <cstdlib>
#include <sstream>

#include "cl/program_cache.hpp"
#include "util/error.hpp"
#include "util/log.hpp"
#include "util/progress.hpp"
#include "util/timer.hpp"

namespace clrt {
namespace {

ProgramCacheKey make_key(const DeviceInfo& dev, const std::string& source, const std::string& options) {
  std::string platform_version;
  try {
    platform_version = dev.platform.getInfo<CL_PLATFORM_VERSION>();
  } catch (const cl::Error&) {
  }
  return {source, options, dev.name, dev.driver, dev.platform_name + " " + platform_version};
}

// A program from a cached binary, or a null program if the driver rejects it.
cl::Program load_binary(const cl::Context& ctx, const DeviceInfo& dev, const std::vector<unsigned char>& bin,
                        const std::string& options) {
  try {
    cl::Program::Binaries bins{bin};
    std::vector<cl_int> status;
    cl::Program p(ctx, {dev.device}, bins, &status);
    if (status.empty() || status[0] != CL_SUCCESS) return cl::Program();
    p.build({dev.device}, options.c_str());
    return p;
  } catch (const cl::Error&) {
    return cl::Program();
  }
}

cl::Program build_from_source(const cl::Context& ctx, const DeviceInfo& dev, const std::string& source,
                              const std::string& options) {
  cl::Program program(ctx, source);
  try {
    // A cold build takes seconds on some drivers: a line counting them, on a terminal.
    SlowStep note("building kernel for " + dev.name);
    program.build({dev.device}, options.c_str());
  } catch (const cl::Error& e) {
    std::string log;
    try {
      log = program.getBuildInfo<CL_PROGRAM_BUILD_LOG>(dev.device);
    } catch (const cl::Error&) {
    }
    // Before the exception: main() reports it as one line, after the log.
    log_message(LogLevel::Error, "---- kernel build log (" + dev.name + ", options: " + options + ") ----\n" + log +
                                     "\n---- end of build log ----");
    throw DeviceError("kernel build failed on " + dev.name + ": " + cl_error_name(e.err()) + " (build log above)");
  }
  return program;
}

}  // namespace

bool driver_caches_programs(const DeviceInfo& dev) {
  if (dev.platform_name != "Portable Computing Language") return false;
  const char* cache = std::getenv("POCL_KERNEL_CACHE");
  return !(cache && std::string(cache) == "0");
}

cl::Program build_program(const cl::Context& ctx, const DeviceInfo& dev, const std::string& source,
                          const std::string& options, BuildStats* stats, BuildFlags flags) {
  auto t0 = std::chrono::steady_clock::now();
  ProgramCacheKey key = make_key(dev, source, options);
  cl::Program program;
  bool hit = false, stored = false;
  const bool driver_keeps = driver_caches_programs(dev);
  std::string note;
  if (flags.use_cache) {
    if (auto bin = cache_load(key); bin && cache_begin_load(key, &note)) {
      // Guarded: a crash inside the driver here leaves the marker, and the
      // next run discards the entry (program_cache.hpp).
      program = load_binary(ctx, dev, *bin, options);
      hit = program() != nullptr;
      cache_end_load(key, hit);
    }
  }
  if (!hit) {
    program = build_from_source(ctx, dev, source, options);
    if (flags.use_cache && !driver_keeps) {
      try {
        auto bins = program.getInfo<CL_PROGRAM_BINARIES>();
        if (bins.size() == 1) stored = cache_store(key, bins[0]);
      } catch (const cl::Error&) {
      }
    }
  }
  double ms = ms_since(t0);
  if (!note.empty()) log_message(LogLevel::Warning, note);
  if (flags.verbose) {
    log_message(LogLevel::Info, "build options (" + dev.name + "): " + options);
    std::ostringstream line;  // a stream: the time as it has always been printed (6 significant digits)
    line << "program "
         << (hit                ? "loaded from cache"
             : !flags.use_cache ? "built (cache off)"
             : stored           ? "built, stored in cache"
             : driver_keeps     ? "built, not stored in the cache (the driver keeps its own: PoCL)"
                                : "built, not stored in the cache")
         << " in " << ms << " ms" << (flags.use_cache ? " [" + cache_entry_path(key) + "]" : "");
    log_message(LogLevel::Info, line.str());
  }
  if (stats) {
    stats->ms = ms;
    stats->cached = hit;
  }
  return program;
}

}  // namespace clrt
