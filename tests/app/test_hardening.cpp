// test_hardening.cpp - what adversarial input, full disks, hostile
// directories, bad caches and signals must not break: each case
// reproduces a failure the earlier code had.
#include <fcntl.h>
#include <signal.h>
#include <sys/mount.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <catch2/catch.hpp>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <thread>

#include "cl/program_cache.hpp"
#include "cli_run.hpp"
#include "eval/compare.hpp"
#include "reference/reference.hpp"
#include "render/build_options.hpp"
#include "render/precision.hpp"
#include "render/renderer.hpp"
#include "scene/ray_tree.hpp"
#include "scene/scene_json.hpp"
#include "test_util.hpp"
#include "util/error.hpp"
#include "util/output_file.hpp"

// (clrt_tests is a unity build: each file's code is in a namespace of its own.)
namespace test_hardening {

using Catch::Matchers::Contains;
using Catch::Matchers::StartsWith;
using clrt_test::run_clrt;
using clrt_test::RunResult;
using clrt_test::source_path;
using clrt_test::TempDir;
namespace fs = std::filesystem;

namespace {

const std::string kDemo = source_path("scenes/cgfs-demo.json");

void check_error(const RunResult& r, std::initializer_list<std::string> needles) {
  INFO("status " << r.status << ", stderr: " << r.err);
  CHECK(r.status == 2);
  CHECK(r.one_line_error());
  CHECK_THAT(r.err, StartsWith("clrt: error: "));
  for (const auto& n : needles) CHECK_THAT(r.err, Contains(n));
}

// Runs a shell command line; returns its exit status (-1 if it did not exit).
int shell(const std::string& cmd) {
  int st = std::system(cmd.c_str());
  return st != -1 && WIFEXITED(st) ? WEXITSTATUS(st) : -1;
}

// A small tmpfs, or nothing when this process may not mount (not root, no
// CAP_SYS_ADMIN, a container): the caller skips then.
struct SmallTmpfs {
  std::string dir;
  bool mounted = false;
  SmallTmpfs(const TempDir& parent, const char* size) : dir(parent / "tmpfs") {
    fs::create_directory(dir);
    mounted = ::mount("tmpfs", dir.c_str(), "tmpfs", 0, (std::string("size=") + size).c_str()) == 0;
  }
  ~SmallTmpfs() {
    if (mounted) ::umount(dir.c_str());
  }
};

std::vector<std::string> entries(const std::string& dir) {
  std::vector<std::string> out;
  for (auto& e : fs::directory_iterator(dir)) out.push_back(e.path().filename().string());
  return out;
}

}  // namespace

// ---- 1. symlink attacks and temp files --------------------------------------

TEST_CASE("output goes through an exclusive temp file: planted links are never followed", "[cli][hardening][opencl]") {
  TempDir dir;
  // What the old predictable temp name would have been: a planted symlink to
  // a victim file must stay untouched.
  const std::string victim = dir.write("victim.txt", "precious");
  for (int pid = 1; pid < 200; ++pid)
    fs::create_symlink(victim, dir / (".out.tmp" + std::to_string(pid) + clrt_test::image_name("")));
  RunResult r =
      run_clrt({"render", kDemo, "-o", dir / clrt_test::image_name("out"), "--width", "16", "--height", "16"});
  INFO(r.err);
  REQUIRE(r.status == 0);
  CHECK(clrt_test::slurp(victim) == "precious");
  CHECK(fs::is_regular_file(fs::symlink_status(dir / clrt_test::image_name("out"))));
  // The final file has the usual permissions (the temp file is 0600 while it
  // is incomplete), and no temp file is left.
  struct stat st {};
  REQUIRE(::stat((dir / clrt_test::image_name("out")).c_str(), &st) == 0);
  const mode_t mask = ::umask(022);
  ::umask(mask);
  CHECK((st.st_mode & 0777) == (0666 & ~mask));
  for (const auto& e : dir.entries()) CHECK_FALSE(e.rfind(".clrt-", 0) == 0);
}

TEST_CASE("a 250-character output name still works", "[cli][hardening][opencl]") {
  TempDir dir;
  const std::string name = std::string(246, 'n') + clrt_test::image_name("");
  RunResult r = run_clrt({"render", kDemo, "-o", dir / name, "--width", "8", "--height", "8"});
  INFO(r.err);
  CHECK(r.status == 0);
  CHECK(dir.entries() == std::vector<std::string>{name});
}

// ---- 2. full disks ---------------------------------------------------------

TEST_CASE("a full disk is an error, with no output and no temp file", "[cli][hardening][opencl]") {
  // /dev/full: every write fails with ENOSPC (no privileges needed).
  check_error(run_clrt({"render", kDemo, "-o", "/dev/full", "--width", "32", "--height", "32"}),
              {"/dev/full: cannot write output: No space left on device"});
  check_error(run_clrt({"sweep", kDemo, "--depths", "0:1", "--width", "8", "--height", "8", "--repeat", "1", "--csv",
                        "/dev/full"}),
              {"/dev/full: cannot write CSV: No space left on device"});
  // JSON (and every table) on a full standard output.
  const int status = shell(clrt_test::shell_quote(CLRT_BINARY) + " compare " + clrt_test::shell_quote(kDemo) +
                           " --width 8 --height 8 --json >/dev/full 2>/dev/null");
  CHECK(status == 2);

  TempDir parent;
  SmallTmpfs tmpfs(parent, "48k");
  if (!tmpfs.mounted) {
    WARN("cannot mount a tmpfs here (needs root); the small-disk part is skipped");
    return;
  }
  const std::vector<std::string> exts = clrt::kLeanBuild
                                            ? std::vector<std::string>{"ppm", "pfm"}
                                            : std::vector<std::string>{"png", "jpg", "exr", "tif", "sgi", "gif"};
  for (const std::string& ext : exts) {
    INFO(ext);
    const std::string out = tmpfs.dir + "/out." + ext;
    // 600x600 does not fit in 48 KiB in any of these formats.
    check_error(run_clrt({"render", kDemo, "-o", out, "--engine", "reference"}),
                {out + ": cannot write output: No space left on device"});
    CHECK(entries(tmpfs.dir).empty());
  }
  // An already full disk: not even the check file fits.
  std::ofstream(tmpfs.dir + "/filler", std::ios::binary) << std::string(1 << 20, 'x');
  check_error(
      run_clrt({"render", kDemo, "-o", tmpfs.dir + clrt_test::image_name("/out"), "--width", "8", "--height", "8"}),
      {"No space left on device"});
  CHECK(entries(tmpfs.dir) == std::vector<std::string>{"filler"});
}

// ---- 3. launch sizes --------------------------------------------------------

TEST_CASE("a --local size beyond the device's limits is bad input, not a blank image", "[cli][hardening][opencl]") {
  TempDir dir;
  const std::string out = dir / clrt_test::image_name("out");
  for (const char* local : {"2147483647x1", "1x2147483647", "65536x65536"}) {
    INFO(local);
    check_error(run_clrt({"render", kDemo, "-o", out, "--width", "16", "--height", "16", "--local", local}),
                {"--local", "exceeds what"});
    CHECK_FALSE(fs::exists(out));
  }
  check_error(run_clrt({"render", kDemo, "-o", out, "--local", "99999999999x1"}), {"--local: expected WxH"});
}

// ---- 4. and 5. values float32 (or double) cannot hold -----------------------

TEST_CASE("scene values beyond the float32 range are rejected, naming value and limit", "[cli][hardening]") {
  using clrt::parse_scene;
  auto error_of = [](const std::string& text) {
    try {
      parse_scene(text, "s.json");
    } catch (const clrt::UserError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  const std::string sphere = R"({"center": [0, 0, 3], "radius": 1, "color": [255, 0, 0]})";
  CHECK_THAT(error_of(R"({"lights": [{"type": "point", "intensity": 1, "position": [0, 0, -1e39]}]})"),
             Contains("lights[0].position[2]: must be within ±1e+08") && Contains("got -1e+39"));
  CHECK_THAT(error_of(R"({"spheres": [{"center": [0, 0, 0], "radius": 1e20, "color": [1, 1, 1]}]})"),
             Contains("spheres[0].radius: must be in [1e-08, 1e+08]") && Contains("got 1e+20"));
  CHECK_THAT(error_of(R"({"spheres": [{"center": [0, 0, 0], "radius": 1e-20, "color": [1, 1, 1]}]})"),
             Contains("spheres[0].radius: must be in [1e-08, 1e+08]"));
  CHECK_THAT(error_of(R"({"camera": {"position": [1e9, 0, 0]}})"), Contains("camera.position[0]"));
  CHECK_THAT(error_of(R"({"camera": {"viewport": [1e9, 1]}})"), Contains("camera.viewport[0]"));
  CHECK_THAT(error_of(R"({"camera": {"rotation": [[1e5, 0, 0], [0, 1, 0], [0, 0, 1]], "viewport": [1e4, 1]}})"),
             Contains("camera: ray directions reach 5e+08"));
  CHECK_THAT(
      error_of(R"({"lights": [{"type": "ambient", "intensity": 1e30}, {"type": "ambient", "intensity": 1e30}]})"),
      Contains("lights: the intensities add up to 2e+30, more than 1e+30"));
  CHECK_THAT(error_of("{\"spheres\": [" + sphere.substr(0, sphere.size() - 1) + R"(, "specular": 1e9}]})"),
             Contains("spheres[0].specular: must be at most 1e+08"));
}

TEST_CASE("directional light directions are rescaled without overflow or underflow", "[hardening][reference]") {
  // Lighting does not depend on a direction's length; before, [1e-300, ...]
  // made the reference itself output NaN and [0, 1e39, -1e39] NaN pixels.
  auto with_direction = [](const std::string& d, const std::string& epsilon = "0.001") {
    return clrt::parse_scene(R"({"epsilon": )" + epsilon + R"(, "spheres": [{"center": [0, -1, 3], "radius": 1,
      "color": [255, 0, 0], "specular": 10}], "lights": [{"type": "ambient", "intensity": 0.2},
      {"type": "directional", "intensity": 0.8, "direction": )" +
                                 d + "}]}",
                             "s.json");
  };
  const clrt::Scene unit = with_direction("[1, 1, -1]");
  const clrt::Image want = clrt::render_reference(unit, 40, 30, 3);
  // The book's shadow range [epsilon, inf) is in units of the direction
  // given: [4, 4, -4] is [1, 1, -1] with epsilon 4 x 0.001 (the scene has
  // no other ray that epsilon starts), bit for bit.
  CHECK(clrt::render_reference(with_direction("[4, 4, -4]"), 40, 30, 3).rgb ==
        clrt::render_reference(with_direction("[1, 1, -1]", "0.004"), 40, 30, 3).rgb);
  for (const char* d :
       {"[1e-300, 1e-300, -1e-300]", "[1e300, 1e300, -1e300]", "[5e-324, 5e-324, -5e-324]", "[0, 1e39, -1e39]"}) {
    INFO(d);
    const clrt::Vec3 v = with_direction(d).lights[1].vec;
    const double m = std::max({std::fabs(v.x), std::fabs(v.y), std::fabs(v.z)});
    CHECK(m >= 0.5);
    CHECK(m < 1);
  }
  for (const char* d : {"[1e-300, 1e-300, -1e-300]", "[1e300, 1e300, -1e300]", "[5e-324, 5e-324, -5e-324]"}) {
    INFO(d);
    const clrt::Image got = clrt::render_reference(with_direction(d), 40, 30, 3);
    const clrt::Comparison c = clrt::compare_images(got, want);
    CHECK(c.nan_inf == 0);
    CHECK(c.nan_inf_reference == 0);
    // A huge direction's shadow range starts far away (epsilon x |D|): the
    // sphere's lit side is as with [1, 1, -1], whose shadow rays hit nothing.
    // A tiny one's starts at ~1e-303: the book's self-shadowing wherever
    // rounding puts the sphere's own surface past that, so only finiteness
    // is checked there.
    if (std::string(d).find("e300") != std::string::npos) CHECK(c.max_abs_float < 1e-9);
  }
}

TEST_CASE("a directional light's shadow range is the book's, in units of the direction the scene gives",
          "[opencl][hardening][reference]") {
  // The parser rescales a direction by a power of two (above); before, the
  // shadow ray's t_min stayed epsilon along the rescaled direction, so a
  // surface within epsilon x |given direction| of the lit point cast a
  // shadow the book does not (11 pixels of a floor 0.0024 in front of a
  // wall at 512x384). Here: the pixel through the wall point P = (0, 0, 5),
  // light direction D = (4, 0, -4) (|D| = 5.66), and a sphere of radius
  // 0.0005 whose near side lies h = 0.002 from P along D: the book's shadow
  // ray meets it at t = h / |D| = 0.00035 < epsilon = 0.001: lit; along the
  // rescaled (0.5, 0, -0.5), t = 0.0028 > 0.001 was taken for a shadow.
  const double h = 0.002, r = 0.0005, u = 1 / std::sqrt(2.0);
  const double c = (h + r) * u;  // the sphere's centre: P + (h + r) D/|D|
  auto scene = [&](bool sphere) {
    std::ostringstream text;
    text.precision(17);
    // (A viewport of 1e-6: the one pixel's ray meets the wall 5e-6 from P.)
    text << R"({"camera": {"viewport": [1e-6, 1e-6]}, "epsilon": 0.001, "background": [0, 0, 0],
      "planes": [{"point": [0, 0, 5], "normal": [0, 0, -1], "color": [200, 200, 200]}],
      "spheres": [)";
    if (sphere) text << R"({"center": [)" << c << ", 0, " << 5 - c << R"(], "radius": )" << r << R"(, "color": [0, 0, 255]})";
    text << R"(], "lights": [{"type": "ambient", "intensity": 0.1},
      {"type": "directional", "intensity": 0.9, "direction": [4, 0, -4]}]})";
    return clrt::parse_scene(text.str(), "epsilon.json");
  };
  const clrt::Scene open = scene(false), shaded = scene(true);
  const clrt::Image lit = clrt::render_reference(open, 1, 1, 0);
  const clrt::Image got = clrt::render_reference(shaded, 1, 1, 0);
  REQUIRE(lit.rgb[0] > 100);  // 200 x (0.1 + 0.9 cos 45°)
  CHECK(got.rgb == lit.rgb);
  const clrt::Image cl = clrt_test::render_cl(shaded, 1, 1, 0, clrt::KernelConfig{});
  CHECK(clrt::compare_images(cl, got).off_by_gt1 == 0);
  CHECK(std::fabs(cl.rgb[0] - lit.rgb[0]) <= 1);
  // The scene writes back the direction it was given, so it reads back the same.
  const clrt::Scene back = clrt::parse_scene(clrt::scene_to_json(shaded), "back.json");
  CHECK(back.lights[1].vec.x == shaded.lights[1].vec.x);
  CHECK(back.lights[1].scale_exponent == 3);
  CHECK(clrt::render_reference(back, 1, 1, 0).rgb == lit.rgb);
}

