// scene_json.hpp - scenes from and to JSON text: a strict parser (unknown
// keys, duplicate keys, wrong types, non-finite numbers and values outside
// the range of scene.hpp are rejected with a one-line message naming the
// file). The parser streams: it builds the scene sphere by sphere while it
// reads (one SAX pass, no document tree), so loading a file takes the memory
// of the Scene, not of its text.
#pragma once
#include <cstddef>
#include <functional>
#include <iosfwd>
#include <string>
#include <vector>

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

// A key of the format (scene_keys.hpp).
struct Key;

// `-D PATH=VALUE` on the command line: a value set as if the scene file said
// so (docs/reference/scene-format.md#overrides). PATH's segments are keys and
// indices into the scene's arrays ("spheres.2.reflective", or
// "spheres[2].reflective"); VALUE is JSON.
struct SceneOverride {
  std::string text;   // as given: "spheres.2.reflective=0.8"
  std::string path;   // the path, dotted: "spheres.2.reflective"
  std::string shown;  // the path as messages name it: "spheres[2].reflective"
  std::string value;  // the JSON text: "0.8"
  // The path: a key (key set) or an index into the array before it.
  struct Step {
    const Key* key = nullptr;
    size_t index = 0;
  };
  std::vector<Step> steps;
};
using SceneOverrides = std::vector<SceneOverride>;
// The overrides of `-D` texts, checked against the format: UserError naming
// the text for one without '=', a path the format does not have, a value that
// is not JSON, or a path given twice. Whether the scene has the element a
// path names, and whether the value keeps the key's rules, is checked as the
// scene is read.
SceneOverrides parse_overrides(const std::vector<std::string>& texts);

// Parses and validates a scene; throws UserError("<name>: <path>: <problem>",
// or "-D <text>: <problem>" for a problem of an override). Directional light
// directions are rescaled by a power of two so their largest component lies
// in [0.5, 1) (no length underflows or overflows): the book's lighting does
// not depend on their length.
Scene parse_scene(const std::string& json_text, const std::string& name, const SceneLimits& limits = {},
                  const SceneOverrides& overrides = {});
// The same, read from a stream in 64 KiB chunks: more than limits.bytes is a
// UserError ("<name>: scene file is larger than ..."), and so is a read error.
Scene parse_scene(std::istream& in, const std::string& name, const SceneLimits& limits = {},
                  const SceneOverrides& overrides = {});
// Reads a file (or FIFO, or device) and parses it as it reads; a
// missing/unreadable/oversized file is a UserError.
Scene load_scene(const std::string& path, const SceneLimits& limits = {}, const SceneOverrides& overrides = {});
// Reads a scene file as load_scene does but goes on after a problem: each
// problem (the message load_scene would throw for it) goes to `problem`, and
// the count is returned (0: the scene is valid). Only malformed JSON, and a
// file that cannot be read, end the reading early.
size_t validate_scene(const std::string& path, const std::function<void(const std::string&)>& problem,
                      const SceneLimits& limits = {}, const SceneOverrides& overrides = {});
// Serializes a scene back to JSON text (used by generated test suites).
// Pretty: two-space indents; compact: no white space (large scenes).
enum class JsonStyle { Pretty, Compact };
std::string scene_to_json(const Scene& s, JsonStyle style = JsonStyle::Pretty);

}  // namespace clrt
