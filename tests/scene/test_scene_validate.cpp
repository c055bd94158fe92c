// test_scene_validate.cpp - validate_scene (`clrt validate`): every problem
// of a file, each in the reader's own words, the first one the problem the
// reader stops at.
#include <catch2/catch.hpp>
#include <filesystem>

#include "cli_run.hpp"
#include "scene/scene_json.hpp"
#include "test_util.hpp"
#include "util/error.hpp"

// (clrt_tests is a unity build: each file's code is in a namespace of its own.)
namespace test_scene_validate {

using clrt_test::TempDir;

namespace {

// The problems validate_scene reports for the file at `path`.
std::vector<std::string> problems_of(const std::string& path) {
  std::vector<std::string> found;
  const size_t n = clrt::validate_scene(path, [&](const std::string& m) { found.push_back(m); });
  CHECK(n == found.size());
  return found;
}

}  // namespace

TEST_CASE("validate reports every problem of a file, each with the reader's text", "[scene][full-build]") {
  // ([full-build]: it reads an OBJ mesh.)
  TempDir dir;
  dir.write("cube.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  const std::string path = dir.write("bad.json", R"({
    "camera": {"position": [0, 0, 1e9], "viewport": [1, 2, 3], "zoom": 2},
    "recursion_depth": 1.5,
    "spheres": [{"center": [0, 0, 3], "radius": -1, "color": [1, 2, 300], "specular": "shiny"},
                {"radius": 1},
                7],
    "lights": [{"type": "point", "intensity": 2, "direction": [0, 1, 0]},
               {"type": "spot", "intensity": 0.5}],
    "meshes": [{"file": "cube.obj", "color": [1, 1, 1]}, {"file": "missing.obj", "color": [1, 1, 1]},
               {"file": "../up.obj", "color": [1, 1, 1]}],
    "epsilon": 0.001, "epsilon": 0.002})");
  const std::vector<std::string> expected = {
      path + ": camera.position[2]: must be within ±1e+08, the range clrt renders in float32 (got 1e+09)",
      path + ": camera.viewport: expected an array of 2 numbers",
      path + ": camera: unknown key \"zoom\"",
      path + ": recursion_depth: expected an integer, got number",
      path + ": spheres[0].radius: must be > 0 (got -1)",
      path + ": spheres[0].color: color components must be in [0, 255] (got 300)",
      path + ": spheres[0].specular: expected a number, got string",
      path + ": spheres[1]: missing \"center\"",
      path + ": spheres[1]: missing \"color\"",
      path + ": spheres[2]: expected an object, got number",
      path + ": lights[0]: unknown key \"direction\"",
      path + ": lights[0]: point light needs \"position\"",
      path + ": lights[1].type: unknown light type \"spot\" (expected ambient, point or directional)",
      path + ": meshes[2].file: must not leave the scene's folder (\"..\")",
      path + ": duplicate key \"epsilon\"",
      path + ": meshes[1].file: " + (dir / "missing.obj") + ": cannot open mesh file: No such file or directory",
  };
  CHECK(problems_of(path) == expected);
  // The first is where the reader stops.
  try {
    clrt::load_scene(path);
    FAIL("no error");
  } catch (const clrt::UserError& e) {
    CHECK(e.what() == expected[0]);
  }
}

TEST_CASE("validate's first problem is the reader's, for every file of the fuzz corpus", "[scene]") {
  TempDir dir;
  size_t files = 0, invalid = 0;
  for (const auto& entry : std::filesystem::directory_iterator(clrt_test::source_path("tests/fuzz/corpus"))) {
    const std::string path = dir.write("s.json", clrt_test::slurp(entry.path().string()));
    std::string error;
    try {
      clrt::load_scene(path);
    } catch (const clrt::UserError& e) {
      error = e.what();
    }
    const std::vector<std::string> found = problems_of(path);
    INFO(entry.path().filename().string());
    if (error.empty()) {
      CHECK(found.empty());
    } else {
      REQUIRE_FALSE(found.empty());
      CHECK(found[0] == error);
      ++invalid;
    }
    ++files;
  }
  CHECK(files > 1000);
  CHECK(invalid > 900);
}

}  // namespace test_scene_validate