TEST_CASE("at the edges of the accepted range no engine or precision gives a NaN pixel", "[opencl][hardening][slow]") {
  // Each scene is at a limit of scene.hpp's range; every variant the device
  // runs must stay finite, and so must the reference.
  const std::vector<std::string> scenes = {
      // far and huge: coordinates at 1e8, a sphere of radius 1e8 around them
      R"({"camera": {"position": [1e8, 1e8, -1e8]}, "spheres": [{"center": [1e8, 1e8, 0], "radius": 1e8,
         "color": [255, 255, 255], "specular": 1e8, "reflective": 1}], "lights": [{"type": "point",
         "intensity": 1e29, "position": [-1e8, -1e8, -1e8]}, {"type": "directional", "intensity": 1e29,
         "direction": [0, 1e300, -1e300]}]})",
      // tiny: radius, viewport and projection distance at 1e-8
      R"({"camera": {"viewport": [1e-8, 1e-8], "projection_plane_d": 1e-8}, "epsilon": 0,
         "spheres": [{"center": [0, 0, 3e-8], "radius": 1e-8, "color": [255, 0, 0], "specular": 0,
         "reflective": 0.5}], "lights": [{"type": "point", "intensity": 1, "position": [0, 0, 0]}]})",
      // long rays: viewport 1e8 seen from a projection distance of 1e-8
      R"({"camera": {"viewport": [1e8, 1e8], "projection_plane_d": 1e-8}, "spheres": [{"center": [0, 0, 1e8],
         "radius": 1e8, "color": [9, 9, 9], "specular": 500}], "lights": [{"type": "ambient", "intensity": 1e30}]})"};
  const clrt::DeviceInfo dev = clrt_test::test_device();
  for (const auto& text : scenes) {
    const clrt::Scene s = clrt::parse_scene(text, "edge.json");
    const clrt::Image ref = clrt::render_reference(s, 32, 24, 3);
    for (clrt::Precision p : clrt::all_precisions()) {
      if (p == clrt::Precision::Fp64 && !dev.fp64) continue;
      INFO(text.substr(0, 60) << " / " << clrt::precision_name(p));
      clrt::KernelConfig cfg;
      cfg.precision = p;
      const clrt::Comparison c = clrt::compare_images(clrt_test::render_cl(s, 32, 24, 3, cfg), ref);
      CHECK(c.nan_inf == 0);
      CHECK(c.nan_inf_reference == 0);
    }
  }
}

