// cmd_cache.cpp - `clrt cache info`, `clrt cache clear` and `clrt cache
// warm`: the program binary cache (cl/program_cache.hpp) seen, emptied and
// filled from the command line.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "app/options.hpp"
#include "cl/program.hpp"
#include "cl/program_cache.hpp"
#include "dist/communicator.hpp"
#include "dist/job.hpp"
#include "dist/wire.hpp"
#include "image/image_file.hpp"
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

// `clrt cache warm SCENE...`: builds (or finds in the cache) the programs a
// `clrt render` of those scenes with the same options would use, on this
// rank's devices, and stores them: one line per scene. Returns the lines.
std::vector<std::string> warm_programs(const RenderOptions& o, const std::vector<Scene>& scenes,
                                       const std::string& format) {
  RenderSettings settings = o.settings();
  // What render asks the kernel for: the output's colour, no classification.
  settings.kernel.output = FrameContents{output_pixel_format("frame." + format, format), /*classes=*/false};
  std::unique_ptr<Renderer> renderer;
  std::vector<std::string> lines;
  // (where every device's driver caches its own builds, clrt stores none:
  // cl/program.hpp, driver_caches_programs())
  const std::vector<DeviceInfo> devices = o.device.devices();
  const bool driver_keeps = std::all_of(devices.begin(), devices.end(), driver_caches_programs);
  for (size_t i = 0; i < scenes.size(); ++i) {
    if (!renderer) renderer = std::make_unique<Renderer>(o.device.devices(), settings);
    renderer->prepare(scenes[i], o.image.width, o.image.height, o.image.effective_depth(scenes[i]),
                      o.image.sampling());
    const FrameStats f = renderer->stats();
    // One launch over the frame's first rows: drivers that compile for the
    // launch (PoCL: for the work-group size; its own cache, POCL_CACHE_DIR)
    // do it now, not in the render's first frame.
    Image rows;
    renderer->render_rows(rows, 0, std::min(o.image.height, 8));
    char ms[32];
    std::snprintf(ms, sizeof ms, "%.1f ms", f.build_ms);
    lines.push_back(o.scene_paths[i] + ": " + renderer->device_names() + ": " +
                    (f.build_cached   ? "in the cache already (loaded in " + std::string(ms) + ")"
                     : driver_keeps ? "built in " + std::string(ms) + "; the driver keeps it in its own cache (PoCL)"
                                    : "built and stored in the cache in " + std::string(ms)));
  }
  return lines;
}

// cache warm under mpirun: rank 0 loads the scenes (no shared file system is
// assumed) and every rank gets them; each rank warms its own node's cache
// (its devices, its CLRT_CACHE_DIR) and sends its lines to rank 0, which
// prints them in rank order. A failure anywhere is one error line.
void warm_across_ranks(const RenderOptions& o, const std::string& format) {
  dist::Communicator& comm = dist::world();
  std::vector<Scene> scenes;
  const dist::Bytes shared = dist::share_from_root(comm, [&] {
    dist::Writer w;
    for (const std::string& p : o.scene_paths) {
      scenes.push_back(o.image.load_scene(p));
      const dist::Bytes b = dist::encode_scene(scenes.back());
      w.put<uint64_t>(b.size());
      w.put_raw(b.data(), b.size());
    }
    return std::move(w.bytes);
  });
  if (comm.rank() != 0) {
    dist::Reader in(shared);
    for (size_t i = 0; i < o.scene_paths.size(); ++i) {
      dist::Bytes b(size_t(in.get_count(1)));
      in.get_raw(b.data(), b.size());
      scenes.push_back(dist::decode_scene(b));
    }
    std::vector<std::string> lines;
    try {
      dist::keep_alive(comm, [&] { lines = warm_programs(o, scenes, format); });
    } catch (...) {
      dist::report_failure_to_root(comm, dist::exception_text(std::current_exception()));
    }
    dist::Writer w;
    w.put<uint64_t>(lines.size());
    for (const std::string& l : lines) w.put_text(l);
    comm.send(0, dist::kTagReport, w.bytes);
    comm.flush();
    return;
  }
  std::vector<std::vector<std::string>> lines(size_t(comm.size()));
  std::string failure;
  try {
    lines[0] = warm_programs(o, scenes, format);
  } catch (...) {
    failure = dist::rank_label(0, comm.host()) + ": " + dist::exception_text(std::current_exception());
  }
  std::vector<bool> reported(size_t(comm.size()), false);
  reported[0] = true;
  dist::Liveness live(comm);
  for (int waiting = comm.size() - 1; waiting > 0 && failure.empty();) {
    dist::Message m;
    if (!comm.try_receive(m)) {
      const std::string silent = live.silent([&](int r) { return !reported[size_t(r)]; });
      if (!silent.empty()) dist::fail_silent(comm, silent);
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
      continue;
    }
    live.heard(m.source);
    dist::Reader in(m.data);
    if (m.tag == dist::kTagError) {
      failure = in.get_text();
    } else if (m.tag == dist::kTagReport && !reported[size_t(m.source)]) {
      for (uint64_t n = in.get_count(sizeof(uint64_t)); n > 0; --n) lines[size_t(m.source)].push_back(in.get_text());
      reported[size_t(m.source)] = true;
      --waiting;
    }
  }
  if (!failure.empty()) {
    std::vector<int> running;
    for (int r = 1; r < comm.size(); ++r)
      if (!reported[size_t(r)]) running.push_back(r);
    dist::stop_ranks(comm, running, [&] { std::fprintf(stderr, "clrt: error: %s\n", failure.c_str()); });
    throw DeviceError(failure);
  }
  for (int r = 0; r < comm.size(); ++r)
    for (const std::string& l : lines[size_t(r)])
      std::printf("%s: %s\n", dist::rank_label(r, comm.host_of(r)).c_str(), l.c_str());
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

  auto o = std::make_shared<RenderOptions>();
  auto format = std::make_shared<std::string>("png");
  auto* warm = cmd->add_subcommand(
      "warm",
      "Build and store the programs that `clrt render` of these scenes with the same options would use, so that "
      "its first frame loads them (run it on every node, or as `mpirun --map-by ppr:1:node clrt cache warm ...`)");
  o->add(warm, /*with_engine=*/false, /*several_scenes=*/true);
  warm->add_option("--format", *format,
                   "The output format the renders will write, as an extension (float formats such as exr and pfm "
                   "use another program than 8-bit ones such as png)")
      ->capture_default_str();
  warm->callback([o, format] {
    o->validate();
    if (o->kernel.no_cache) throw UserError("--no-cache: cache warm fills the cache");
    const ProgramCacheLocation loc = location_or_throw();
    if (!loc.problem.empty()) throw UserError((loc.path.empty() ? loc.configured : loc.path) + ": " + loc.problem);
    if (dist::world().distributed()) return warm_across_ranks(*o, *format);
    std::vector<Scene> scenes;
    for (const std::string& p : o->scene_paths) scenes.push_back(o->image.load_scene(p));
    for (const std::string& line : warm_programs(*o, scenes, *format)) std::printf("%s\n", line.c_str());
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
