// test_chapter5_scene.cpp - the scene format's chapter 5 keys: transparency
// and refractive index, planes, inline triangles and OBJ meshes (paths,
// transforms, limits), their errors, and the round trip through JSON.
#include <sys/stat.h>
#include <unistd.h>

#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

#include "scene/scene_json.hpp"
#include "cli_run.hpp"
#include "test_util.hpp"
#include "util/error.hpp"

// (clrt_tests is a unity build: each file's code is in a namespace of its own.)
namespace test_chapter5_scene {

using namespace clrt;

namespace {

// parse_scene's message for `text`, "" when it parses.
std::string error_of(const std::string& text, const SceneLimits& limits = {}) {
  try {
    parse_scene(text, "t", limits);
  } catch (const UserError& e) {
    return e.what();
  }
  return "";
}

const std::string kLight = R"("lights": [{"type": "ambient", "intensity": 1}])";

}  // namespace

TEST_CASE("transparency and refractive index: defaults, ranges", "[scene]") {
  const Scene s = parse_scene(R"({"spheres": [{"center": [0,0,3], "radius": 1, "color": [1,2,3]},
      {"center": [0,0,3], "radius": 1, "color": [1,2,3], "transparency": 0.5, "refractive_index": 1.33}]})",
                              "t");
  CHECK(s.spheres[0].transparency == 0);
  CHECK(s.spheres[0].refractive_index == 1);
  CHECK(s.spheres[1].transparency == 0.5);
  CHECK(s.spheres[1].refractive_index == 1.33);
  const std::string sphere = R"({"spheres": [{"center": [0,0,3], "radius": 1, "color": [1,2,3], )";
  CHECK(error_of(sphere + R"("transparency": 1.5}]})") == "t: spheres[0].transparency: must be in [0, 1] (got 1.5)");
  CHECK(error_of(sphere + R"("refractive_index": 0}]})") ==
        "t: spheres[0].refractive_index: must be in [0.1, 10] (got 0)");
  CHECK(error_of(sphere + R"("refractive_index": "glass"}]})") ==
        "t: spheres[0].refractive_index: expected a number, got string");
}

TEST_CASE("planes: the normal is rescaled by a power of two, the material read", "[scene][flat]") {
  const Scene s = parse_scene(R"({"planes": [{"point": [0, -1, 0], "normal": [0, 1e-300, 0], "color": [9, 8, 7],
      "specular": 10, "reflective": 0.5}, {"point": [1, 2, 3], "normal": [3, 0, -4], "color": [1, 1, 1]}]})",
                              "t");
  REQUIRE(s.planes.size() == 2);
  CHECK(s.planes[0].normal.y == 0.5 * (1e-300 / std::ldexp(1.0, std::ilogb(1e-300))));  // exact, no underflow
  CHECK(s.planes[0].normal.y >= 0.5);
  CHECK(s.planes[0].normal.y < 1);
  CHECK(s.planes[0].point.y == -1);
  CHECK(s.planes[0].material.color.x == 9);
  CHECK(s.planes[0].material.specular == 10);
  CHECK(s.planes[0].material.reflective == 0.5);
  CHECK(s.planes[1].normal.x == 0.375);  // (3, 0, -4) / 8
  CHECK(s.planes[1].normal.z == -0.5);
  CHECK(s.planes[1].material.specular == -1);  // matte by default, like a sphere
  CHECK(error_of(R"({"planes": [{"point": [0, 0, 0], "normal": [0, 0, 0], "color": [1, 1, 1]}]})") ==
        "t: planes[0].normal: must not be the zero vector");
  CHECK(error_of(R"({"planes": [{"point": [0, 0, 0], "color": [1, 1, 1]}]})") == "t: planes[0]: missing \"normal\"");
  CHECK(error_of(R"({"planes": [{"point": [0, 0, 0], "normal": [0, 1, 0], "color": [1, 1, 1], "radius": 2}]})") ==
        "t: planes[0]: unknown key \"radius\"");
  CHECK(error_of(R"({"planes": [{"point": [0, 2e8, 0], "normal": [0, 1, 0], "color": [1, 1, 1]}]})")
            .find("planes[0].point[1]: must be within") != std::string::npos);
  SceneLimits few;
  few.planes = 1;
  CHECK(error_of(R"({"planes": [{"point": [0, 0, 0], "normal": [0, 1, 0], "color": [1, 1, 1]},
                                {"point": [0, 0, 0], "normal": [0, 1, 0], "color": [1, 1, 1]}]})",
                 few) == "t: planes: more than 1 planes, the most clrt loads");
}