// ---- 6. cached binaries are untrusted ----------------------------------------

TEST_CASE("a cached binary whose load crashed is never loaded again", "[cli][hardening][cache][opencl]") {
  TempDir cache, out;
  const std::string env = "CLRT_CACHE_DIR=" + clrt_test::shell_quote(cache.path().string());
  const std::string scene = out / "one.json";  // (cold builds: clrt_test::kOneSphereScene says why)
  std::ofstream(scene) << clrt_test::kOneSphereScene;
  const std::vector<std::string> render = {"render", scene, "--width", "16", "--height", "16", "--verbose", "-o"};
  auto run = [&](const std::string& name, const std::string& prefix = "") {
    std::vector<std::string> args = render;
    args.push_back(out / name);
    return run_clrt(args, prefix + env);
  };
  // Stores the entry (PoCL's own cache off for this run only: the later runs
  // load the entry, or build without storing, whatever the driver keeps).
  REQUIRE(run(clrt_test::image_name("a"), std::string(clrt_test::kStoringDriverEnv) + " ").status == 0);
  std::string entry;
  for (const auto& e : cache.entries())
    if (e.size() > 4 && e.substr(e.size() - 4) == ".bin") entry = cache / e;
  REQUIRE_FALSE(entry.empty());

  SECTION("the marker of a load that never finished") {
    // A process that no longer runs left its marker: it crashed while loading.
    pid_t child = ::fork();
    if (child == 0) ::_exit(0);
    ::waitpid(child, nullptr, 0);
    std::ofstream(entry + ".loading") << child << "\n";
    RunResult r = run(clrt_test::image_name("b"));
    INFO(r.err);
    CHECK(r.status == 0);
    CHECK_THAT(r.err, Contains("discarded the cached binary"));
    CHECK(fs::exists(entry + ".bad"));
    CHECK_FALSE(fs::exists(entry + ".loading"));
    // From now on this key is always built from source, never stored.
    RunResult again = run(clrt_test::image_name("c"));
    CHECK(again.status == 0);
    CHECK_THAT(again.err, Contains("built, not stored in the cache"));
    CHECK(clrt_test::slurp(out / clrt_test::image_name("b")) == clrt_test::slurp(out / clrt_test::image_name("a")));
  }
  SECTION("a well-formed entry holding a bad binary") {
    std::string key_text;
    std::vector<unsigned char> binary;
    REQUIRE(clrt::cache_read_entry(entry, key_text, binary));
    std::vector<unsigned char> garbage(binary.size(), 0);
    for (size_t i = 0; i < garbage.size(); ++i) garbage[i] = static_cast<unsigned char>(i * 131 + 7);
    std::copy(binary.begin(), binary.begin() + std::min<size_t>(16, binary.size()),
              garbage.begin());  // keep a plausible header
    REQUIRE(clrt::cache_write_entry(entry, key_text, garbage));
    // The first run may die inside the driver (PoCL asserts); it must not
    // take every later run with it.
    RunResult first = run(clrt_test::image_name("b"));
    INFO("first run: status " << first.status << ": " << first.err);
    RunResult second = run(clrt_test::image_name("c"));
    INFO("second run: " << second.err);
    CHECK(second.status == 0);
    CHECK(clrt_test::slurp(out / clrt_test::image_name("c")) == clrt_test::slurp(out / clrt_test::image_name("a")));
  }
}

