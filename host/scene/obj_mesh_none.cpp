// obj_mesh_none.cpp - load_obj_mesh in a lean build (CLRT_LEAN=ON, no
// tinyobjloader; CMakeLists.txt builds this file instead of obj_mesh.cpp):
// a scene that names a mesh file is refused (UserError, exit 2) while it is
// parsed, before any OpenCL work.
#include "scene/obj_mesh.hpp"

#include <unistd.h>

#include "util/build_features.hpp"
#include "util/error.hpp"

namespace clrt {

namespace {

[[noreturn]] void refuse(const std::string& path) {
  throw UserError(path + ": " + kLeanBuildNote +
                  ": no OBJ meshes (tinyobjloader); use the full build, or inline \"triangles\" in the scene");
}

}  // namespace

std::string read_mesh_file(int fd, const std::string& path, size_t) {
  ::close(fd);
  refuse(path);
}
ObjMesh parse_obj_mesh(const std::string& path, std::string, size_t) {
  refuse(path);
}
void check_mesh_transform(const std::string&, const MeshTransform&) {}
std::vector<Triangle> place_obj_mesh(const std::string& path, const ObjMesh&, const MeshTransform&, const Material&) {
  refuse(path);
}
std::vector<Triangle> load_obj_mesh(const std::string& path, const MeshTransform&, const Material&, size_t, size_t) {
  refuse(path);
}

}  // namespace clrt