TEST_CASE("triangles: three vertices of three numbers", "[scene][flat]") {
  const Scene s = parse_scene(
      R"({"triangles": [{"vertices": [[0, 0, 5], [1, 0, 5], [0, 1, 5]], "color": [4, 5, 6], "reflective": 0.25}]})",
      "t");
  REQUIRE(s.triangles.size() == 1);
  CHECK(s.triangles[0].v1.x == 1);
  CHECK(s.triangles[0].v2.y == 1);
  CHECK(s.triangles[0].material.reflective == 0.25);
  CHECK(error_of(R"({"triangles": [{"vertices": [[0, 0, 5], [1, 0, 5]], "color": [4, 5, 6]}]})") ==
        "t: triangles[0].vertices: expected 3 vertices of 3 numbers each");
  CHECK(
      error_of(R"({"triangles": [{"vertices": [[0, 0, 5], [1, 0, 5], [0, 1, 5], [1, 1, 1]], "color": [4, 5, 6]}]})") ==
      "t: triangles[0].vertices: expected 3 vertices of 3 numbers each");
  CHECK(error_of(R"({"triangles": [{"vertices": [[0, 0, 5], [1, 0], [0, 1, 5]], "color": [4, 5, 6]}]})") ==
        "t: triangles[0].vertices[1]: expected an array of 3 numbers");
  CHECK(error_of(R"({"triangles": [{"color": [4, 5, 6]}]})") == "t: triangles[0]: missing \"vertices\"");
  CHECK(error_of(R"({"triangles": {"vertices": []}})") == "t: triangles: expected an array, got object");
}

TEST_CASE("meshes: OBJ files from the scene's folder, transformed, with the scene's material",
          "[scene][flat][mesh][full-build]") {
  const Scene s = clrt_test::load("scenes/large/mesh.json");
  CHECK(s.triangles.size() == 2 * 5120);
  CHECK(s.planes.size() == 1);
  // The first mesh: the unit icosphere scaled by 1.1 around (0, 0.1, 4.5).
  for (size_t i = 0; i < 5120; ++i) {
    const Vec3 v = s.triangles[i].v0 - Vec3{0, 0.1, 4.5};
    CHECK(length(v) == Approx(1.1).epsilon(1e-7));
    CHECK(s.triangles[i].material.color.x == 60);
  }
  // Paths that leave the scene's folder, absolute paths, missing files.
  const std::string head = R"({"meshes": [{"color": [1, 1, 1], "file": )";
  CHECK(error_of(head + R"("/etc/passwd"}]})") ==
        "t: meshes[0].file: must be a path relative to the scene's folder (got an absolute path)");
  CHECK(error_of(head + R"("models/../../secret.obj"}]})") ==
        "t: meshes[0].file: must not leave the scene's folder (\"..\")");
  CHECK(error_of(head + R"(""}]})") == "t: meshes[0].file: must not be empty");
  CHECK(error_of(head + R"(3}]})") == "t: meshes[0].file: expected a string");
  const std::string missing = error_of(head + R"("no-such-mesh.obj"}]})");
  CHECK(missing.find("t: meshes[0].file: ") == 0);
  CHECK(missing.find("no-such-mesh.obj") != std::string::npos);
  CHECK(error_of(R"({"meshes": [{"file": "a.obj"}]})") == "t: meshes[0]: missing \"color\"");
  CHECK(error_of(R"({"meshes": [{"file": "a.obj", "color": [1, 1, 1], "scale": 0}]})") ==
        "t: meshes[0].scale: must be > 0 (got 0)");
  // The triangle limit counts inline triangles and every mesh's faces.
  SceneLimits few;
  few.triangles = 5000;
  CHECK_THROWS_AS(load_scene(clrt_test::source_path("scenes/large/mesh.json"), few), UserError);
}