TEST_CASE("verbose output says when nothing was stored in the cache", "[cli][hardening][cache][opencl]") {
  TempDir out;
  RunResult r = run_clrt({"render", kDemo, "--width", "8", "--height", "8", "--verbose", "--no-cache", "-o",
                          out / clrt_test::image_name("a")});
  CHECK_THAT(r.err, Contains("built (cache off)"));
  // /proc accepts no new directory or file, even for root.
  RunResult ro =
      run_clrt({"render", kDemo, "--width", "8", "--height", "8", "--verbose", "-o", out / clrt_test::image_name("b")},
               "CLRT_CACHE_DIR=/proc/clrt-cache");
  INFO(ro.err);
  CHECK(ro.status == 0);
  CHECK_THAT(ro.err, Contains("built, not stored in the cache"));
  CHECK_THAT(ro.err, !Contains("built, stored in cache"));
}

TEST_CASE("an unusable XDG_CACHE_HOME is named, not reported as a missing device", "[cli][hardening][opencl]") {
  TempDir dir;
  const std::string file = dir.write("not-a-dir", "x");
  RunResult r = run_clrt({"devices"}, "XDG_CACHE_HOME=" + clrt_test::shell_quote(file));
  if (r.status == 0) {
    WARN("this OpenCL driver starts without a cache directory; nothing to diagnose");
    return;
  }
  check_error(r, {"XDG_CACHE_HOME=" + file});
}

// ---- 7. specialization stays bounded ------------------------------------------

TEST_CASE("large scenes are specialized without unrolling their loops", "[hardening][specialize]") {
  clrt::Scene s;
  s.spheres.resize(clrt::kMaxUnrolledSpheres);
  s.lights.resize(3);
  clrt::KernelConfig cfg;
  CHECK_THAT(clrt::build_options(cfg, s, 3, true), Contains("-DCLRT_N_SPHERES=16"));
  s.spheres.resize(clrt::kMaxUnrolledSpheres + 1);
  CHECK_THAT(clrt::build_options(cfg, s, 3, true), !Contains("CLRT_N_SPHERES") && Contains("-DCLRT_SPECIALIZED"));
  s.spheres.resize(4);
  s.lights.resize(clrt::kMaxUnrolledLights + 1);
  CHECK_THAT(clrt::build_options(cfg, s, 3, true), !Contains("CLRT_N_LIGHTS") && !Contains("CLRT_LIGHT_TYPES"));
}

TEST_CASE("100,000 ambient lights render (before: 330 s of build and first launch)", "[cli][hardening][opencl]") {
  TempDir dir;
  std::string text = R"({"spheres": [{"center": [0, 0, 3], "radius": 1, "color": [255, 0, 0]}], "lights": [)";
  for (int i = 0; i < 100000; ++i) text += std::string(i ? "," : "") + R"({"type": "ambient", "intensity": 1e-5})";
  text += "]}";
  const std::string scene = dir.write("many.json", text);
  RunResult r = run_clrt({"compare", scene, "--width", "8", "--height", "8", "--fail-percent", "0"});
  INFO(r.out << r.err);
  CHECK(r.status == 0);
}

