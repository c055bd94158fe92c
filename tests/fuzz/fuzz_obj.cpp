// fuzz_obj.cpp - libFuzzer target for the OBJ mesh reader: any text must
// either give a mesh or raise a one-line UserError naming the file; a mesh
// that parses has only indices within its vertices, and places (at the
// identity) into that many triangles or into such an error.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "scene/obj_mesh.hpp"
#include "util/error.hpp"

namespace {

[[noreturn]] void die(const char* what, const std::string& detail) {
  std::fprintf(stderr, "fuzz_obj: %s: %s\n", what, detail.c_str());
  std::abort();
}

void check_message(const clrt::UserError& e) {
  const std::string msg = e.what();
  if (msg.rfind("fuzz.obj: ", 0) != 0) die("error does not name the file", msg);
  if (msg.find('\n') != std::string::npos) die("error is not one line", msg);
}

// Small enough that libFuzzer's inputs (4 KiB by default) reach it.
constexpr size_t kMaxTriangles = 1000;

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  clrt::ObjMesh mesh;
  try {
    mesh = clrt::parse_obj_mesh("fuzz.obj", std::string(reinterpret_cast<const char*>(data), size), kMaxTriangles);
  } catch (const clrt::UserError& e) {
    check_message(e);
    return 0;
  }
  // Any other exception escapes and libFuzzer reports it as a crash.
  if (mesh.faces.empty() || mesh.faces.size() % 3 != 0)
    die("faces are not whole triangles", std::to_string(mesh.faces.size()));
  if (mesh.triangles() > kMaxTriangles) die("more triangles than the limit", std::to_string(mesh.triangles()));
  if (mesh.lines.size() != mesh.vertices.size()) die("a vertex without its line", std::to_string(mesh.lines.size()));
  for (uint32_t index : mesh.faces)
    if (index >= mesh.vertices.size()) die("a face index past the vertices", std::to_string(index));
  try {
    const auto triangles = clrt::place_obj_mesh("fuzz.obj", mesh, clrt::MeshTransform{}, clrt::Material{});
    if (triangles.size() != mesh.triangles())
      die("placed a different number of triangles", std::to_string(triangles.size()));
  } catch (const clrt::UserError& e) {
    check_message(e);
  }
  return 0;
}
