// cmd_render.cpp - `clrt render SCENE... -o OUT`: one frame, or one frame
// per scene written to OUT's pattern (frame_####.png).
#include <CLI/CLI.hpp>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "app/engine.hpp"
#include "app/frame_report.hpp"
#include "app/image_metadata.hpp"
#include "app/options.hpp"
#include "cl/launch_timing.hpp"
#include "dist/communicator.hpp"
#include "dist/frame_farm.hpp"
#include "dist/frame_queue.hpp"
#include "dist/job.hpp"
#include "dist/wire.hpp"
#include "image/image_file.hpp"
#include "reference/reference.hpp"
#include "scene/scene_json.hpp"
#include "util/error.hpp"
#include "util/frame_pattern.hpp"
#include "util/output_file.hpp"
#include "util/progress.hpp"
#include "util/stats.hpp"
#include "util/timer.hpp"

namespace clrt {

namespace {

// `clrt render` launched by mpirun with several ranks: rank 0 checks the
// output and reads the scene, every rank gets it (no shared file system is
// assumed), the frame is farmed out in tiles (dist/frame_farm.hpp), and rank
// 0 writes it.
void render_across_ranks(const RenderOptions& o, const std::string& out, const std::string& format, int tile_rows,
                         int test_stall_rank) {
  dist::Communicator& comm = dist::world();
  OutputTarget target;
  const Scene scene = dist::share_scene(comm, [&] {
    if (o.engine != "opencl") throw UserError("--engine " + o.engine + " does not run across MPI ranks");
    target = check_output_format(out, format);  // fail before any rank renders
    return o.image.load_scene(o.scene_path);
  });
  const int depth = o.image.effective_depth(scene);
  RenderSettings settings = o.settings();
  settings.kernel.output = FrameContents{output_pixel_format(out, format), /*classes=*/false};
  std::unique_ptr<Renderer> renderer;
  const auto prepare = [&]() -> Renderer& {
    renderer = std::make_unique<Renderer>(o.device.devices(), settings);  // this rank's --device
    renderer->prepare(scene, o.image.width, o.image.height, depth, o.image.sampling());
    return *renderer;
  };
  dist::FarmSettings farm;
  farm.width = o.image.width, farm.height = o.image.height, farm.contents = settings.kernel.output;
  farm.tile_rows = tile_rows;
  farm.test_stall_rank = test_stall_rank;
  farm.progress = stderr_progress();
  dist::FarmStats stats;
  Image img = dist::farm_frame(comm, prepare, farm, &stats);
  if (comm.rank() != 0) return;
  dist::stop_if_orphaned();  // a job that was ended writes nothing
  const std::string device = std::to_string(comm.size()) + " MPI ranks (rank 0: " + stats.ranks[0].devices + ")";
  write_image(img, out, image_metadata("clrt render", o, depth, o.engine, device), format);
  std::FILE* report = target.kind == OutputKind::File ? stdout : stderr;
  if (report == stderr && quiet()) return;
  std::fprintf(report, "%s: %dx%d depth %d on %d MPI ranks: %.1f ms, %d tiles, %.2f MiB of rows gathered\n",
               out.c_str(), o.image.width, o.image.height, depth, comm.size(), stats.wall_ms, stats.tiles,
               double(stats.bytes_received) / (1 << 20));
  print_rank_shares(stats.ranks, "tiles", report);
}

// One frame's line, as it is written: where it went, its scene, and its
// times (the kernel's and the build's on a device, or the reference's).
void print_frame_line(const RenderOptions& o, const std::string& path, const std::string& scene_path, int depth,
                      const std::string& device, const dist::FrameRun& run) {
  clear_progress_line();
  if (o.engine == "opencl")
    std::printf("%s: %s, %dx%d depth %d on %s: kernel %.2f ms%s, build %.1f ms%s, frame %.1f ms\n", path.c_str(),
                scene_path.c_str(), o.image.width, o.image.height, depth, device.c_str(), run.kernel_ms,
                time_source_note(run.host_timed_launches, run.launches).c_str(), run.build_ms,
                run.build_cached ? " (cached)" : "", run.ms);
  else
    std::printf("%s: %s, %dx%d depth %d with the reference renderer: %.1f ms\n", path.c_str(), scene_path.c_str(),
                o.image.width, o.image.height, depth, run.ms);
}

// `clrt render A.json B.json ... -o frame_####.png`: one frame per scene,
// frame i written to OUT's pattern with i. Every output name is checked and
// every scene loaded before the first frame renders (on rank 0 under
// mpirun), so bad input fails at once. One renderer renders frame after
// frame (its programs are reused: a scene that needs the same kernel
// rebuilds nothing); each frame is written, atomically, as it is done, so a
// failure leaves the frames written before it, complete, and no partial
// file. Under mpirun whole frames are farmed out to the ranks
// (dist/frame_queue.hpp); each rank encodes the frames it renders and rank 0
// writes their bytes.
void render_frames(const RenderOptions& o, const std::vector<std::string>& paths, const std::string& format) {
  const auto t0 = Clock::now();
  dist::Communicator& comm = dist::world();
  const bool across = comm.distributed();
  // Rank 0's scenes: every one is loaded (checked) before the first frame,
  // and kept for its frame while they total at most kHeldSceneBytes; the
  // rest are loaded again when their frame comes (before, three frames of
  // 4 M triangles held 3.1 GB before frame 0 rendered).
  constexpr size_t kHeldSceneBytes = size_t(512) << 20;
  std::vector<std::shared_ptr<const Scene>> held(o.scene_paths.size());
  std::vector<int> depths(o.scene_paths.size());
  dist::share_from_root(comm, [&] {
    if (across && o.engine != "opencl") throw UserError("--engine " + o.engine + " does not run across MPI ranks");
    std::vector<NamedOutput> frames;
    for (const std::string& p : paths) {
      if (check_output_format(p, format).kind != OutputKind::File)
        throw UserError(p + ": several frames are written to files, not to standard output, a device or a FIFO");
      frames.push_back({p, "frame " + std::to_string(frames.size())});
    }
    check_distinct_outputs(frames);  // f_1.png -> f_0.png would replace frame 0
    size_t held_bytes = 0;
    for (size_t i = 0; i < o.scene_paths.size(); ++i) {
      Scene scene = o.image.load_scene(o.scene_paths[i]);
      depths[i] = o.image.effective_depth(scene);
      const size_t bytes = scene.spheres.size() * sizeof(Sphere) + scene.triangles.size() * sizeof(Triangle) +
                           scene.planes.size() * sizeof(Plane) + scene.lights.size() * sizeof(Light);
      if (held_bytes + bytes <= kHeldSceneBytes) {
        held_bytes += bytes;
        held[i] = std::make_shared<const Scene>(std::move(scene));
      }
    }
    return dist::Bytes{};
  });
  const double load_ms = ms_since(t0);

  RenderSettings settings = o.settings();
  settings.kernel.output = FrameContents{output_pixel_format(paths[0], format), /*classes=*/false};
  std::unique_ptr<Renderer> renderer;  // this rank's (its --device), made at its first frame
  const dist::RenderFrameFn render = [&](const Scene& scene, dist::FrameRun& run) {
    const int depth = o.image.effective_depth(scene);
    if (o.engine == "reference") {
      run.devices = "host (scalar double)";
      return render_reference(scene, o.image.width, o.image.height, depth, o.image.sampling());
    }
    if (!renderer) renderer = std::make_unique<Renderer>(o.device.devices(), settings);
    renderer->prepare(scene, o.image.width, o.image.height, depth, o.image.sampling());
    Image img = renderer->render();
    const FrameStats& f = renderer->stats();
    run.devices = renderer->device_names();
    run.kernel_ms = f.kernel_ms, run.build_ms = f.build_ms, run.build_cached = f.build_cached;
    run.launches = f.launches, run.host_timed_launches = f.host_timed_launches;
    return img;
  };

  // Each frame is encoded where it was rendered (under mpirun, on every rank
  // at once: rank 0 only writes the bytes), with its metadata.
  const auto device_of = [&](const dist::FrameRun& run) {
    return across ? dist::rank_label(run.rank, run.host) + ": " + run.devices : run.devices;
  };
  const dist::EncodeFrameFn encode = [&](const Image& img, const Scene& scene, const dist::FrameRun& run) {
    const size_t i = size_t(run.index);
    RenderOptions frame_options = o;  // scene_path: the frame's, for its metadata
    frame_options.scene_path = o.scene_paths[i];
    const ImageMetadata metadata =
        image_metadata("clrt render", frame_options, o.image.effective_depth(scene), o.engine, device_of(run));
    return encode_image(img, paths[i], metadata, format);
  };
  // Rank 0: each frame written, and its line, as it arrives.
  std::vector<double> frame_ms;
  const dist::FileDoneFn done = [&](const std::string& file, const dist::FrameRun& run) {
    const size_t i = size_t(run.index);
    const int depth = depths[i];
    const std::string device = device_of(run);
    dist::stop_if_orphaned();  // a job that was ended writes nothing
    write_output(paths[i], file);
    frame_ms.push_back(run.ms);
    print_frame_line(o, paths[i], o.scene_paths[i], depth, device, run);
  };
  dist::FrameQueueSettings queue;
  queue.width = o.image.width, queue.height = o.image.height, queue.contents = settings.kernel.output;
  queue.progress = stderr_progress();
  queue.encode = encode;
  queue.file_done = done;
  dist::FrameQueueStats stats;
  const dist::SceneSource scenes = [&](size_t i) {
    return held[i] ? held[i] : std::make_shared<const Scene>(o.image.load_scene(o.scene_paths[i], /*warn=*/false));
  };
  dist::farm_frames(comm, o.scene_paths.size(), scenes, queue, render, /*done=*/nullptr, &stats);
  if (comm.rank() != 0) return;
  clear_progress_line();
  const std::string where = across ? " on " + std::to_string(comm.size()) + " MPI ranks" : "";
  std::printf("%d frames, %dx%d%s: %.1f ms (scenes loaded in %.1f ms), frame time %s\n", stats.frames, o.image.width,
              o.image.height, where.c_str(), ms_since(t0), load_ms, format_stats(summarize(frame_ms)).c_str());
  if (!across) return;
  std::printf("%.2f MiB of frames gathered\n", double(stats.bytes_received) / (1 << 20));
  print_rank_shares(stats.ranks, "frames", stdout);
}

}  // namespace

void add_render_command(CLI::App& app) {
  auto o = std::make_shared<RenderOptions>();
  auto out = std::make_shared<std::string>();
  auto format = std::make_shared<std::string>();
  auto tile_rows = std::make_shared<int>(0);
  auto stall_rank = std::make_shared<int>(-1);
  auto* cmd = app.add_subcommand(
      "render", "Render a scene to an image (png, ppm, exr, ...), or several scenes to numbered frames");
  o->add(cmd, /*with_engine=*/true, /*several_scenes=*/true);
  o->image.add_ray_cut_flag(cmd);
  cmd->add_option("-o,--output", *out,
                  "Output image; the extension picks the format ('-' = PNG on standard output, as are devices and "
                  "FIFOs named without an extension). A run of '#' in its file name is the frame number, "
                  "zero-padded (frame_####.png: frame_0000.png, ...; needed for several scenes)")
      ->required();
  cmd->add_option("--format", *format,
                  "Image format, as an extension (png, ppm, exr, pfm, ...), instead of OUT's: for '-o -' and "
                  "devices (unset: OUT's extension; PNG for '-' and names without one)");
  cmd->add_option("--mpi-tile-rows", *tile_rows,
                  "Under mpirun: rows per tile that rank 0 hands out (0 = guided: shrinking tiles of at least 32768 "
                  "pixels)")
      ->check(CLI::Range(0, kMaxImageEdge))
      ->capture_default_str()
      ->group(kDeveloperGroup);
  add_aov_option(cmd, o->aov);
  add_mpi_timeout_option(cmd);
  // A test hook, not in the help (an empty group): rank R stops taking part
  // in MPI in the middle of its first rows message (dist::FarmSettings).
  cmd->add_option("--mpi-test-stall", *stall_rank, "")->check(CLI::Range(1, 1 << 20))->group("");
  cmd->callback([o, out, format, tile_rows, stall_rank] {
    o->validate();
    // One name per frame (a pattern's run of '#' is replaced, for one scene too).
    const std::vector<std::string> paths = frame_paths(*out, int(o->scene_paths.size()));
    const unsigned layers = o->layers();
    if (layers && (paths.size() > 1 || dist::world().distributed()))
      throw UserError("--aov writes the layers of one frame: one SCENE, not under mpirun");
    if (paths.size() > 1) return render_frames(*o, paths, *format);
    o->scene_path = o->scene_paths.at(0);
    const std::string& path = paths[0];
    if (dist::world().distributed()) return render_across_ranks(*o, path, *format, *tile_rows, *stall_rank);
    const OutputTarget target = check_output_format(path, *format);  // fail before rendering
    if (layers) check_layers_output(path, *format);
    Scene scene = o->image.load_scene(o->scene_path);
    check_layers_fit(scene, layers);
    int depth = o->image.effective_depth(scene);
    EngineRun run;
    // The kernel writes what the file needs: 8-bit RGBA for 8-bit formats,
    // float colour for float ones, the layers asked for, never the
    // per-pixel classification.
    const FrameContents contents{output_pixel_format(path, *format), /*classes=*/false, uint8_t(layers)};
    Image img = run_engine(o->engine, scene, *o, depth, &run, contents);
    ImageMetadata metadata = image_metadata("clrt render", *o, depth, o->engine, run.device);
    if (layers) {
      metadata.push_back({"clrt:aov", layer_list(layers)});
      write_image(img, run.layers, path, metadata, *format);
    } else {
      write_image(img, path, metadata, *format);
    }
    // The report goes to stderr when the image itself goes to stdout.
    std::FILE* report = target.kind == OutputKind::File ? stdout : stderr;
    if (report == stderr && quiet()) return;  // --quiet: only the image
    if (o->engine == "opencl")
      std::fprintf(report, "%s: %dx%d depth %d on %s: kernel %.2f ms%s, build %.1f ms%s\n", path.c_str(),
                   o->image.width, o->image.height, depth, run.device.c_str(), run.frame.kernel_ms,
                   time_source_note(run.frame.host_timed_launches, run.frame.launches).c_str(), run.frame.build_ms,
                   run.frame.build_cached ? " (cached)" : "");
    if (o->engine == "opencl" && run.frame.bvh)
      std::fprintf(report, "%s: hierarchy built in %.1f ms, %.2f MiB, %d levels\n", path.c_str(),
                   run.frame.bvh_build_ms, double(run.frame.bvh_bytes) / (1 << 20), run.frame.bvh_depth + 1);
    if (run.frame.shares.size() > 1) print_shares(run.frame.shares, report);
    if (o->engine != "opencl")
      std::fprintf(report, "%s: %dx%d depth %d with the reference renderer: %.1f ms\n", path.c_str(), o->image.width,
                   o->image.height, depth, run.wall_ms);
  });
}

}  // namespace clrt