// ---- 8. outputs that are not regular files -----------------------------------

TEST_CASE("symlinks, devices, FIFOs and '-' are written to, not replaced", "[cli][hardening][opencl]") {
  TempDir dir;
  SECTION("a symlink OUT writes its target and stays a link") {
    fs::create_symlink(clrt_test::image_name("target"), dir / clrt_test::image_name("link"));
    RunResult r =
        run_clrt({"render", kDemo, "-o", dir / clrt_test::image_name("link"), "--width", "8", "--height", "8"});
    INFO(r.err);
    REQUIRE(r.status == 0);
    CHECK(fs::is_symlink(fs::symlink_status(dir / clrt_test::image_name("link"))));
    CHECK(fs::is_regular_file(dir / clrt_test::image_name("target")));
  }
  SECTION("a character device stays a device") {
    RunResult r = run_clrt({"render", kDemo, "-o", "/dev/null", "--width", "8", "--height", "8"});
    INFO(r.err);
    CHECK(r.status == 0);
    CHECK(fs::is_character_file("/dev/null"));
    RunResult csv = run_clrt(
        {"sweep", kDemo, "--depths", "0", "--width", "8", "--height", "8", "--repeat", "1", "--csv", "/dev/null"});
    CHECK(csv.status == 0);
    CHECK(fs::is_character_file("/dev/null"));
  }
  SECTION("'-' is PNG (a lean build: PPM) on standard output, the report on stderr") {
    RunResult r = run_clrt({"render", kDemo, "-o", "-", "--width", "8", "--height", "8"});
    INFO(r.err);
    REQUIRE(r.status == 0);
    REQUIRE(r.out.size() > 8);
    CHECK(clrt_test::starts_as_image(r.out));
    CHECK_THAT(r.err, Contains("8x8 depth 3"));
  }
  SECTION("a FIFO is written in place") {
    const std::string fifo = dir / "pipe.ppm";
    REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);
    std::string got;
    std::thread reader([&] { got = clrt_test::slurp(fifo); });
    RunResult r = run_clrt({"render", kDemo, "-o", fifo, "--width", "8", "--height", "8"});
    reader.join();
    INFO(r.err);
    CHECK(r.status == 0);
    CHECK(got.rfind("P6", 0) == 0);  // a PPM went through the pipe
    CHECK(fs::is_fifo(fifo));
  }
}

// ---- 9. signals ---------------------------------------------------------------

TEST_CASE("a signal removes the scratch files and exits 128 + signal", "[hardening]") {
  int fds[2];
  REQUIRE(::pipe(fds) == 0);
  pid_t child = ::fork();
  if (child == 0) {
    clrt::install_signal_cleanup();
    clrt::ScratchFile scratch("out.sgi");
    std::ofstream(scratch.path()) << "partial";
    const std::string p = scratch.path() + "\n";
    if (::write(fds[1], p.data(), p.size()) < 0) ::_exit(99);
    ::raise(SIGTERM);
    ::_exit(98);  // not reached
  }
  ::close(fds[1]);
  char buf[4096] = {0};
  ssize_t n = ::read(fds[0], buf, sizeof buf - 1);
  ::close(fds[0]);
  int status = 0;
  ::waitpid(child, &status, 0);
  REQUIRE(n > 0);
  const std::string path(buf, size_t(n) - 1);
  CHECK(WIFEXITED(status));
  CHECK(WEXITSTATUS(status) == 143);
  CHECK_FALSE(fs::exists(path));
  CHECK_FALSE(fs::exists(fs::path(path).parent_path()));
}

// Waits (up to 60 s) until process `pid` runs the clrt binary and catches
// `sig` (/proc/PID/status: Name, SigCgt): a signal sent before it has its
// handler would end it the default way. Loading its libraries can take over
// a second on a loaded machine, so a fixed sleep is not enough.
static bool wait_for_handler(pid_t pid, int sig) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (std::chrono::steady_clock::now() < deadline) {
    std::ifstream status("/proc/" + std::to_string(pid) + "/status");
    std::string line, name;
    unsigned long long caught = 0;
    while (std::getline(status, line)) {
      if (line.rfind("Name:", 0) == 0) name = line.substr(line.find_first_not_of(" \t", 5));
      if (line.rfind("SigCgt:", 0) == 0) caught = std::stoull(line.substr(7), nullptr, 16);
    }
    if (name == "clrt" && (caught >> (sig - 1) & 1)) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  return false;
}

TEST_CASE("SIGINT during a render: exit 130, one line, nothing written", "[cli][hardening][opencl]") {
  TempDir dir;
  const std::string out = dir / clrt_test::image_name("out");
  // The reference engine at 4096x4096 takes seconds: interrupt it.
  const std::string cmd = clrt_test::shell_quote(CLRT_BINARY) + " render " + clrt_test::shell_quote(kDemo) +
                          " --engine reference --width 4096 --height 4096 -o " + clrt_test::shell_quote(out) + " 2>" +
                          clrt_test::shell_quote(dir / "err.txt");
  pid_t child = ::fork();
  if (child == 0) {
    ::execl("/bin/sh", "sh", "-c", ("exec " + cmd).c_str(), static_cast<char*>(nullptr));
    ::_exit(127);
  }
  const bool ready = wait_for_handler(child, SIGINT);
  // then into the render (the reference at 4096x4096 takes seconds)
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  ::kill(child, SIGINT);
  int status = 0;
  ::waitpid(child, &status, 0);
  REQUIRE(ready);
  REQUIRE(WIFEXITED(status));
  CHECK(WEXITSTATUS(status) == 130);
  CHECK(clrt_test::slurp(dir / "err.txt") == "clrt: error: interrupted by SIGINT\n");
  CHECK(dir.entries() == std::vector<std::string>{"err.txt"});
}

