// test_validate_command.cpp - `clrt validate SCENE...`: one line a problem
// (tests/scene/test_scene_validate.cpp: which problems), `FILE: valid`, exit
// status 0 or 2, -D; `clrt validate --schema` and the committed schema.
#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>
#include <sstream>

#include "cli_run.hpp"
#include "scene/scene_schema.hpp"
#include "test_util.hpp"

// (clrt_tests is a unity build: each file's code is in a namespace of its own.)
namespace test_validate_command {

using Catch::Matchers::Contains;
using clrt_test::run_clrt;
using clrt_test::RunResult;
using clrt_test::TempDir;

namespace {

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

}  // namespace

TEST_CASE("clrt validate: one error line a problem, 'valid' for a valid file, exit status 0 or 2", "[cli]") {
  TempDir dir;
  const std::string good = clrt_test::source_path("scenes/cgfs-demo.json");
  const std::string bad = dir.write("bad.json", R"({"epsilon": -1, "spheres": [{"radius": 1}]})");
  const RunResult ok = run_clrt({"validate", good, clrt_test::source_path("scenes/glass.json")});
  INFO(ok.err);
  CHECK(ok.status == 0);
  CHECK(ok.err.empty());
  CHECK(ok.out == good + ": valid\n" + clrt_test::source_path("scenes/glass.json") + ": valid\n");
  const RunResult r = run_clrt({"validate", good, bad, dir / "none.json"});
  CHECK(r.status == 2);
  CHECK(r.out == good + ": valid\n");
  CHECK(lines_of(r.err) == std::vector<std::string>{
                               "clrt: error: " + bad + ": epsilon: must be in [0, 1e+08] (got -1)",
                               "clrt: error: " + bad + ": spheres[0]: missing \"center\"",
                               "clrt: error: " + bad + ": spheres[0]: missing \"color\"",
                               "clrt: error: " + (dir / "none.json") +
                                   ": cannot open scene file: No such file or directory",
                           });
  // With -D: the scene as the other commands would read it.
  const RunResult d = run_clrt({"validate", good, "-D", "spheres.0.radius=0"});
  CHECK(d.status == 2);
  CHECK(d.err == "clrt: error: -D spheres.0.radius=0: must be > 0 (got 0)\n");
  // No scene: one error line.
  const RunResult none = run_clrt({"validate"});
  CHECK(none.status == 2);
  CHECK(none.err == "clrt: error: a SCENE is required (or --schema)\n");
}

TEST_CASE("clrt validate --schema prints the committed docs/reference/scene.schema.json", "[cli]") {
  const std::string committed = clrt_test::slurp(clrt_test::source_path("docs/reference/scene.schema.json"));
  // (Made anew: `clrt validate --schema > docs/reference/scene.schema.json`.)
  CHECK(clrt::scene_schema_text() == committed);
  const RunResult r = run_clrt({"validate", "--schema"});
  CHECK(r.status == 0);
  CHECK(r.out == committed);
  const auto schema = nlohmann::json::parse(committed);
  CHECK(schema["$schema"] == "https://json-schema.org/draft/2020-12/schema");
  CHECK(schema["properties"]["recursion_depth"]["maximum"] == 64);
  CHECK(schema["$defs"]["sphere"]["required"] == nlohmann::json::parse(R"(["center", "radius", "color"])"));
  CHECK(schema["$defs"]["light"]["allOf"].size() == 3);
  CHECK(run_clrt({"validate", "--schema", clrt_test::source_path("scenes/glass.json")}).status == 2);
}

}  // namespace test_validate_command