TEST_CASE("a mesh file is read relative to the scene file's folder", "[scene][mesh][full-build]") {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / ("clrt-mesh-test-" + std::to_string(::getpid()));
  fs::create_directories(dir / "parts");
  {
    std::ofstream(dir / "parts" / "tri.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 4 3\n";
    std::ofstream(dir / "scene.json") << R"({"meshes": [{"file": "parts/tri.obj", "color": [1, 2, 3],
        "translate": [0, 0, 5], "rotate": [0, 0, 90]}], )"
                                      << kLight << "}";
  }
  const Scene s = load_scene((dir / "scene.json").string());
  REQUIRE(s.triangles.size() == 2);  // the quad, triangulated
  // rotate z by 90 degrees: (1, 0, 0) -> (0, 1, 0), then moved to z = 5
  CHECK(s.triangles[0].v1.x == Approx(0).margin(1e-12));
  CHECK(s.triangles[0].v1.y == Approx(1).epsilon(1e-12));
  CHECK(s.triangles[0].v1.z == 5);
  fs::remove_all(dir);
}

TEST_CASE("planes and triangles survive the round trip through JSON", "[scene][flat][full-build]") {
  const Scene s = clrt_test::load("scenes/large/mesh.json");
  const Scene back = parse_scene(scene_to_json(s, JsonStyle::Compact), "back");
  REQUIRE(back.triangles.size() == s.triangles.size());
  REQUIRE(back.planes.size() == s.planes.size());
  REQUIRE(back.spheres.size() == s.spheres.size());
  for (size_t i = 0; i < s.triangles.size(); ++i) {
    CHECK(back.triangles[i].v0.x == s.triangles[i].v0.x);
    CHECK(back.triangles[i].v2.z == s.triangles[i].v2.z);
    CHECK(back.triangles[i].material.reflective == s.triangles[i].material.reflective);
  }
  CHECK(back.planes[0].normal.y == s.planes[0].normal.y);
  CHECK(back.spheres[1].transparency == s.spheres[1].transparency);
  CHECK(back.spheres[1].refractive_index == s.spheres[1].refractive_index);
  // Pretty text too, and the book's scenes keep their text (no new keys).
  CHECK(parse_scene(scene_to_json(s, JsonStyle::Pretty), "pretty").triangles.size() == s.triangles.size());
  const std::string demo = scene_to_json(clrt_test::load("scenes/cgfs-demo.json"), JsonStyle::Pretty);
  CHECK(demo.find("planes") == std::string::npos);
  CHECK(demo.find("transparency") == std::string::npos);
}

namespace {

// A scene folder with a scene naming `files` (one mesh each), beside an
// "outside" folder holding a file the scene must not read.
struct MeshFolder {
  clrt_test::TempDir root;
  std::filesystem::path scene_dir = root.path() / "scene", outside = root.path() / "outside";
  MeshFolder() {
    std::filesystem::create_directories(scene_dir / "models");
    std::filesystem::create_directories(outside);
    std::ofstream(outside / "secret.obj") << "SECRET-LINE root:x:0:0\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    std::ofstream(scene_dir / "models" / "tri.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
  }
  std::string scene(const std::vector<std::string>& files) const {
    std::string text = R"({"meshes": [)";
    for (size_t i = 0; i < files.size(); ++i)
      text += std::string(i ? ", " : "") + R"({"color": [1, 1, 1], "translate": [0, 0, 5], "file": ")" + files[i] + "\"}";
    text += "], " + kLight + "}";
    const std::string path = (scene_dir / "scene.json").string();
    std::ofstream(path) << text;
    return path;
  }
  std::string error_of_scene(const std::vector<std::string>& files, const SceneLimits& limits = {}) const {
    try {
      load_scene(scene(files), limits);
    } catch (const UserError& e) {
      return e.what();
    }
    return "";
  }
};

}  // namespace