// ---- 10. user input that used to reach the "bug" exit status -----------------

TEST_CASE("odd user input is bad input (exit 2), never an internal error", "[cli][hardening][opencl]") {
  TempDir dir;
  const std::string out = dir / clrt_test::image_name("out");
  check_error(run_clrt({"render", kDemo, "-o", out, "--device", "99999999999999999999999"}), {"unknown device"});
  // A NUL byte: nothing after it may be ignored.
  check_error(run_clrt({"render", dir.write("nul.json", std::string("{\"spheres\": []}\0{\"x\":1}", 24)), "-o", out}),
              {"NUL byte at offset 15"});
  // Duplicate keys, at any depth.
  check_error(run_clrt({"render", dir.write("dup.json", R"({"epsilon": 0.1, "epsilon": 0.2})"), "-o", out}),
              {"duplicate key \"epsilon\""});
  check_error(
      run_clrt({"render", dir.write("dup2.json", R"({"spheres": [{"center": [0,0,3], "center": [0,0,4], "radius": 1,
                                                    "color": [1,1,1]}]})"),
                "-o", out}),
      {"duplicate key \"center\""});
  // A huge unknown key is echoed cut short.
  RunResult big = run_clrt({"render", dir.write("big.json", "{\"" + std::string(100000, 'k') + "\": 1}"), "-o", out});
  check_error(big, {"... (100000 bytes)"});
  CHECK(big.err.size() < 400);
  CHECK_FALSE(fs::exists(out));
  // --json with a scene path that is not UTF-8: replacement characters, exit 0.
  const std::string odd = dir / "sc\xff\xfe.json";
  fs::copy_file(kDemo, odd);
  RunResult j = run_clrt({"compare", odd, "--width", "8", "--height", "8", "--json"});
  INFO(j.err);
  CHECK(j.status == 0);
  CHECK_NOTHROW(nlohmann::json::parse(j.out));
  // A plot path that cannot be written fails before the work, both plots.
  check_error(run_clrt({"sweep", kDemo, "--depths", "0:1", "--width", "8", "--height", "8", "--plot",
                        dir / "no/such/dir/p.png"}),
              {"does not exist"});
}

