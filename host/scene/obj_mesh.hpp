// obj_mesh.hpp - triangle meshes from Wavefront OBJ files (tinyobjloader),
// placed in the scene by a MeshTransform.
#pragma once
#include <cstddef>
#include <cstdint>
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

// An OBJ file read once: its vertex positions (as in the file, with the
// line of each, for messages) and its triangles as vertex indices (polygons
// triangulated as tinyobjloader does), in file order. A scene that names
// the file several times places it once per mention (place_obj_mesh).
struct ObjMesh {
  std::vector<Vec3> vertices;
  std::vector<uint32_t> lines;
  std::vector<uint32_t> faces;  // 3 per triangle
  size_t triangles() const { return faces.size() / 3; }
};

// The bytes of the mesh file open at `fd` (closed here), named `path` in
// messages: UserError ("<path>: <what>") unless it is a regular file of at
// most max_bytes (a FIFO or device is refused, not read).
std::string read_mesh_file(int fd, const std::string& path, size_t max_bytes);

// Parses OBJ text. Only vertex positions (`v`) and faces (`f`) are read;
// normals, texture coordinates, groups and materials (`mtllib`, `usemtl`)
// are ignored, and no file is ever opened. The text is untrusted:
// UserError ("<path>: <what>") for a malformed vertex or face line, a face
// with fewer than 3 or more than kMaxFaceVertices vertices, a face index out
// of range, a non-finite coordinate, no faces, more than max_triangles
// triangles, or a polygon tinyobjloader cannot triangulate completely.
ObjMesh parse_obj_mesh(const std::string& path, std::string text, size_t max_triangles);

// UserError unless the transform is one clrt places meshes with (scale
// finite and > 0, angles finite, translate within ±kMaxLength).
void check_mesh_transform(const std::string& path, const MeshTransform& transform);

// The mesh's triangles, transformed, each with `material`, in file order;
// UserError for a bad transform or for a vertex of a face that lies outside
// ±kMaxLength (scene.hpp) once transformed.
std::vector<Triangle> place_obj_mesh(const std::string& path, const ObjMesh& mesh, const MeshTransform& transform,
                                     const Material& material);

// The three above for the file at `path` (opened as given).
std::vector<Triangle> load_obj_mesh(const std::string& path, const MeshTransform& transform, const Material& material,
                                    size_t max_triangles, size_t max_bytes);

// The largest mesh file and triangle count a scene may load (the defaults
// the scene parser passes): 256 MiB and 4 000 000 triangles.
constexpr size_t kMaxMeshBytes = size_t(256) << 20, kMaxMeshTriangles = 4000000;
// The most vertices one face (polygon) may have: tinyobjloader's ear
// clipping takes time cubic in a polygon's vertex count.
constexpr size_t kMaxFaceVertices = 256;

}  // namespace clrt
