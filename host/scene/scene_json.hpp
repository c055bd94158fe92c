// scene_json.hpp - scenes from and to JSON text: a strict parser (unknown
// keys, wrong types, non-finite numbers and values outside the range of
// scene.hpp are rejected with a one-line message naming the file).
#pragma once
#include <cstddef>
#include <string>

#include "scene/scene.hpp"

namespace clrt {

// Parses and validates a scene; throws UserError("<name>: <path>: <problem>").
// Directional light directions are rescaled by a power of two so their
// largest component lies in [0.5, 1) (no length underflows or overflows):
// the book's lighting does not depend on their length.
Scene parse_scene(const std::string& json_text, const std::string& name);
// Largest scene file load_scene() accepts.
constexpr size_t kMaxSceneBytes = size_t(64) << 20;
// Reads a file and parses it; a missing/unreadable/oversized file is a UserError.
Scene load_scene(const std::string& path);
// Serializes a scene back to JSON text (used by generated test suites).
// Pretty: two-space indents; compact: no white space (large scenes).
enum class JsonStyle { Pretty, Compact };
std::string scene_to_json(const Scene& s, JsonStyle style = JsonStyle::Pretty);

}  // namespace clrt