TEST_CASE("another user's file in a sticky directory fails before the work", "[cli][hardening]") {
  // rename() may not replace another user's file in a sticky directory such
  // as /tmp; that used to surface only after the render. Needs root to act
  // as a second user (CI runs as root).
  if (::geteuid() != 0) {
    WARN("not root: cannot act as a second user; skipped");
    return;
  }
  TempDir dir;
  const std::string sticky = dir / "sticky";
  fs::create_directory(sticky);
  ::chmod(dir.path().c_str(), 0755);
  ::chmod(sticky.c_str(), 01777);
  const std::string out = sticky + clrt_test::image_name("/out");
  std::ofstream(out) << "root's file";
  const std::string err = dir / "err.txt";
  pid_t child = ::fork();
  if (child == 0) {
    const int fd = ::open(err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (fd < 0) ::_exit(96);
    ::dup2(fd, STDERR_FILENO);
    if (::setgid(65534) != 0 || ::setuid(65534) != 0) ::_exit(97);  // nobody
    ::execl(CLRT_BINARY, CLRT_BINARY, "render", kDemo.c_str(), "-o", out.c_str(), static_cast<char*>(nullptr));
    ::_exit(127);
  }
  int status = 0;
  ::waitpid(child, &status, 0);
  REQUIRE(WIFEXITED(status));
  if (WEXITSTATUS(status) >= 96) {
    WARN("could not run clrt as nobody (status " << WEXITSTATUS(status) << "); skipped");
    return;
  }
  CHECK(WEXITSTATUS(status) == 2);
  CHECK_THAT(clrt_test::slurp(err),
             Contains(out + ": cannot write output: it belongs to another user in the sticky directory"));
  CHECK(clrt_test::slurp(out) == "root's file");
  CHECK(entries(sticky) == std::vector<std::string>{clrt_test::image_name("out")});
}

TEST_CASE("image headers are checked: a PPM maxval of 0 or over 65535, a PFM scale of NaN, infinity or 0",
          "[cli][hardening]") {
  // Before, OpenImageIO read such files: a maxval of 0 as a white image, a
  // NaN scale into NaN pixels; compare then gave a verdict on them.
  TempDir dir;
  const std::string demo = source_path("scenes/cgfs-demo.json");
  const std::string rgb(2 * 2 * 3, '\x10'), floats(2 * 2 * 3 * 4, '\0');
  const std::vector<std::pair<std::string, std::string>> files = {
      {"zero.ppm", "P6\n2 2\n0\n" + rgb},           {"huge.ppm", "P6\n2 2\n65536\n" + rgb},
      {"ascii.ppm", "P3\n2 2\n0\n" + std::string(12 * 2, ' ')}, {"nan.pfm", "PF\n2 2\nnan\n" + floats},
      {"inf.pfm", "PF\n2 2\n-inf\n" + floats},      {"zero.pfm", "PF\n2 2\n0.0\n" + floats},
  };
  for (const auto& [name, bytes] : files) {
    const std::string path = dir.write(name, bytes);
    const RunResult r = run_clrt({"compare", demo, "--image", path, "--fail-percent", "100"});
    INFO(name << ": " << r.out << r.err);
    CHECK(r.status == 2);
    CHECK_THAT(r.err, StartsWith("clrt: error: " + path + ": cannot read image: bad "));
    CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
  }
  // The same headers with sane values are read.
  const std::string good = dir.write("good.pfm", "PF\n2 2\n-1.0\n" + floats);
  CHECK(run_clrt({"compare", demo, "--image", good, "--fail-percent", "100"}).status == 0);
}

TEST_CASE("running out of memory is one clear line naming what did not fit, exit 2", "[cli][hardening]") {
#if defined(__SANITIZE_ADDRESS__)
  SUCCEED("AddressSanitizer reserves terabytes of address space: no address-space limit under it");
#else
  // Before: "clrt: internal error: std::bad_alloc", exit 3. A 1 GB address
  // space cannot hold the reference's 8000x8000 image (1.5 GB of doubles).
  TempDir dir;
  const std::string out = dir / clrt_test::image_name("big");
  const RunResult r = clrt_test::run_command_line(
      "ulimit -v 1000000 && " +
      clrt_test::clrt_command({"render", source_path("scenes/cgfs-demo.json"), "--engine", "reference", "--width",
                               "8000", "--height", "8000", "-o", out}));
  INFO(r.out << r.err);
  CHECK(r.status == 2);
  CHECK(r.err == "clrt: error: out of memory while rendering 8000x8000 with the reference\n");
  CHECK_FALSE(std::filesystem::exists(out));
#endif
}

TEST_CASE("a copied clrt never loads the imaging module from the build folder or a planted one", "[cli][hardening]") {
  namespace fs = std::filesystem;
  TempDir dir;
  // Beside nothing: the build folder's module (compiled in as a path) is not
  // a candidate for a binary outside that folder.
  fs::create_directories(dir.path() / "alone");
  const std::string alone = dir / "alone/clrt";
  fs::copy_file(CLRT_BINARY, alone);
  const std::string demo = source_path("scenes/cgfs-demo.json");
  const std::string build_module = (fs::path(CLRT_BINARY).parent_path() / "clrt_imageio.so").string();
  if (!fs::exists(build_module)) {
    SUCCEED("a lean build has no imaging module");
    return;
  }
  RunResult r = clrt_test::run_command_line(clrt_test::shell_quote(alone) + " render " + clrt_test::shell_quote(demo) +
                                            " --engine reference --width 8 --height 8 -o " +
                                            clrt_test::shell_quote(dir / "a.png"));
  INFO(r.err);
  CHECK(r.status == 2);
  CHECK_THAT(r.err, Contains("was not found"));
  CHECK_THAT(r.err, !Contains(build_module));
  // The installed layout (bin/clrt, lib/clrt/clrt_imageio.so) works - unless
  // others may write the module's folder.
  fs::create_directories(dir.path() / "prefix/bin");
  fs::create_directories(dir.path() / "prefix/lib/clrt");
  const std::string installed = dir / "prefix/bin/clrt";
  fs::copy_file(CLRT_BINARY, installed);
  fs::copy_file(build_module, dir / "prefix/lib/clrt/clrt_imageio.so");
  const std::string render = clrt_test::shell_quote(installed) + " render " + clrt_test::shell_quote(demo) +
                             " --engine reference --width 8 --height 8 -o " + clrt_test::shell_quote(dir / "b.png");
  r = clrt_test::run_command_line(render);
  INFO(r.err);
  CHECK(r.status == 0);
  REQUIRE(::chmod((dir / "prefix/lib/clrt").c_str(), 0777) == 0);
  r = clrt_test::run_command_line(render);
  CHECK(r.status == 2);
  CHECK_THAT(r.err, Contains("may be written by others"));
}

TEST_CASE("with --csv - standard output holds the CSV alone, and two outputs that are one file are refused",
          "[cli][hardening][opencl]") {
  namespace fs = std::filesystem;
  TempDir dir;
  const std::string demo = source_path("scenes/cgfs-demo.json");
  const std::vector<std::string> small = {"--width", "8", "--height", "8", "--repeat", "1"};
  auto with = [&](std::vector<std::string> a, const std::vector<std::string>& b) {
    a.insert(a.end(), b.begin(), b.end());
    return a;
  };
  // Every line of standard output is a CSV row of the header's width.
  auto only_csv = [](const std::string& out) {
    std::istringstream in(out);
    std::string line, header;
    std::getline(in, header);
    const auto commas = std::count(header.begin(), header.end(), ',');
    bool ok = commas > 0;
    while (std::getline(in, line)) ok = ok && std::count(line.begin(), line.end(), ',') == commas;
    return ok;
  };
  RunResult r = run_clrt(with({"sweep", demo, "--depths", "0:1", "--csv", "-"}, small));
  INFO(r.out << r.err);
  CHECK(r.status == 0);
  CHECK(only_csv(r.out));
  CHECK_THAT(r.err, Contains("depth"));  // the table went to standard error
  r = run_clrt(with({"scaling", "--spheres", "40", "--no-embree", "--csv", "-"}, small));
  CHECK(r.status == 0);
  CHECK(only_csv(r.out));

  // The same file twice, directly or through a link: refused before any work.
  if (!clrt::kLeanBuild) {  // (a lean build has no plots)
    const std::string y = dir / "y.svg";
    r = run_clrt(with({"sweep", demo, "--depths", "0:1", "--plot", y, "--csv", y}, small));
    CHECK(r.status == 2);
    CHECK_THAT(r.err, StartsWith("clrt: error: ") && Contains("are the same file"));
    CHECK_FALSE(fs::exists(y));
  }
  r = run_clrt(with({"sweep", demo, "--depths", "0:1", "--csv", "-", "--json"}, small));
  CHECK(r.status == 2);
  CHECK_THAT(r.err, Contains("standard output"));
  fs::create_symlink(clrt_test::image_name("f_0"), dir / clrt_test::image_name("f_1"));
  r = run_clrt({"render", demo, demo, "--width", "8", "--height", "8", "-o", dir / clrt_test::image_name("f_#")});
  INFO(r.err);
  CHECK(r.status == 2);
  CHECK_THAT(r.err, Contains("frame 1 and the frame 0"));
  CHECK_FALSE(fs::exists(dir / clrt_test::image_name("f_0")));
  const std::string image = dir / "image.ppm";
  REQUIRE(run_clrt({"render", demo, "--width", "8", "--height", "8", "-o", image}).status == 0);
  const std::string before = clrt_test::slurp(image);
  r = run_clrt({"compare", demo, "--image", image, "--diff", image});
  CHECK(r.status == 2);
  CHECK(clrt_test::slurp(image) == before);
}

TEST_CASE("a scene whose ray tree may take hours says so before the work", "[cli][hardening]") {
  // Two transparent, reflective shells: every hit both reflects and
  // refracts, 2^(depth+1) - 1 rays per camera ray at most.
  TempDir dir;
  const std::string shells = dir.write("shells.json", R"({"spheres": [
      {"center": [0, 0, 4], "radius": 1, "color": [200, 200, 255], "reflective": 0.3, "transparency": 0.7,
       "refractive_index": 1.5},
      {"center": [0, 0, 4], "radius": 2, "color": [200, 255, 200], "reflective": 0.3, "transparency": 0.7,
       "refractive_index": 1.3}],
    "lights": [{"type": "ambient", "intensity": 1}]})");
  const clrt::Scene s = clrt::load_scene(shells);
  CHECK(clrt::worst_rays_per_camera_ray(s, 3) == 15);
  CHECK(clrt::worst_rays_per_camera_ray(s, 30, /*cut=*/false) == std::ldexp(1.0, 31) - 1);
  // The weight cut-off (scene/ray_tree.hpp) bounds every level at
  // min_weight^-alpha rays (here ~5e7): 2^26 - 1 rays down to level 25,
  // then at most that many a level.
  const clrt::RayCut cut = clrt::ray_cut(s);
  const double per_level = std::floor(std::pow(double(cut.min_weight), -cut.exponent));
  CHECK(per_level < std::ldexp(1.0, 26));
  CHECK(per_level > std::ldexp(1.0, 25));
  CHECK(clrt::worst_rays_per_camera_ray(s, 30) == std::ldexp(1.0, 26) - 1 + 5 * per_level);
  CHECK(clrt::worst_rays_per_camera_ray(s, 64) == std::ldexp(1.0, 26) - 1 + 39 * per_level);
  CHECK(clrt::ray_tree_warning(s, 3, 600, 600, 1).empty());
  CHECK_FALSE(clrt::ray_tree_warning(s, 30, 600, 600, 1).empty());
  // The book's demo: reflection only, depth + 1 rays.
  CHECK(clrt::worst_rays_per_camera_ray(clrt::load_scene(source_path("scenes/cgfs-demo.json")), 3) == 4);
  // The warning comes before any work. (Here the one camera ray misses the
  // shells, so the frame itself ends at once.)
  const std::string aside = dir.write("aside.json", R"({"spheres": [
      {"center": [0, 100, 4], "radius": 1, "color": [200, 200, 255], "reflective": 0.3, "transparency": 0.7}],
    "lights": [{"type": "ambient", "intensity": 1}]})");
  RunResult r = run_clrt({"render", aside, "--engine", "reference", "--depth", "40", "--width", "1", "--height",
                          "1", "--no-ray-cut", "-o", dir / clrt_test::image_name("s")});
  INFO(r.err);
  CHECK(r.status == 0);
  CHECK_THAT(r.err, Contains("clrt: warning: " + aside + ": a camera ray may branch into up to 2.2e+12 rays"));
  // With the cut: at most 2^26 - 1 + 15 x 5.15e7 = 8.39e8 rays a camera ray.
  r = run_clrt({"render", aside, "--engine", "reference", "--depth", "40", "--width", "1000", "--height", "1000",
                "-o", dir / clrt_test::image_name("s")});
  CHECK(r.status == 0);
  CHECK_THAT(r.err, Contains("clrt: warning: " + aside + ": a camera ray may branch into up to 8.39e+08 rays"));
}

