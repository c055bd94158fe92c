// mpi_bench.cpp - clrt_mpi_bench: what distributing one frame over MPI ranks
// costs (docs/developer/distributed.md). A benchmark tool, not part of clrt.
//
//   clrt_mpi_bench frames [--scene F] [--width W] [--height H] [--depth D] [--repeat R]
//                         [--tile-rows N] [--band-rows N] [--device SPEC] [--json]
//   clrt_mpi_bench queue [--scene F] [--width W] [--height H] [--depth D] [--repeat R] [--device SPEC]
//   mpirun -np 2 clrt_mpi_bench pingpong [--max-bytes B] [--json]
//
// queue: R whole frames over the ranks by dist::farm_frames, the code path
// of `clrt render A B C ... -o f_##.png` under mpirun (after one warm-up
// frame per rank), gathered on rank 0 but not written; prints frames/s.
//
// frames: every rank prepares a Renderer (8-bit RGBA frames, as `clrt render
// -o x.png` renders them) and the frame is farmed by dist::farm_frame, the
// code path of `clrt render` under mpirun, R times after one unmeasured
// warm-up frame (the kernel build or cache load and the first launch).
// Without mpirun (a world of one) farm_frame renders the frame in one piece:
// the plain single-process render. Rank 0 prints each frame's wall time,
// frames/s, every rank's per-tile render times and rank 0's gather time.
//
// pingpong: rank 0 sends a message of each size (0 B .. max, x4) to rank 1,
// which sends it back, through dist::Communicator: send(), then receive()
// (which polls with sleeps, as the farm's ranks do) or try_receive() in a
// loop (spinning: MPI's own latency). One-way time = round trip / 2.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "cl/cl.hpp"
#include "cl/device.hpp"
#include "dist/communicator.hpp"
#include "dist/frame_farm.hpp"
#include "dist/frame_queue.hpp"
#include "dist/job.hpp"
#include "dist/wire.hpp"
#include "render/renderer.hpp"
#include "scene/scene_json.hpp"
#include "util/error.hpp"
#include "util/stats.hpp"
#include "util/timer.hpp"

