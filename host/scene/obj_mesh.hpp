// obj_mesh.hpp - triangle meshes from Wavefront OBJ files (tinyobjloader),
// placed in the scene by a MeshTransform.
#pragma once
#include <cstddef>
#include <string>
#include <vector>

#include "scene/scene.hpp"

namespace clrt {

// A mesh's placement: v' = translate + R (scale * v), with R = Rz * Ry * Rx
// for rotate = (x, y, z) angles in degrees (x applied first).
struct MeshTransform {
  Vec3 translate{0, 0, 0};
  Vec3 rotate_degrees{0, 0, 0};
  double scale = 1;
};

// The triangles of an OBJ file (polygons triangulated as tinyobjloader
// does), transformed, each with `material`, in file order. Only vertex
// positions (`v`) and faces (`f`) are read; normals, texture coordinates,
// groups and materials (`mtllib`, `usemtl`) are ignored, and no file other
// than `path` is ever opened. The file is untrusted: UserError
// ("<path>: <what>") for an unreadable, missing or non-regular file, one
// larger than max_bytes, a malformed vertex or face line, a face with fewer
// than 3 or more than kMaxFaceVertices vertices, a face index out of range,
// a non-finite coordinate, no faces, more than max_triangles triangles, a
// polygon tinyobjloader cannot triangulate completely, any transformed
// coordinate outside ±kMaxLength (scene.hpp), or a bad transform (scale not
// finite and > 0, an angle not finite, translate outside ±kMaxLength).
std::vector<Triangle> load_obj_mesh(const std::string& path, const MeshTransform& transform, const Material& material,
                                    size_t max_triangles, size_t max_bytes);

// The largest mesh file and triangle count a scene may load (the defaults
// the scene parser passes): 256 MiB and 4 000 000 triangles.
constexpr size_t kMaxMeshBytes = size_t(256) << 20, kMaxMeshTriangles = 4000000;
// The most vertices one face (polygon) may have: tinyobjloader's ear
// clipping takes time cubic in a polygon's vertex count.
constexpr size_t kMaxFaceVertices = 256;

}  // namespace clrt