TEST_CASE("a frame over the ray budget is refused before the work", "[cli][hardening][ray-cut]") {
  // A fully transparent, half-reflective sphere passes all of its light on
  // to two rays: no cut-off can be honest there, and at depth 64 a camera
  // ray that stays inside may take 2^65 - 1 rays. Such a frame would never
  // end; it is refused with one error line, before any file is made.
  TempDir dir;
  const std::string lossless = dir.write("lossless.json", R"({"spheres": [
      {"center": [0, 0, 4], "radius": 1, "color": [200, 200, 255], "reflective": 0.5, "transparency": 1,
       "refractive_index": 1.5}],
    "lights": [{"type": "ambient", "intensity": 1}]})");
  const std::string out = dir / clrt_test::image_name("x");
  RunResult r = run_clrt({"render", lossless, "--depth", "64", "--width", "8", "--height", "8", "-o", out});
  INFO(r.err);
  CHECK(r.status == 2);
  CHECK(r.one_line_error());
  CHECK_THAT(r.err, Contains("up to 3.69e+19 rays at depth 64 (a surface passes all of its light on to two rays"));
  CHECK_THAT(r.err, Contains("over the ray budget of 1e+18 (--ray-budget)"));
  r = run_clrt({"compare", lossless, "--depth", "64", "--width", "8", "--height", "8"});
  CHECK(r.status == 2);
  CHECK(r.one_line_error());
  // A sweep is checked at its deepest depth.
  r = run_clrt({"sweep", lossless, "--depths", "0:64", "--width", "8", "--height", "8"});
  CHECK(r.status == 2);
  CHECK(r.one_line_error());
  CHECK_THAT(r.err, Contains("at depth 64"));
  // A scene whose surfaces keep some light is bounded by the cut at any
  // depth: the shells of the test above are not refused at depth 64.
  const std::string shells = dir.write("shells.json", R"({"spheres": [
      {"center": [0, 100, 4], "radius": 1, "color": [200, 200, 255], "reflective": 0.3, "transparency": 0.7}],
    "lights": [{"type": "ambient", "intensity": 1}]})");
  r = run_clrt({"render", shells, "--depth", "64", "--width", "8", "--height", "8", "-o", out});
  CHECK(r.status == 0);
  CHECK(dir.entries().size() == 3);
}

}  // namespace test_hardening
