// obj_mesh_none.cpp - load_obj_mesh in a lean build (CLRT_LEAN=ON, no
// tinyobjloader; CMakeLists.txt builds this file instead of obj_mesh.cpp):
// a scene that names a mesh file is refused (UserError, exit 2) while it is
// parsed, before any OpenCL work.
#include "scene/obj_mesh.hpp"
#include "util/build_features.hpp"
#include "util/error.hpp"

namespace clrt {

std::vector<Triangle> load_obj_mesh(const std::string& path, const MeshTransform&, const Material&, size_t, size_t) {
  throw UserError(path + ": " + kLeanBuildNote +
                  ": no OBJ meshes (tinyobjloader); use the full build, or inline \"triangles\" in the scene");
}

}  // namespace clrt