TEST_CASE("mesh files cannot leave the scene's folder through links", "[scene][mesh][hardening][full-build]") {
  namespace fs = std::filesystem;
  MeshFolder f;
  REQUIRE(load_scene(f.scene({"models/tri.obj"})).triangles.size() == 1);
  fs::create_symlink("../outside/secret.obj", f.scene_dir / "relative.obj");
  fs::create_symlink(f.outside / "secret.obj", f.scene_dir / "absolute.obj");
  fs::create_symlink("/etc/passwd", f.scene_dir / "models" / "passwd.obj");
  fs::create_symlink("../outside", f.scene_dir / "linked");  // a folder that is a link
  fs::create_symlink("models/tri.obj", f.scene_dir / "inside.obj");  // even one that stays inside
  for (const std::string file :
       {"relative.obj", "absolute.obj", "models/passwd.obj", "linked/secret.obj", "./linked/secret.obj", "inside.obj"}) {
    const std::string e = f.error_of_scene({file});
    INFO(file << ": " << e);
    CHECK(e.find("meshes[0].file: ") != std::string::npos);
    CHECK(e.find("symbolic link") != std::string::npos);
    // Not one byte of what lies behind the link.
    CHECK(e.find("SECRET") == std::string::npos);
    CHECK(e.find("root:") == std::string::npos);
  }
  // A plain file is not reached through a non-folder either.
  CHECK(f.error_of_scene({"models/tri.obj/x.obj"}).find("not a folder") != std::string::npos);
}

TEST_CASE("a scene that is not a file has no folder to read meshes from", "[scene][mesh][hardening][full-build]") {
  namespace fs = std::filesystem;
  MeshFolder f;
  // As text (no folder at all) and through a FIFO (before: looked up beside
  // the FIFO, so under /dev for /dev/stdin, where /dev/shm is anyone's).
  const std::string text = R"({"meshes": [{"color": [1, 1, 1], "file": "models/tri.obj"}], )" + kLight + "}";
  CHECK_THAT(error_of(text), Catch::Contains("has no folder to read mesh files from"));
  const std::string fifo = (f.scene_dir / "scene.fifo").string();
  REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);
  std::thread writer([&] { std::ofstream(fifo) << text; });
  std::string e;
  try {
    load_scene(fifo);
  } catch (const UserError& x) {
    e = x.what();
  }
  writer.join();
  CHECK_THAT(e, Catch::StartsWith(fifo + ": meshes[0].file: \"models/tri.obj\": a scene that is not read from a file"));
}

TEST_CASE("mesh limits count the whole scene, and a file named twice is read once", "[scene][mesh][hardening][full-build]") {
  MeshFolder f;
  const Scene three = load_scene(f.scene({"models/tri.obj", "models/tri.obj", "./models//tri.obj"}));
  REQUIRE(three.triangles.size() == 3);
  CHECK(three.triangles[2].v1.x == 1);
  SceneLimits two;
  two.triangles = 2;
  CHECK_THAT(f.error_of_scene({"models/tri.obj", "models/tri.obj", "models/tri.obj"}, two),
             Catch::Contains("meshes[2].file: ") && Catch::Contains("1 triangles, more than the 0 the scene's limit of 2 leaves"));
  // Bytes: every distinct file once, all together.
  std::ofstream(f.scene_dir / "models" / "tri2.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
  const size_t one_file = std::filesystem::file_size(f.scene_dir / "models" / "tri.obj");
  SceneLimits bytes;
  bytes.mesh_bytes = one_file + one_file / 2;
  CHECK(load_scene(f.scene({"models/tri.obj", "models/tri.obj", "models/tri.obj"}), bytes).triangles.size() == 3);
  CHECK_THAT(f.error_of_scene({"models/tri.obj", "models/tri2.obj"}, bytes),
             Catch::Contains("meshes[1].file: ") && Catch::Contains("mesh files total more than"));
}

}  // namespace test_chapter5_scene