namespace {

using namespace clrt;

struct Options {
  std::string mode;
  std::string scene = "scenes/cgfs-demo.json";
  int width = 1920, height = 1080, depth = 3, repeat = 10, tile_rows = 0, band_rows = 0;
  std::string device;
  long long max_bytes = 64LL << 20;
  bool json = false;
};

[[noreturn]] void usage(const std::string& why) {
  throw UserError(why +
                  "\nusage: clrt_mpi_bench frames [--scene F] [--width W] [--height H] [--depth D] [--repeat R] "
                  "[--tile-rows N] [--band-rows N] [--device SPEC] [--json]\n"
                  "       mpirun -np 2 clrt_mpi_bench pingpong [--max-bytes B] [--json]");
}

Options parse(int argc, char** argv) {
  Options o;
  if (argc < 2) usage("a mode is required");
  o.mode = argv[1];
  if (o.mode != "frames" && o.mode != "queue" && o.mode != "pingpong") usage("unknown mode '" + o.mode + "'");
  for (int i = 2; i < argc; ++i) {
    const std::string a = argv[i];
    const auto value = [&]() -> std::string {
      if (i + 1 >= argc) usage(a + " needs a value");
      return argv[++i];
    };
    const auto number = [&](long long lo, long long hi) {
      const std::string v = value();
      char* end = nullptr;
      const long long n = std::strtoll(v.c_str(), &end, 10);
      if (v.empty() || *end || n < lo || n > hi)
        usage(a + " " + v + ": not a number in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
      return n;
    };
    if (a == "--json")
      o.json = true;
    else if (a == "--scene")
      o.scene = value();
    else if (a == "--width")
      o.width = int(number(1, 16384));
    else if (a == "--height")
      o.height = int(number(1, 16384));
    else if (a == "--depth")
      o.depth = int(number(0, 64));
    else if (a == "--repeat")
      o.repeat = int(number(1, 100000));
    else if (a == "--tile-rows")
      o.tile_rows = int(number(0, 16384));
    else if (a == "--band-rows")
      o.band_rows = int(number(0, 16384));
    else if (a == "--device")
      o.device = value();
    else if (a == "--max-bytes")
      o.max_bytes = number(0, 1LL << 30);
    else
      usage("unknown option '" + a + "'");
  }
  return o;
}

nlohmann::json stats_of(const std::vector<double>& v, const std::string& unit) {
  return stats_json(summarize(v), unit);
}

// ---- queue: whole frames over the ranks (clrt render A B C ... -o f_##.png) ----

// R + 1 frames of the scene (the first is the warm-up of every rank's
// renderer) farmed whole by dist::farm_frames; frames are gathered on rank
// 0 but not written. Prints the frames/s of the R measured frames.
int queue(dist::Communicator& comm, const Options& o) {
  const Scene scene = dist::share_scene(comm, [&] { return load_scene(o.scene); });
  RenderSettings settings;
  settings.kernel.output = FrameContents{PixelFormat::Rgba8, /*classes=*/false};
  std::unique_ptr<Renderer> renderer;
  const auto render = [&](const Scene& s, dist::FrameRun& run) {
    if (!renderer) renderer = std::make_unique<Renderer>(select_devices(o.device), settings);
    const auto t0 = Clock::now();
    renderer->prepare(s, o.width, o.height, o.depth);
    Image img = renderer->render();
    run.ms = ms_since(t0);
    run.devices = renderer->device_names();
    return img;
  };
  dist::FrameQueueSettings q;
  q.width = o.width, q.height = o.height, q.contents = settings.kernel.output;
  // Warm-up: one frame per rank builds or loads every rank's program.
  dist::farm_frames(
      comm, std::vector<Scene>(size_t(comm.size()), scene), q, render, [](const Image&, const dist::FrameRun&) {},
      nullptr);
  const auto t0 = Clock::now();
  dist::FrameQueueStats stats;
  dist::farm_frames(
      comm, std::vector<Scene>(size_t(o.repeat), scene), q, render, [](const Image&, const dist::FrameRun&) {}, &stats);
  const double ms = ms_since(t0);
  if (comm.rank() != 0) return 0;
  std::printf("%d frames whole over %d rank(s), %dx%d depth %d: %.1f ms\n", o.repeat, comm.size(), o.width, o.height,
              o.depth, ms);
  for (const dist::RankShare& r : stats.ranks) std::printf("rank %d: %d frames\n", r.rank, r.units);
  std::printf("frames/s: %.4f\n", 1000.0 * o.repeat / ms);
  return 0;
}

// ---- frames -------------------------------------------------------------------

int frames(dist::Communicator& comm, const Options& o) {
  const Scene scene = dist::share_scene(comm, [&] { return load_scene(o.scene); });
  RenderSettings settings;
  settings.kernel.output = FrameContents{PixelFormat::Rgba8, /*classes=*/false};
  settings.tiles.band_rows = o.band_rows;  // clrt's --band-rows: launches per tile (0: the renderer's choice)
  std::unique_ptr<Renderer> renderer;
  double prepare_ms = 0;
  // The first frame prepares (builds or loads the program, uploads the
  // scene); every later one reuses it, as frames of one job would.
  const auto prepare = [&]() -> Renderer& {
    if (!renderer) {
      const auto t0 = Clock::now();
      renderer = std::make_unique<Renderer>(select_devices(o.device), settings);
      renderer->prepare(scene, o.width, o.height, o.depth);
      prepare_ms = ms_since(t0);
    }
    return *renderer;
  };
  dist::FarmSettings farm;
  farm.width = o.width, farm.height = o.height, farm.contents = settings.kernel.output;
  farm.tile_rows = o.tile_rows;

  std::vector<double> wall, gather;
  std::vector<int> tiles;
  std::vector<long long> gathered;
  // Per rank: every measured frame's tiles (render ms, rows).
  std::vector<std::vector<dist::TileTime>> tile_log(size_t(comm.size()));
  std::vector<double> send_ms(size_t(comm.size()), 0);
  double warmup_ms = 0;
  for (int f = 0; f <= o.repeat; ++f) {
    dist::FarmStats stats;
    const auto t0 = Clock::now();
    dist::farm_frame(comm, prepare, farm, &stats);
    const double ms = ms_since(t0);
    if (comm.rank() != 0) continue;
    if (f == 0) {
      warmup_ms = ms;
      continue;
    }
    wall.push_back(ms);
    gather.push_back(stats.gather_ms);
    tiles.push_back(stats.tiles);
    gathered.push_back(stats.bytes_received);
    for (const dist::RankShare& s : stats.ranks) {
      auto& log = tile_log[size_t(s.rank)];
      log.insert(log.end(), s.tiles.begin(), s.tiles.end());
      send_ms[size_t(s.rank)] += s.send_ms;
    }
    if (!o.json)
      std::printf("frame %d: %.2f ms, %d tiles, %.2f MiB gathered in %.2f ms\n", f, ms, stats.tiles,
                  double(stats.bytes_received) / (1 << 20), stats.gather_ms);
  }
  if (comm.rank() != 0) return 0;

  const Stats w = summarize(wall);
  const double fps = 1000.0 / w.mean;
  const long long pixel_bytes = 4;
  nlohmann::json j;
  j["mode"] = "frames";
  j["ranks"] = comm.size();
  j["scene"] = o.scene;
  j["width"] = o.width, j["height"] = o.height, j["depth"] = o.depth;
  j["tile_rows"] = o.tile_rows;
  j["band_rows"] = o.band_rows;
  j["device"] = renderer ? renderer->device_names() : "";
  j["prepare_ms_rank0"] = prepare_ms;
  j["warmup_frame_ms"] = warmup_ms;
  j["frame_ms"] = wall;
  j["frame"] = stats_json(w, "ms");
  j["frames_per_s"] = fps;
  j["gather"] = stats_of(gather, "ms");
  j["tiles_per_frame"] = tiles;
  j["bytes_gathered_per_frame"] = gathered;
  nlohmann::json per_rank = nlohmann::json::array();
  for (int r = 0; r < comm.size(); ++r) {
    const auto& log = tile_log[size_t(r)];
    std::vector<double> ms, ms_per_mpixel;
    long long rows = 0;
    nlohmann::json list = nlohmann::json::array();
    for (const dist::TileTime& t : log) {
      ms.push_back(t.ms);
      ms_per_mpixel.push_back(t.ms / (double(t.y1 - t.y0) * o.width / 1e6));
      rows += t.y1 - t.y0;
      list.push_back({{"y0", t.y0}, {"y1", t.y1}, {"ms", t.ms}, {"bytes", (t.y1 - t.y0) * o.width * pixel_bytes}});
    }
    per_rank.push_back({{"rank", r},
                        {"tiles", log.size()},
                        {"rows", rows},
                        {"tile", stats_of(ms, "ms")},
                        {"ms_per_mpixel", stats_of(ms_per_mpixel, "ms")},
                        {"send_ms_total", send_ms[size_t(r)]},
                        {"tile_log", list}});
  }
  j["per_rank"] = per_rank;
  if (o.json) {
    std::printf("%s\n", j.dump(2).c_str());
    return 0;
  }
  std::printf("%d rank(s), %s, %dx%d depth %d, tile rows %d (%s)\n", comm.size(),
              j["device"].get<std::string>().c_str(), o.width, o.height, o.depth, o.tile_rows,
              o.tile_rows ? "fixed" : "guided");
  std::printf("prepare (rank 0) %.1f ms, warm-up frame %.1f ms\n", prepare_ms, warmup_ms);
  std::printf("frame: %s\n", format_stats(w).c_str());
  std::printf("rank 0 gather (receive + store rows): %s\n", format_stats(summarize(gather)).c_str());
  for (const auto& r : per_rank) {
    const int rank = r["rank"];
    std::vector<double> ms, mp;
    for (const auto& t : r["tile_log"]) ms.push_back(t["ms"].get<double>());
    for (const dist::TileTime& t : tile_log[size_t(rank)]) mp.push_back(t.ms / (double(t.y1 - t.y0) * o.width / 1e6));
    std::printf("rank %d: %zu tiles, %lld rows; per tile %s; per Mpixel %s; encode+send %.2f ms in all\n", rank,
                ms.size(), r["rows"].get<long long>(), format_stats(summarize(ms)).c_str(),
                format_stats(summarize(mp)).c_str(), send_ms[size_t(rank)]);
  }
  std::printf("frames/s: %.4f\n", fps);
  return 0;
}

// ---- pingpong -----------------------------------------------------------------

int pingpong(dist::Communicator& comm, const Options& o) {
  if (comm.size() < 2) throw UserError("pingpong needs two ranks: mpirun -np 2 clrt_mpi_bench pingpong");
  std::vector<long long> sizes{0};
  for (long long s = 1; s <= o.max_bytes; s *= 4) sizes.push_back(s);
  nlohmann::json rows = nlohmann::json::array();
  if (comm.rank() == 0 && !o.json)
    std::printf("%-10s %-8s %5s  %-28s %s\n", "bytes", "wait", "N", "one-way latency (us)", "bandwidth (MB/s)");
  for (const bool spin : {false, true}) {
    for (const long long size : sizes) {
      // Enough round trips for ~0.3 s of 1 GB/s traffic, at least 5, at most 300.
      const int n = int(std::clamp<long long>((300LL << 20) / std::max<long long>(size, 1), 5, 300));
      const dist::Bytes data(size_t(size), uint8_t(0x5a));
      const auto receive = [&](int from) {
        if (!spin) return comm.receive(from, 7);
        dist::Message m;
        while (!comm.try_receive(m, from, 7)) {
        }
        return m;
      };
      std::vector<double> one_way_us;
      for (int i = -2; i < n; ++i) {  // two unmeasured round trips first
        if (comm.rank() == 0) {
          const auto t0 = Clock::now();
          comm.send(1, 7, data);
          const dist::Message back = receive(1);
          const double us = ms_since(t0) * 1000 / 2;
          if (back.data.size() != data.size()) throw std::runtime_error("pingpong: wrong size back");
          if (i >= 0) one_way_us.push_back(us);
        } else if (comm.rank() == 1) {
          const dist::Message m = receive(0);
          comm.send(0, 7, m.data);
        }
      }
      comm.flush();
      if (comm.rank() != 0) continue;
      const Stats s = summarize(one_way_us);
      std::vector<double> mbps;
      for (double us : one_way_us) mbps.push_back(double(size) / us);  // bytes/us = MB/s
      const Stats b = summarize(mbps);
      rows.push_back({{"bytes", size},
                      {"wait", spin ? "spin" : "receive"},
                      {"one_way", stats_json(s, "us")},
                      {"bandwidth", stats_json(b, "MBps")}});
      if (!o.json)
        std::printf("%-10lld %-8s %5d  %10.1f ± %-8.1f (med %.1f)  %9.1f ± %.1f\n", size, spin ? "spin" : "receive",
                    s.n, s.mean, s.sd, s.median, b.mean, b.sd);
    }
  }
  if (comm.rank() == 0 && o.json) {
    nlohmann::json j;
    j["mode"] = "pingpong";
    j["ranks"] = comm.size();
    j["sizes"] = rows;
    std::printf("%s\n", j.dump(2).c_str());
  }
  // Ranks beyond 1 only wait.
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  // MPI when launched by mpirun, as clrt's main() does.
  std::unique_ptr<dist::Session> mpi;
  try {
    mpi = std::make_unique<dist::Session>(argc, argv);
  } catch (const std::exception& e) {
    if (dist::environment_rank() == 0) std::fprintf(stderr, "clrt_mpi_bench: error: %s\n", e.what());
    return 2;
  }
  dist::Communicator& comm = dist::world();
  try {
    const Options o = parse(argc, argv);
    return o.mode == "frames" ? frames(comm, o) : o.mode == "queue" ? queue(comm, o) : pingpong(comm, o);
  } catch (const dist::JobAborted&) {
    return 2;
  } catch (const cl::Error& e) {
    if (comm.rank() == 0) std::fprintf(stderr, "clrt_mpi_bench: error: %s\n", describe(e).c_str());
  } catch (const std::exception& e) {
    if (comm.rank() == 0) std::fprintf(stderr, "clrt_mpi_bench: error: %s\n", e.what());
  }
  if (comm.distributed()) comm.abort(2);
  return 2;
}
