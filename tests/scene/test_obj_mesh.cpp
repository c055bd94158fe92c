// test_obj_mesh.cpp - OBJ meshes: reading, triangulation, the transform, the
// shipped icosphere, and every rejected input.
#include <unistd.h>

#include <atomic>
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <tuple>

#include "scene/obj_mesh.hpp"
#include "test_util.hpp"
#include "util/error.hpp"

// (clrt_tests is a unity build: each file's code is in a namespace of its own.)
namespace test_obj_mesh {

using namespace clrt;

namespace {

// A file in the temporary directory, removed when it goes out of scope.
struct TempObj {
  std::string path;
  explicit TempObj(const std::string& text, const std::string& ext = ".obj") {
    static std::atomic<int> counter{0};
    path = (std::filesystem::temp_directory_path() /
            ("clrt_test_obj_mesh_" + std::to_string(::getpid()) + "_" + std::to_string(counter++) + ext))
               .string();
    std::ofstream(path, std::ios::binary) << text;
  }
  ~TempObj() {
    std::error_code ec;
    std::filesystem::remove(path, ec);
  }
};

Material red() {
  Material m;
  m.color = {255, 0, 0};
  m.specular = 10;
  m.reflective = 0.25;
  return m;
}

std::vector<Triangle> load(const std::string& path, const MeshTransform& t = {}, size_t max_triangles = 1000,
                           size_t max_bytes = 1 << 20) {
  return load_obj_mesh(path, t, red(), max_triangles, max_bytes);
}

void check_vec(Vec3 a, Vec3 b, double tol = 1e-12) {
  CHECK(a.x == Approx(b.x).margin(tol));
  CHECK(a.y == Approx(b.y).margin(tol));
  CHECK(a.z == Approx(b.z).margin(tol));
}

// The loader throws UserError and the message names the file.
void require_rejected(const std::string& path, const MeshTransform& t = {}, size_t max_triangles = 1000,
                      size_t max_bytes = 1 << 20) {
  REQUIRE_THROWS_AS(load(path, t, max_triangles, max_bytes), UserError);
  try {
    load(path, t, max_triangles, max_bytes);
  } catch (const UserError& e) {
    const std::string what = e.what();
    INFO(what);
    CHECK(what.rfind(path + ": ", 0) == 0);
    CHECK(what.find('\n') == std::string::npos);
  }
}

}  // namespace

TEST_CASE("an OBJ triangle loads with its vertices and the material", "[mesh]") {
  TempObj f("# a comment\nv 0 0 0\nv 1 0 0\nv 0 2 0.5\nvn 0 0 1\nf 1//1 2//1 3//1\n");
  auto tris = load(f.path);
  REQUIRE(tris.size() == 1);
  check_vec(tris[0].v0, {0, 0, 0}, 0);
  check_vec(tris[0].v1, {1, 0, 0}, 0);
  check_vec(tris[0].v2, {0, 2, 0.5}, 0);
  CHECK(tris[0].material.color.x == 255);
  CHECK(tris[0].material.specular == 10);
  CHECK(tris[0].material.reflective == 0.25);
}

TEST_CASE("OBJ quads become two triangles, relative indices and CRLF work", "[mesh]") {
  TempObj f("v 0 0 0\r\nv 1 0 0\r\nv 1 1 0\r\nv 0 1 0\r\nf -4 -3 -2 -1\r\n");
  auto tris = load(f.path);
  REQUIRE(tris.size() == 2);
  // The two triangles cover the square: areas 1/2 each, every corner used.
  double area = 0;
  for (const auto& t : tris) {
    const Vec3 a = t.v1 - t.v0, b = t.v2 - t.v0;
    area += 0.5 * std::fabs(a.x * b.y - a.y * b.x);
    for (Vec3 v : {t.v0, t.v1, t.v2}) CHECK((v.z == 0 && (v.x == 0 || v.x == 1) && (v.y == 0 || v.y == 1)));
  }
  CHECK(area == Approx(1));
  // A pentagon: three triangles.
  TempObj g("v 0 0 0\nv 2 0 0\nv 2 1 0\nv 1 2 0\nv 0 1 0\nf 1 2 3 4 5\n");
  CHECK(load(g.path).size() == 3);
}

TEST_CASE("plain triangles read by the scan are the faces tinyobjloader makes", "[mesh]") {
  // "f 1 2 3" files skip tinyobjloader (obj_mesh.cpp); the same faces with
  // texture indices ("1/1") go through it: both meshes must be equal, with
  // relative indices, forward references and CRLF lines among them.
  std::string plain, textured;
  for (int i = 0; i < 6; ++i) {
    const std::string v = "v " + std::to_string(i) + " " + std::to_string(i * i) + " 0." + std::to_string(i) + "\r\n";
    plain += v;
    textured += v + "vt 0 0\n";
  }
  const char* faces[][3] = {{"1", "2", "3"}, {"-1", "-2", "-3"}, {"4", "-5", "7"}, {"6", "5", "4"}};
  for (auto& f : faces) {
    plain += std::string("f ") + f[0] + " " + f[1] + " " + f[2] + "\n";
    textured += std::string("f ") + f[0] + "/1 " + f[1] + "/1 " + f[2] + "/1\n";
  }
  plain += "v 7 7 7\n", textured += "v 7 7 7\n";  // the forward reference's vertex
  const ObjMesh a = parse_obj_mesh("plain.obj", plain, 100), b = parse_obj_mesh("textured.obj", textured, 100);
  REQUIRE(a.triangles() == 4);
  CHECK(a.faces == b.faces);
  CHECK(a.lines.size() == b.lines.size());
  REQUIRE(a.vertices.size() == b.vertices.size());
  for (size_t i = 0; i < a.vertices.size(); ++i) check_vec(a.vertices[i], b.vertices[i], 0);
  CHECK(a.faces == std::vector<uint32_t>{0, 1, 2, 5, 4, 3, 3, 1, 6, 5, 4, 3});
  // A quad after plain triangles takes tinyobjloader's path: 2 + 2 triangles.
  const ObjMesh c =
      parse_obj_mesh("mixed.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3\nf 1 3 4\nf 1 2 3 4\n", 100);
  CHECK(c.triangles() == 4);
  CHECK(std::vector<uint32_t>(c.faces.begin(), c.faces.begin() + 6) == std::vector<uint32_t>{0, 1, 2, 0, 2, 3});
}

TEST_CASE("the mesh transform scales, rotates about x, y, z in that order, then translates", "[mesh]") {
  TempObj f("v 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 2 3\n");
  {
    MeshTransform t;
    t.rotate_degrees = {0, 0, 90};
    auto tris = load(f.path, t);
    REQUIRE(tris.size() == 1);
    check_vec(tris[0].v0, {0, 1, 0});
    check_vec(tris[0].v1, {-1, 0, 0});
    check_vec(tris[0].v2, {0, 0, 1});
  }
  {
    // Scale 2, Rx(90): (x,y,z) -> (x,-z,y), then Ry(90): (x,y,z) -> (z,y,-x),
    // then translate (y first would give (0,2,0)+translate for v0).
    MeshTransform t;
    t.scale = 2;
    t.rotate_degrees = {90, 90, 0};
    t.translate = {10, 20, 30};
    auto tris = load(f.path, t);
    REQUIRE(tris.size() == 1);
    check_vec(tris[0].v0, Vec3{10, 20, 30} + Vec3{0, 0, -2});  // (2,0,0) -Rx-> (2,0,0) -Ry-> (0,0,-2)
    check_vec(tris[0].v1, Vec3{10, 20, 30} + Vec3{2, 0, 0});   // (0,2,0) -Rx-> (0,0,2) -Ry-> (2,0,0)
    check_vec(tris[0].v2, Vec3{10, 20, 30} + Vec3{0, -2, 0});  // (0,0,2) -Rx-> (0,-2,0) -Ry-> (0,-2,0)
  }
  {
    // A general angle against the matrices written out.
    MeshTransform t;
    t.scale = 0.5;
    t.rotate_degrees = {30, 45, 60};
    t.translate = {1, -2, 3};
    auto tris = load(f.path, t);
    const double pi = 3.14159265358979323846;
    const double a = 30 * pi / 180, b = 45 * pi / 180, c = 60 * pi / 180;
    auto rot = [&](Vec3 p) {
      p = {p.x, std::cos(a) * p.y - std::sin(a) * p.z, std::sin(a) * p.y + std::cos(a) * p.z};
      p = {std::cos(b) * p.x + std::sin(b) * p.z, p.y, -std::sin(b) * p.x + std::cos(b) * p.z};
      p = {std::cos(c) * p.x - std::sin(c) * p.y, std::sin(c) * p.x + std::cos(c) * p.y, p.z};
      return Vec3{1, -2, 3} + p;
    };
    check_vec(tris[0].v0, rot({0.5, 0, 0}));
    check_vec(tris[0].v1, rot({0, 0.5, 0}));
    check_vec(tris[0].v2, rot({0, 0, 0.5}));
  }
}

TEST_CASE("the shipped icosphere is a closed unit sphere wound consistently", "[mesh]") {
  const auto tris =
      load(clrt_test::source_path("scenes/large/models/icosphere.obj"), {}, kMaxMeshTriangles, kMaxMeshBytes);
  REQUIRE(tris.size() == 5120);
  using Key = std::tuple<double, double, double>;
  auto key = [](Vec3 v) { return Key{v.x, v.y, v.z}; };
  // Directed edge counts: every edge once in each direction.
  std::map<std::pair<Key, Key>, int> directed;
  size_t far = 0, outward = 0;
  for (const auto& t : tris) {
    const Vec3 vs[3] = {t.v0, t.v1, t.v2};
    for (int k = 0; k < 3; ++k) {
      far += std::fabs(length(vs[k]) - 1) > 1e-8;
      ++directed[{key(vs[k]), key(vs[(k + 1) % 3])}];
    }
    const Vec3 a = t.v1 - t.v0, b = t.v2 - t.v0;
    const Vec3 n{a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
    outward += dot(n, t.v0 + t.v1 + t.v2) > 0;
  }
  CHECK(far == 0);
  CHECK(outward == tris.size());  // counter-clockwise seen from outside
  CHECK(directed.size() == 3 * tris.size());
  size_t bad = 0;
  for (const auto& [edge, count] : directed) {
    const auto reverse = directed.find({edge.second, edge.first});
    bad += count != 1 || reverse == directed.end() || reverse->second != 1;
  }
  CHECK(bad == 0);  // each undirected edge in exactly two triangles, traversed in opposite directions
  CHECK(directed.size() / 2 == 7680);  // E = 3F/2 (V - E + F = 2562 - 7680 + 5120 = 2)
}

TEST_CASE("mtllib and other statements are ignored, no other file is opened", "[mesh]") {
  // An existing, malformed .mtl beside the mesh: were it read, it could only
  // add warnings; the mesh loads with the scene's material either way.
  TempObj mtl("this is not a material file\n", ".mtl");
  const std::string mtl_name = std::filesystem::path(mtl.path).filename().string();
  TempObj f(
      "mtllib evil.mtl\nmtllib " + mtl_name +
      "\nusemtl evil\no thing\ng group\ns 1\nv 0 0 0\nv 1 0 0 # a comment\nv 0 1 0\nvt 0 0\nl 1 2\nt crease 1/0/0 5\n"
      "f 1/1 2/1 3/1 # another\n");
  auto tris = load(f.path);
  REQUIRE(tris.size() == 1);
  CHECK(tris[0].material.color.x == 255);
}

TEST_CASE("bad OBJ files and transforms are UserErrors naming the file", "[mesh]") {
  const std::string missing =
      (std::filesystem::temp_directory_path() / ("clrt_no_such_mesh_" + std::to_string(::getpid()) + ".obj")).string();
  require_rejected(missing);
  require_rejected(std::filesystem::temp_directory_path().string());  // a directory

  const std::string tri = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
  for (const char* text : {"",                                       // empty: no faces
                           "v 0 0 0\nv 1 0 0\nv 0 1 0\n",            // no faces
                           "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n",   // index out of range
                           "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 -4\n",  // relative index out of range
                           "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 0\n",   // index 0
                           "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2\n",     // two vertices
                           "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 x\n",   // not an index
                           "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 99999999999\n",
                           "v nan 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n",  // non-finite
                           "v inf 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", "v 1e999 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n",
                           "v 1e300 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n",  // outside ±kMaxLength
                           "v abc 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n",    // not a number
                           "v 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"}) {     // two coordinates
    TempObj f(text);
    INFO(text);
    require_rejected(f.path);
  }
  {
    TempObj f(std::string("v 0 0 0\nv 1 0 0\nv 0 1 0\0\nf 1 2 3\n", 30));  // a NUL byte
    require_rejected(f.path);
  }
  {
    // Within range as written, outside once scaled.
    TempObj f(tri + "f 1 2 3\n");
    MeshTransform t;
    t.scale = 2e8;
    require_rejected(f.path, t);
  }
  {
    TempObj f(tri + "f 1 2 3\n");
    MeshTransform t;
    for (double s : {0.0, -1.0, std::nan(""), HUGE_VAL}) {
      t.scale = s;
      require_rejected(f.path, t);
    }
    t = {};
    t.rotate_degrees = {0, std::nan(""), 0};
    require_rejected(f.path, t);
    t = {};
    t.translate = {0, 0, 1e9};
    require_rejected(f.path, t);
    t = {};
    CHECK(load(f.path, t).size() == 1);
  }
  {
    // More triangles than allowed: two faces, limit 1; a quad counts as 2.
    TempObj f(tri + "f 1 2 3\nf 3 2 1\n");
    CHECK(load(f.path, {}, 2).size() == 2);
    require_rejected(f.path, {}, 1);
    TempObj q("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n");
    require_rejected(q.path, {}, 1);
  }
  {
    // Over max_bytes (and exactly at it: fine).
    const std::string text = tri + "f 1 2 3\n";
    TempObj f(text);
    CHECK(load(f.path, {}, 10, text.size()).size() == 1);
    require_rejected(f.path, {}, 10, text.size() - 1);
  }
  {
    // A face with more vertices than kMaxFaceVertices.
    std::string text;
    for (size_t i = 0; i <= kMaxFaceVertices; ++i) {
      const double a = 2 * 3.14159265358979 * double(i) / double(kMaxFaceVertices + 1);
      text += "v " + std::to_string(std::cos(a)) + " " + std::to_string(std::sin(a)) + " 0\n";
    }
    text += "f";
    for (size_t i = 1; i <= kMaxFaceVertices + 1; ++i) text += " " + std::to_string(i);
    TempObj f(text + "\n");
    require_rejected(f.path);
  }
  {
    // Not a regular file.
    if (std::filesystem::exists("/dev/zero")) require_rejected("/dev/zero");
  }
}

}  // namespace test_obj_mesh
