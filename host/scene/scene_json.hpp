// scene_json.hpp - scenes from and to JSON text: a strict parser (unknown
// keys, duplicate keys, wrong types, non-finite numbers and values outside
// the range of scene.hpp are rejected with a one-line message naming the
// file). The parser streams: it builds the scene sphere by sphere while it
// reads (one SAX pass, no document tree), so loading a file takes the memory
// of the Scene, not of its text.
#pragma once
#include <cstddef>
#include <iosfwd>
#include <string>

#include "scene/scene.hpp"

namespace clrt {

// Largest scene file load_scene() accepts (one million spheres take about
// 120 MB of compact JSON, 240 MB of pretty JSON).
constexpr size_t kMaxSceneBytes = size_t(256) << 20;
// Most spheres and lights a scene may have: a bound on the memory any file
// makes the loader take (72 bytes a sphere, 40 a light), well within the
// kernels' 32-bit counts. (Every hit point tries every light, so many lights
// make a slow render; 100 000 still render, tests/app/test_hardening.cpp.)
constexpr size_t kMaxSceneSpheres = size_t(1) << 22, kMaxSceneLights = size_t(1) << 22;  // 4 194 304
// Chapter 5's other primitives: planes are tested by every ray (no
// hierarchy holds them), so few; triangles (inline and from OBJ meshes, see
// obj_mesh.hpp) as many as a mesh may have.
constexpr size_t kMaxScenePlanes = 1024, kMaxSceneTriangles = size_t(4000000), kMaxSceneMeshes = 1024;
// What the loader accepts; tests lower the limits.
struct SceneLimits {
  size_t bytes = kMaxSceneBytes;
  size_t spheres = kMaxSceneSpheres;
  size_t lights = kMaxSceneLights;
  size_t planes = kMaxScenePlanes;
  size_t triangles = kMaxSceneTriangles;  // inline and from meshes together
  size_t meshes = kMaxSceneMeshes;
  // The bytes of every distinct mesh file together (a file named twice is
  // read once and counts once).
  size_t mesh_bytes = size_t(256) << 20;
};
// JSON nesting needs no limit of its own: a scene nests 5 levels deep (root,
// triangles, triangle, vertices, vertex) and the parser stops at the first
// array or object where the format has none.

// Parses and validates a scene; throws UserError("<name>: <path>: <problem>").
// Directional light directions are rescaled by a power of two so their
// largest component lies in [0.5, 1) (no length underflows or overflows):
// the book's lighting does not depend on their length.
Scene parse_scene(const std::string& json_text, const std::string& name, const SceneLimits& limits = {});
// The same, read from a stream in 64 KiB chunks: more than limits.bytes is a
// UserError ("<name>: scene file is larger than ..."), and so is a read error.
Scene parse_scene(std::istream& in, const std::string& name, const SceneLimits& limits = {});
// Reads a file (or FIFO, or device) and parses it as it reads; a
// missing/unreadable/oversized file is a UserError.
Scene load_scene(const std::string& path, const SceneLimits& limits = {});
// Serializes a scene back to JSON text (used by generated test suites).
// Pretty: two-space indents; compact: no white space (large scenes).
enum class JsonStyle { Pretty, Compact };
std::string scene_to_json(const Scene& s, JsonStyle style = JsonStyle::Pretty);

}  // namespace clrt
