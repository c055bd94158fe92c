// test_scene_keys.cpp - the table of the scene format's keys
// (scene/scene_keys.hpp) against what else names them: the fuzz dictionary,
// docs/reference/scene-format.md, and the scene model's defaults.
#include <catch2/catch.hpp>
#include <regex>
#include <set>
#include <sstream>

#include "cli_run.hpp"
#include "scene/scene_keys.hpp"
#include "test_util.hpp"

// (clrt_tests is a unity build: each file's code is in a namespace of its own.)
namespace test_scene_keys {

using namespace clrt;

namespace {

const Ctx kAll[] = {Ctx::Root, Ctx::Camera, Ctx::Sphere, Ctx::Light, Ctx::Plane, Ctx::Triangle, Ctx::Mesh};

// One row of a key table of the documentation: the key and its default cell.
struct DocRow {
  std::string key, fallback;
};

// The rows of the first table after the heading "## <title>".
std::vector<DocRow> doc_table(const std::string& doc, const std::string& title) {
  std::vector<DocRow> rows;
  const size_t at = doc.find("\n## " + title + "\n");
  if (at == std::string::npos) return rows;
  std::istringstream in(doc.substr(at + 1));
  std::string line;
  std::getline(in, line);  // the heading
  bool in_table = false;
  const std::regex row(R"(^\| `([a-z_]+)` \|.*\| ([^|]*) \|$)");
  while (std::getline(in, line)) {
    std::smatch m;
    if (std::regex_match(line, m, row)) {
      rows.push_back({m[1], m[2]});
      in_table = true;
    } else if (in_table && line.rfind("|", 0) != 0) {
      break;
    } else if (line.rfind("## ", 0) == 0) {
      break;
    }
  }
  return rows;
}

}  // namespace

TEST_CASE("the fuzz dictionary has every key and choice of the table, and no other word", "[scene]") {
  const std::string dict = clrt_test::slurp(clrt_test::source_path("tests/fuzz/scene.dict"));
  std::set<std::string> words;
  const std::regex entry(R"re(^"\\"([a-z_]+)\\""$)re");
  std::istringstream in(dict);
  for (std::string line; std::getline(in, line);) {
    std::smatch m;
    if (std::regex_match(line, m, entry)) words.insert(m[1]);
  }
  std::set<std::string> table;
  for (const Key& k : all_keys()) {
    table.insert(std::string(k.name));
    for (std::string_view c : k.choices)
      if (!c.empty()) table.insert(std::string(c));
  }
  CHECK(words == table);
}

TEST_CASE("docs/reference/scene-format.md lists each context's keys, in order, required or with their defaults",
          "[scene]") {
  const std::string doc = clrt_test::slurp(clrt_test::source_path("docs/reference/scene-format.md"));
  for (Ctx c : kAll) {
    const std::string title(context(c).title);
    INFO("## " << title);
    const std::vector<DocRow> rows = doc_table(doc, title);
    REQUIRE(rows.size() == keys_of(c).size());
    for (size_t i = 0; i < rows.size(); ++i) {
      const Key& k = keys_of(c)[i];
      INFO("key " << k.name << ", default cell \"" << rows[i].fallback << "\"");
      CHECK(rows[i].key == k.name);
      CHECK((rows[i].fallback.rfind("required", 0) == 0) == k.required);
      if (!k.fallback.empty()) CHECK(rows[i].fallback.find("`" + std::string(k.fallback) + "`") != std::string::npos);
    }
  }
}

TEST_CASE("the table's defaults are the scene model's own", "[scene]") {
  // Code that builds scenes (random_scene, the tests) starts from Sphere{}
  // and the like; the reader starts from the table's prototypes.
  const Prototypes& p = prototypes();
  const Scene scene;
  const void* defaults[] = {&scene, &scene.camera, nullptr, nullptr, nullptr, nullptr, nullptr};
  const Sphere sphere;
  const Light light;
  const Plane plane;
  const Triangle triangle;
  const MeshSource mesh;
  defaults[2] = &sphere, defaults[3] = &light, defaults[4] = &plane, defaults[5] = &triangle, defaults[6] = &mesh;
  const void* made[] = {&p.scene, &p.scene.camera, &p.sphere, &p.light, &p.plane, &p.triangle, &p.mesh};
  size_t checked = 0;
  for (Ctx c : kAll)
    for (const Key& k : keys_of(c)) {
      if (k.fallback.empty() || k.kind == Kind::Object || k.kind == Kind::Objects) continue;
      INFO(context(c).noun << "." << k.name);
      const auto i = static_cast<size_t>(c);
      CHECK(value_json(k, made[i]) == nlohmann::json::parse(k.fallback));
      CHECK(value_json(k, defaults[i]) == nlohmann::json::parse(k.fallback));
      ++checked;
    }
  CHECK(checked == 21);
}

TEST_CASE("a key's member is the one its name says", "[scene]") {
  // Each key, read into an object from the text {"key": value}, is what
  // value_json gives back.
  Scene s = parse_scene(R"({"camera": {"position": [1, 2, 3], "rotation": [[0, 1, 0], [1, 0, 0], [0, 0, 1]],
                                       "viewport": [2, 3], "projection_plane_d": 4, "aspect": "image"},
                            "background": [5, 6, 7], "recursion_depth": 8, "epsilon": 0.5,
                            "lights": [{"type": "directional", "intensity": 0.25, "direction": [0, 0, 3]}]})",
                        "t");
  CHECK(value_json(*find_key(Ctx::Camera, "position"), &s.camera) == nlohmann::json::parse("[1, 2, 3]"));
  CHECK(value_json(*find_key(Ctx::Camera, "rotation"), &s.camera) ==
        nlohmann::json::parse("[[0, 1, 0], [1, 0, 0], [0, 0, 1]]"));
  CHECK(s.camera.viewport_w == 2);
  CHECK(s.camera.viewport_h == 3);
  CHECK(s.camera.projection_plane_d == 4);
  CHECK(s.camera.aspect_from_image);
  CHECK(s.background.z == 7);
  CHECK(s.recursion_depth == 8);
  CHECK(s.epsilon == 0.5);
  // A direction is rescaled on load and written back as given.
  CHECK(s.lights[0].vec.z == 0.75);
  CHECK(value_json(*find_key(Ctx::Light, "direction"), &s.lights[0]) == nlohmann::json::parse("[0, 0, 3]"));
}

}  // namespace test_scene_keys
