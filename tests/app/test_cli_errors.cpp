// test_cli_errors.cpp - every bad input to the clrt binary: exit status 2, one
// line on stderr naming the file and the problem, and no output file.
#include <catch2/catch.hpp>
#include <filesystem>
#include <sstream>

#include "cli_run.hpp"
#include "test_util.hpp"

// (clrt_tests is a unity build: each file's code is in a namespace of its own.)
namespace test_cli_errors {

using Catch::Matchers::Contains;
using Catch::Matchers::StartsWith;
using clrt_test::run_clrt;
using clrt_test::RunResult;
using clrt_test::TempDir;
namespace fs = std::filesystem;

namespace {

const char* kSphere = R"({"center": [0, 0, 3], "radius": 1, "color": [255, 0, 0]})";

std::string scene_with_sphere(const std::string& sphere) {
  return R"({"spheres": [)" + sphere + "]}";
}
std::string scene_with_light(const std::string& light) {
  return R"({"spheres": [)" + std::string(kSphere) + R"(], "lights": [)" + light + "]}";
}

// A failed run: status 2, exactly one stderr line "clrt: error: ..." that
// contains every string in `needles`.
void check_error(const RunResult& r, std::initializer_list<std::string> needles) {
  INFO("stderr: " << r.err);
  CHECK(r.status == 2);
  CHECK(r.one_line_error());
  CHECK_THAT(r.err, StartsWith("clrt: error: "));
  for (const auto& n : needles) CHECK_THAT(r.err, Contains(n));
}

// Renders `scene_text` (written to bad.json) and expects the error `problem`
// naming bad.json, with no out.png left behind.
void check_bad_scene(const std::string& scene_text, const std::string& problem) {
  TempDir dir;
  std::string scene = dir.write("bad.json", scene_text);
  std::string out = dir / clrt_test::image_name("out");
  check_error(run_clrt({"render", scene, "-o", out, "--width", "16", "--height", "16"}), {scene + ": ", problem});
  CHECK_FALSE(fs::exists(out));
  CHECK(dir.entries() == std::vector<std::string>{"bad.json"});
}

// Renders the demo scene with `extra` options into `out` and expects `needles`.
void check_bad_render(const std::vector<std::string>& extra, const std::string& out,
                      std::initializer_list<std::string> needles) {
  std::vector<std::string> args = {"render", clrt_test::source_path("scenes/cgfs-demo.json"), "-o", out};
  args.insert(args.end(), extra.begin(), extra.end());
  check_error(run_clrt(args), needles);
}

}  // namespace

TEST_CASE("bad scene files: message names the file and the problem, no output", "[cli]") {
  SECTION("malformed JSON") {
    check_bad_scene(R"({"spheres": [)", "malformed JSON");
  }
  SECTION("empty file") {
    check_bad_scene("", "malformed JSON");
  }
  SECTION("NaN and Infinity are not JSON") {
    check_bad_scene(R"({"epsilon": NaN})", "malformed JSON");
    check_bad_scene(R"({"epsilon": Infinity})", "malformed JSON");
  }
  SECTION("unknown key") {
    check_bad_scene(R"({"spherez": []})", "unknown key \"spherez\"");
  }
  SECTION("wrong type") {
    check_bad_scene(scene_with_sphere(R"({"center": [0, 0, 3], "radius": "1", "color": [1, 2, 3]})"),
                    "spheres[0].radius: expected a number, got string");
    check_bad_scene(R"({"spheres": {}})", "spheres: expected an array, got object");
  }
  SECTION("overflowing numbers") {
    check_bad_scene(R"({"epsilon": 1e400})", "number out of range");
    check_bad_scene(R"({"recursion_depth": 18446744073709551615})",
                    "recursion_depth: must be in [0, 64] (got 18446744073709551615)");
    check_bad_scene(scene_with_light(R"({"type": "point", "intensity": 1, "position": [0, 0, -1e39]})"),
                    "lights[0].position[2]: must be within ±1e+08, the range clrt renders in float32 (got -1e+39)");
  }
  SECTION("negative or zero radius") {
    check_bad_scene(scene_with_sphere(R"({"center": [0, 0, 3], "radius": -1, "color": [1, 2, 3]})"),
                    "spheres[0].radius: must be > 0 (got -1)");
    check_bad_scene(scene_with_sphere(R"({"center": [0, 0, 3], "radius": 0, "color": [1, 2, 3]})"),
                    "spheres[0].radius: must be > 0 (got 0)");
  }
  SECTION("reflective outside [0, 1]") {
    check_bad_scene(scene_with_sphere(R"({"center": [0, 0, 3], "radius": 1, "color": [1, 2, 3], "reflective": 1.5})"),
                    "spheres[0].reflective: must be in [0, 1] (got 1.5)");
    check_bad_scene(scene_with_sphere(R"({"center": [0, 0, 3], "radius": 1, "color": [1, 2, 3], "reflective": -0.1})"),
                    "spheres[0].reflective: must be in [0, 1] (got -0.1)");
  }
  SECTION("unknown light type") {
    check_bad_scene(scene_with_light(R"({"type": "spot", "intensity": 1})"),
                    "lights[0].type: unknown light type \"spot\"");
  }
  SECTION("zero-length directional light") {
    check_bad_scene(scene_with_light(R"({"type": "directional", "intensity": 1, "direction": [0, 0, 0]})"),
                    "lights[0].direction: must not be the zero vector");
  }
  SECTION("recursion_depth above the maximum") {
    check_bad_scene(R"({"recursion_depth": 65})", "recursion_depth: must be in [0, 64] (got 65)");
  }
}

TEST_CASE("missing or unreadable scene file", "[cli]") {
  TempDir dir;
  std::string out = dir / clrt_test::image_name("out");
  std::string missing = dir / "missing.json";
  check_error(run_clrt({"render", missing, "-o", out}), {missing + ": cannot open scene file: No such file"});
  check_error(run_clrt({"render", dir.path().string(), "-o", out}),
              {dir.path().string() + ": cannot open scene file: is a directory"});
  check_error(run_clrt({"compare", missing}), {missing + ": cannot open scene file"});
  CHECK(dir.entries().empty());
}

TEST_CASE("bad image size and depth options", "[cli]") {
  TempDir dir;
  std::string out = dir / clrt_test::image_name("out");
  check_bad_render({"--width", "0"}, out, {"--width/--height must be > 0 (got 0x600)"});
  check_bad_render({"--height", "-5"}, out, {"--width/--height must be > 0 (got 600x-5)"});
  check_bad_render({"--width", "100000"}, out, {"image 100000x600 is too large"});
  check_bad_render({"--width", "16384", "--height", "16384"}, out, {"image 16384x16384 is too large"});
  check_bad_render({"--width", "99999999999"}, out, {"--width"});
  check_bad_render({"--depth", "-5"}, out, {"--depth: Value -5 not in range 0 to 64"});
  check_bad_render({"--depth", "-1"}, out, {"--depth: Value -1 not in range 0 to 64"});
  check_bad_render({"--depth", "65"}, out, {"--depth: Value 65 not in range 0 to 64"});
  CHECK(dir.entries().empty());
}

TEST_CASE("every floating option refuses NaN and infinities, every unsigned one a negative number", "[cli]") {
  // The options are read off each command's --help by the type CLI11 shows
  // (FLOAT, UINT), so an option added later is covered too. Before this
  // rule, `compare --fail-percent nan` dropped the gate (NaN passes a range
  // check) and `generate --seed -1` wrapped to 2^64 - 1.
  TempDir dir;
  const std::string scene = clrt_test::source_path("scenes/cgfs-demo.json");
  const std::string out = dir / clrt_test::image_name("out");
  const std::vector<std::pair<std::string, std::vector<std::string>>> commands = {
      {"render", {scene, "-o", out}},
      {"compare", {scene}},
      {"bench", {scene}},
      {"sweep", {scene}},
      {"accuracy", {scene}},
      {"stability", {}},
      {"scaling", {}},
      {"devices", {}},
      {"generate", {"-o", dir / "scene.json"}}};
  size_t floats = 0, unsigneds = 0;
  for (const auto& [command, required] : commands) {
    const RunResult help = run_clrt({command, "--help"});
    REQUIRE(help.status == 0);
    std::istringstream lines(help.out);
    for (std::string line; std::getline(lines, line);) {
      std::istringstream words(line);
      std::string names, type;
      words >> names >> type;
      if (names.rfind("-", 0) != 0) continue;
      const std::string option = names.substr(names.rfind(',') == std::string::npos ? 0 : names.rfind(',') + 1);
      const bool is_float = type.rfind("FLOAT", 0) == 0, is_unsigned = type.rfind("UINT", 0) == 0;
      std::vector<std::string> bad;
      if (is_float) bad = {"nan", "NaN", "inf", "-inf", "1e999"};
      if (is_unsigned) bad = {"-1", "-1e3"};
      floats += is_float;
      unsigneds += is_unsigned;
      for (const std::string& value : bad) {
        INFO(command << " " << option << " " << value);
        std::vector<std::string> args = {command};
        args.insert(args.end(), required.begin(), required.end());
        args.insert(args.end(), {option, value});
        const RunResult r = run_clrt(args);
        // (An option with a range refuses infinities and negative numbers
        // by its range already; NaN passes every range check.)
        if (value == "nan" || value == "NaN")
          check_error(r, {option, "expected a finite number (got \"" + value + "\")"});
        else
          check_error(r, {option});
      }
    }
  }
  CHECK(floats >= 5);     // --adaptive, --fail-percent, --fill, --max-launch-ms, ...
  CHECK(unsigneds >= 2);  // --seed, --spheres
  CHECK(dir.entries().empty());
  // The two that got through before, with the rule's own messages.
  check_error(run_clrt({"compare", scene, "--fail-percent", "nan"}),
              {"--fail-percent: expected a finite number (got \"nan\")"});
  check_error(run_clrt({"generate", "--seed", "-1", "-o", dir / "seed.json"}),
              {"--seed: expected a number >= 0 (got \"-1\")"});
  CHECK(dir.entries().empty());
  // A finite number is still a number, and a bad one still CLI11's error.
  check_error(run_clrt({"compare", scene, "--fail-percent", "abc"}), {"--fail-percent"});
  CHECK(run_clrt({"generate", "--seed", "0", "--spheres", "3", "-o", dir / "ok.json"}).status == 0);
}

TEST_CASE("bad --spp: one error line, exit 2, on every command that renders", "[cli][spp]") {
  TempDir dir;
  const std::string out = dir / clrt_test::image_name("out");
  const std::string demo = clrt_test::source_path("scenes/cgfs-demo.json");
  check_bad_render({"--spp", "0"}, out, {"--spp: Value 0 not in range 1 to 16"});
  check_bad_render({"--spp", "17"}, out, {"--spp: Value 17 not in range 1 to 16"});
  check_bad_render({"--spp", "-2"}, out, {"--spp"});
  check_bad_render({"--spp", "two"}, out, {"--spp"});
  check_bad_render({"--spp", "2.5"}, out, {"--spp"});
  check_error(run_clrt({"render", demo, "-o", out, "--engine", "reference", "--spp", "0"}), {"--spp"});
  check_error(run_clrt({"compare", demo, "--spp", "17"}), {"--spp: Value 17 not in range 1 to 16"});
  check_error(run_clrt({"bench", demo, "--spp", "0"}), {"--spp: Value 0 not in range 1 to 16"});
  check_error(run_clrt({"sweep", demo, "--spp", "99"}), {"--spp: Value 99 not in range 1 to 16"});
  check_error(run_clrt({"accuracy", demo, "--spp", "-1"}), {"--spp"});
  // Adaptive supersampling needs a grid with more than its corners.
  check_bad_render({"--spp", "2", "--adaptive", "4"}, out, {"--adaptive needs --spp 3 or more"});
  check_bad_render({"--spp", "4", "--adaptive", "-1"}, out, {"--adaptive"});
  check_bad_render({"--spp", "4", "--adaptive", "nan"}, out, {"--adaptive"});
  check_error(run_clrt({"compare", demo, "--adaptive", "4"}), {"--adaptive needs --spp 3 or more"});
  CHECK(dir.entries().empty());
}

TEST_CASE("compare at spp 2 on the command line: reference and OpenCL agree", "[cli][spp]") {
  TempDir dir;
  const std::string demo = clrt_test::source_path("scenes/cgfs-demo.json");
  RunResult r =
      run_clrt({"compare", demo, "--width", "40", "--height", "30", "--spp", "2", "--json", "--fail-percent", "0.05"});
  INFO("stdout: " << r.out << "\nstderr: " << r.err);
  CHECK(r.status == 0);
  CHECK_THAT(r.out, Contains("\"spp\": 2"));
}

TEST_CASE("bad output paths fail before rendering", "[cli]") {
  TempDir dir;
  SECTION("directory does not exist") {
    std::string out = dir / clrt_test::image_name("nodir/out");
    check_bad_render({}, out, {out + ": cannot write output: directory " + (dir / "nodir") + " does not exist"});
    CHECK(dir.entries().empty());
  }
  SECTION("output is a directory") {
    std::string out = dir / clrt_test::image_name("out");
    fs::create_directory(out);
    check_bad_render({}, out, {out + ": cannot write output: it is a directory"});
    CHECK(fs::is_empty(out));
  }
  SECTION("unwritable location") {
    // /proc refuses new files even for root (CI runs as root).
    check_bad_render(
        {}, clrt_test::image_name("/proc/clrt-test-out"),
        {clrt_test::image_name("/proc/clrt-test-out") + ": cannot write output: cannot create a file in /proc"});
    CHECK_FALSE(fs::exists(clrt_test::image_name("/proc/clrt-test-out")));
  }
  SECTION("unknown image extension") {
    std::string out = dir / "out.xyz";
    check_bad_render({}, out, {out + ": unknown image format \".xyz\""});
    CHECK(dir.entries().empty());
  }
  SECTION("no extension or empty path") {
    std::string out = dir / "out";
    check_bad_render({}, out, {out + ": output has no file extension"});
    check_bad_render({}, "", {"output path is empty"});
    CHECK(dir.entries().empty());
  }
  SECTION("compare --diff is checked too") {
    std::string diff = dir / "diff.xyz";
    check_error(run_clrt({"compare", clrt_test::source_path("scenes/cgfs-demo.json"), "--diff", diff}),
                {diff + ": unknown image format \".xyz\""});
    CHECK(dir.entries().empty());
  }
}

TEST_CASE("a successful render leaves only its output", "[cli]") {
  TempDir dir;
  std::string out = dir / clrt_test::image_name("out");
  RunResult r = run_clrt({"render", clrt_test::source_path("scenes/cgfs-demo.json"), "-o", out, "--width", "16",
                          "--height", "16", "--engine", "reference"});
  INFO("stderr: " << r.err);
  CHECK(r.status == 0);
  CHECK(r.err.empty());
  CHECK(dir.entries() == std::vector<std::string>{clrt_test::image_name("out")});
}

TEST_CASE("no OpenCL platform: clear error, and the reference engine still works", "[cli]") {
  TempDir dir;
  fs::create_directory(dir / "vendors");  // ocl-icd reads ICDs from here: none
  const std::string env = "OCL_ICD_VENDORS=" + clrt_test::shell_quote(dir / "vendors");
  const std::string scene = clrt_test::source_path("scenes/cgfs-demo.json");
  const std::string out = dir / clrt_test::image_name("out");
  const std::vector<std::string> small = {"--width", "16", "--height", "16"};
  std::vector<std::string> args = {"render", scene, "-o", out};
  args.insert(args.end(), small.begin(), small.end());

  check_error(run_clrt(args, env), {"no OpenCL platform found", "--engine reference"});
  CHECK_FALSE(fs::exists(out));
  check_error(run_clrt({"devices"}, env), {"no OpenCL platform found"});

  args.insert(args.end(), {"--engine", "reference"});
  RunResult ok = run_clrt(args, env);
  INFO("stderr: " << ok.err);
  CHECK(ok.status == 0);
  CHECK(fs::exists(out));
}

TEST_CASE("unknown device", "[cli][opencl]") {
  TempDir dir;
  std::string out = dir / clrt_test::image_name("out");
  check_bad_render({"--device", "no-such-device", "--width", "16", "--height", "16"}, out,
                   {"unknown device \"no-such-device\" (available: 0: "});
  CHECK_FALSE(fs::exists(out));
}

TEST_CASE("kernel build failure prints the build log, then one error line", "[cli][opencl]") {
  TempDir dir;
  fs::copy(clrt_test::source_path("kernels"), dir / "kernels", fs::copy_options::recursive);
  std::ofstream(dir / "kernels/trace.cl", std::ios::app) << "\nthis is not OpenCL C;\n";
  std::string out = dir / clrt_test::image_name("out");
  RunResult r = run_clrt({"render", clrt_test::source_path("scenes/cgfs-demo.json"), "-o", out, "--width", "16",
                          "--height", "16", "--kernel-dir", dir / "kernels"});
  INFO("stderr: " << r.err);
  CHECK(r.status == 2);
  CHECK_THAT(r.err, Contains("---- kernel build log"));
  CHECK_THAT(r.err, Contains("trace.cl"));  // the compiler's diagnostic names the file
  CHECK_THAT(r.last_error_line(), StartsWith("clrt: error: kernel build failed on "));
  CHECK_THAT(r.last_error_line(), Contains("CL_BUILD_PROGRAM_FAILURE"));
  CHECK_FALSE(fs::exists(out));

  std::string missing = dir / "nokernels";
  check_bad_render({"--kernel-dir", missing}, out, {missing + "/trace.cl: cannot open kernel file"});
  CHECK_FALSE(fs::exists(out));
}

}  // namespace test_cli_errors
