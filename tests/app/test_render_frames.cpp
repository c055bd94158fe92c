// test_render_frames.cpp - `clrt render A.json B.json ... -o frame_####.png`:
// the output pattern, several scenes in one process giving the pixels of
// separate renders, and the refusals (exit 2, one line, no file).
#include <catch2/catch.hpp>
#include <filesystem>
#include <regex>

#include "cli_run.hpp"
#include "image/image_file.hpp"
#include "test_util.hpp"
#include "util/error.hpp"
#include "util/frame_pattern.hpp"

// (clrt_tests is a unity build: each file's code is in a namespace of its own.)
namespace test_render_frames {

using Catch::Matchers::Contains;
using Catch::Matchers::StartsWith;
using clrt_test::run_clrt;
using clrt_test::RunResult;
using clrt_test::TempDir;
namespace fs = std::filesystem;

namespace {

// Square: the scenes' viewports are, so no warning joins the report.
const std::vector<std::string> kSize = {"--width", "40", "--height", "40"};

std::vector<std::string> scenes() {
  return {clrt_test::source_path("scenes/cgfs-demo.json"), clrt_test::source_path("scenes/glass.json"),
          clrt_test::source_path("scenes/cgfs-camera.json")};
}

RunResult render(std::vector<std::string> args, const std::vector<std::string>& size = kSize) {
  args.insert(args.begin(), "render");
  args.insert(args.end(), size.begin(), size.end());
  return run_clrt(args);
}

void check_error(const RunResult& r, const std::string& needle) {
  INFO("stdout: " << r.out << "\nstderr: " << r.err);
  CHECK(r.status == 2);
  CHECK(r.one_line_error());
  CHECK_THAT(r.err, StartsWith("clrt: error: "));
  CHECK_THAT(r.err, Contains(needle));
}

// The 8-bit pixels of an image file.
std::vector<uint8_t> pixels(const std::string& path) {
  return clrt::to_u8(clrt::read_image(path, 1 << 14, 1LL << 26));
}

}  // namespace

TEST_CASE("frame patterns: a run of '#' is the zero-padded frame number", "[frames]") {
  using clrt::frame_paths;
  CHECK(frame_paths("frame_####.png", 3) ==
        std::vector<std::string>{"frame_0000.png", "frame_0001.png", "frame_0002.png"});
  CHECK(frame_paths("d/f_#.ppm", 2) == std::vector<std::string>{"d/f_0.ppm", "d/f_1.ppm"});
  CHECK(frame_paths("#.exr", 1) == std::vector<std::string>{"0.exr"});
  // More digits where the index needs them (the names stay distinct).
  const auto many = frame_paths("f_##.png", 101);
  CHECK(many[9] == "f_09.png");
  CHECK(many[99] == "f_99.png");
  CHECK(many[100] == "f_100.png");
  CHECK(clrt::frame_path(clrt::parse_frame_pattern("out/f_###.pfm"), 12345) == "out/f_12345.pfm");
  // One scene: OUT itself without a run, its frame 0 with one.
  CHECK(frame_paths("out.png", 1) == std::vector<std::string>{"out.png"});
  CHECK(frame_paths("out_##.png", 1) == std::vector<std::string>{"out_00.png"});
  CHECK(frame_paths("-", 1) == std::vector<std::string>{"-"});
  // Only the file name holds the run: a '#' in a directory is a character.
  CHECK(frame_paths("a#b/f_#.png", 2) == std::vector<std::string>{"a#b/f_0.png", "a#b/f_1.png"});
  CHECK(frame_paths("a#b/f.png", 1) == std::vector<std::string>{"a#b/f.png"});
  CHECK_THROWS_AS(frame_paths("a#b/f.png", 2), clrt::UserError);
  // Several scenes need a run; one run only.
  CHECK_THROWS_WITH(frame_paths("out.png", 2), Contains("out.png: 2 scenes need an output pattern"));
  CHECK_THROWS_WITH(frame_paths("-", 3), Contains("run of '#'"));
  CHECK_THROWS_WITH(frame_paths("f_#_#.png", 2), Contains("more than one run of '#'"));
  CHECK_THROWS_AS(frame_paths("f_##x##.png", 1), clrt::UserError);
}

TEST_CASE("several scenes in one process: the pixels of separate renders, one line each and a total",
          "[frames][cli][opencl][slow]") {
  TempDir dir;
  const auto list = scenes();
  for (const std::string ext : {"ppm", "pfm"}) {
    INFO("format " << ext);
    std::vector<std::string> args = list;
    args.insert(args.end(), {"-o", dir / ("f_##." + ext)});
    const RunResult r = render(args);
    INFO("stdout: " << r.out << "\nstderr: " << r.err);
    REQUIRE(r.status == 0);
    CHECK(r.err.empty());
    for (size_t i = 0; i < list.size(); ++i) {
      const std::string frame = dir / ("f_0" + std::to_string(i) + "." + ext);
      CHECK_THAT(r.out, Contains(frame + ": " + list[i] + ", 40x40 depth "));
      const std::string single = dir / ("single." + ext);
      const RunResult one = render({list[i], "-o", single});
      REQUIRE(one.status == 0);
      if (ext == "ppm") {
        CHECK(pixels(frame) == pixels(single));
      } else {
        const clrt::Image a = clrt::read_image(frame, 1 << 14, 1LL << 26);
        const clrt::Image b = clrt::read_image(single, 1 << 14, 1LL << 26);
        CHECK(a.rgb == b.rgb);
      }
      // Each frame's metadata names its own scene.
      if (ext == "ppm") CHECK_THAT(clrt_test::slurp(frame), Contains("# clrt:scene=" + list[i] + "\n"));
      fs::remove(single);
    }
    CHECK(std::regex_search(r.out, std::regex("3 frames, 40x40: [0-9.]+ ms \\(scenes loaded in [0-9.]+ ms\\), frame "
                                              "time median [0-9.]+ ms, mean [0-9.]+ ± [0-9.]+")));
  }
  CHECK(dir.entries() ==
        std::vector<std::string>{"f_00.pfm", "f_00.ppm", "f_01.pfm", "f_01.ppm", "f_02.pfm", "f_02.ppm"});
}

TEST_CASE("several scenes with the reference engine, and one scene to a pattern", "[frames][cli]") {
  TempDir dir;
  const auto list = scenes();
  const std::vector<std::string> small = {"--width", "12", "--height", "12"};
  RunResult r = render({list[0], list[1], "-o", dir / "r_#.ppm", "--engine", "reference"}, small);
  INFO("stdout: " << r.out << "\nstderr: " << r.err);
  REQUIRE(r.status == 0);
  CHECK_THAT(r.out, Contains("with the reference renderer"));
  CHECK_THAT(r.out, Contains("2 frames, 12x12: "));
  // One scene and a pattern: frame 0's name, the single-frame report.
  r = render({list[2], "-o", dir / "one_###.ppm", "--engine", "reference"}, small);
  REQUIRE(r.status == 0);
  CHECK_THAT(r.out, StartsWith(dir / "one_000.ppm" + ": 12x12 depth "));
  CHECK(dir.entries() == std::vector<std::string>{"one_000.ppm", "r_0.ppm", "r_1.ppm"});
}

TEST_CASE("several scenes: bad input is refused before any frame, and no file is written", "[frames][cli]") {
  TempDir dir;
  const auto list = scenes();
  auto with = [&](std::vector<std::string> args) {
    std::vector<std::string> all = list;
    all.insert(all.end(), args.begin(), args.end());
    return render(all);
  };
  SECTION("a pattern without '#'") {
    check_error(with({"-o", dir / "out.png"}), dir / "out.png" + ": 3 scenes need an output pattern");
  }
  SECTION("standard output") {
    check_error(with({"-o", "-"}), "-: 3 scenes need an output pattern");
  }
  SECTION("two runs of '#'") {
    check_error(with({"-o", dir / "f_#_#.ppm"}), "more than one run of '#'");
  }
  SECTION("a directory that does not exist") {
    const std::string out = dir / "nodir/f_#.ppm";
    check_error(with({"-o", out}), dir / "nodir/f_0.ppm" + ": cannot write output: directory " + (dir / "nodir"));
  }
  SECTION("an unwritable directory") {
    check_error(with({"-o", "/proc/clrt-test-f_#.ppm"}), "/proc/clrt-test-f_0.ppm: cannot write output");
    CHECK_FALSE(fs::exists("/proc/clrt-test-f_0.ppm"));
  }
  SECTION("one frame's name is a directory: checked before the first frame") {
    fs::create_directory(dir / "f_2.ppm");
    check_error(with({"-o", dir / "f_#.ppm"}), dir / "f_2.ppm" + ": cannot write output: it is a directory");
    CHECK(fs::is_empty(dir / "f_2.ppm"));
    fs::remove(dir / "f_2.ppm");
  }
  SECTION("an unknown format") {
    check_error(with({"-o", dir / "f_#.xyz"}), dir / "f_0.xyz" + ": unknown image format");
  }
  SECTION("a bad scene after good ones: every scene is read before the first frame") {
    const std::string bad = dir.write("bad.json", R"({"spheres": [)");
    std::vector<std::string> args = list;
    args.insert(args.end(), {bad, "-o", dir / "f_#.ppm"});
    check_error(render(args), bad + ": ");
    fs::remove(bad);
  }
  SECTION("a missing scene") {
    std::vector<std::string> args = {list[0], dir / "missing.json", "-o", dir / "f_#.ppm"};
    check_error(render(args), dir / "missing.json");
  }
  CHECK(dir.entries().empty());
}

}  // namespace test_render_frames
