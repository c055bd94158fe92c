// test_overrides_cli.cpp - `-D PATH=VALUE` on the command line: every
// command that reads scene files takes it, a bad one is one error line, a
// render with it is the render of the edited file, and images and --json
// reports record it.
#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include "cli_run.hpp"
#include "image/image_file.hpp"
#include "test_util.hpp"

// (clrt_tests is a unity build: each file's code is in a namespace of its own.)
namespace test_overrides_cli {

using Catch::Matchers::Contains;
using clrt_test::run_clrt;
using clrt_test::RunResult;
using clrt_test::TempDir;

namespace {

void check_one_error(const RunResult& r, const std::string& line) {
  INFO("stdout: " << r.out << "stderr: " << r.err);
  CHECK(r.status == 2);
  CHECK(r.one_line_error());
  CHECK(r.err == "clrt: error: " + line + "\n");
}

const std::string& demo() {
  static const std::string path = clrt_test::source_path("scenes/cgfs-demo.json");
  return path;
}

}  // namespace

TEST_CASE("every command that reads scene files takes -D and says which -D is wrong", "[cli]") {
  // Each fails at the scene, before any device work.
  TempDir dir;
  const std::vector<std::vector<std::string>> commands = {
      {"render", demo(), "-o", dir / clrt_test::image_name("never")}, {"compare", demo()}, {"bench", demo()},
      {"sweep", demo()}, {"accuracy", demo()}, {"validate", demo()}};
  for (const auto& command : commands) {
    INFO("clrt " << command[0]);
    std::vector<std::string> args = command;
    args.insert(args.end(), {"-D", "recursion_depth=2", "--set", "spheres.9.radius=1"});
    check_one_error(run_clrt(args), "-D spheres.9.radius=1: the scene has 4 spheres");
    CHECK_THAT(run_clrt({command[0], "--help"}).out, Contains("-D,--set PATH=VALUE"));
  }
}

TEST_CASE("each kind of bad -D is one error line, exit status 2", "[cli]") {
  auto render = [](const std::string& d) {
    return run_clrt({"render", demo(), "--engine", "reference", "-D", d, "-o", TempDir() / "never.ppm"});
  };
  check_one_error(render("spheres.0.radus=1"), R"(-D spheres.0.radus=1: spheres[0]: unknown key "radus"; did you mean "radius"?)");
  check_one_error(render("lights.7.intensity=1"), "-D lights.7.intensity=1: the scene has 3 lights");
  check_one_error(render("epsilon=1,"),
                  "-D epsilon=1,: the value is not JSON: malformed JSON: parse error at line 1, column 2: syntax "
                  "error while parsing value - unexpected ','; expected end of input");
  check_one_error(render("spheres.2.reflective=0.8x"),
                  "-D spheres.2.reflective=0.8x: the value is not JSON: malformed JSON: parse error at line 1, column "
                  "4: syntax error while parsing value - invalid literal; last read: '0.8x'; expected end of input");
  check_one_error(render("spheres.2.reflective=1.5"), "-D spheres.2.reflective=1.5: must be in [0, 1] (got 1.5)");
  check_one_error(render("recursion_depth"),
                  "-D recursion_depth: expected PATH=VALUE (e.g. -D recursion_depth=5, -D spheres.0.radius=2)");
}

TEST_CASE("a render with -D is the render of the edited scene file, pixel for pixel", "[cli]") {
  TempDir dir;
  nlohmann::json doc = nlohmann::json::parse(clrt_test::slurp(demo()));
  doc["recursion_depth"] = 1;
  doc["camera"] = {{"position", {0, 1, -2}}};
  doc["spheres"][2]["reflective"] = 0.8;
  doc["spheres"][0]["transparency"] = 0.5;  // a key the file leaves out
  doc["lights"][1]["intensity"] = 0.4;
  const std::string edited = dir.write("edited.json", doc.dump());
  // PPM: its pixels are its last 48 x 36 x 3 bytes (the comments before them
  // hold the metadata, which names the scene and the -D).
  const std::vector<std::string> size = {"--engine", "reference", "--width", "48", "--height", "36"};
  std::vector<std::string> a = {"render", demo(), "-o", dir / "d.ppm", "-D", "recursion_depth=1",
                                "-D", "camera.position=[0,1,-2]", "-D", "spheres.2.reflective=0.8",
                                "-Dspheres.0.transparency=0.5", "--set=lights.1.intensity=0.4"};
  std::vector<std::string> b = {"render", edited, "-o", dir / "e.ppm"};
  std::vector<std::string> c = {"render", demo(), "-o", dir / "plain.ppm"};
  for (auto* args : {&a, &b, &c}) {
    args->insert(args->end(), size.begin(), size.end());
    const RunResult r = run_clrt(*args);
    INFO(r.err);
    REQUIRE(r.status == 0);
  }
  const auto pixels = [&](const std::string& name) {
    const std::string file = clrt_test::slurp(dir / name);
    REQUIRE(file.size() > 48 * 36 * 3);
    return file.substr(file.size() - 48 * 36 * 3);
  };
  CHECK(pixels("d.ppm") == pixels("e.ppm"));
  CHECK(pixels("d.ppm") != pixels("plain.ppm"));  // (the -D did change the image)
}

TEST_CASE("an image rendered with -D records the overrides", "[cli][full-build]") {
  TempDir dir;
  const RunResult r = run_clrt({"render", demo(), "--engine", "reference", "--width", "16", "--height", "12", "-D",
                                "recursion_depth=1", "-D", "camera.position=[0, 1, -2]", "-o", dir / "m.png"});
  INFO(r.err);
  REQUIRE(r.status == 0);
  const clrt::ImageMetadata meta = clrt::read_metadata(dir / "m.png", {"clrt:overrides", "ImageDescription"});
  REQUIRE(meta.size() == 2);
  CHECK(meta[0].second == R"({"recursion_depth":1,"camera.position":[0,1,-2]})");
  CHECK_THAT(meta[1].second, Contains(", with -D recursion_depth=1 -D camera.position=[0, 1, -2]"));
  // Without -D, no attribute.
  REQUIRE(run_clrt({"render", demo(), "--engine", "reference", "--width", "8", "--height", "8", "-o", dir / "n.png"})
              .status == 0);
  CHECK(clrt::read_metadata(dir / "n.png", {"clrt:overrides"}).empty());
}

}  // namespace test_overrides_cli
