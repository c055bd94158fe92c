// scene_schema.hpp - a JSON Schema (draft 2020-12) of scene files, made from
// the table of keys (scene_keys.hpp): for editors and for the CI of a
// repository of scenes. `clrt validate --schema` prints it; a copy is
// committed as docs/reference/scene.schema.json (a test keeps it equal).
#pragma once
#include <string>

namespace clrt {

// The schema as JSON text, indented by 2, ending in a newline. It says every
// key, type, range, default and required key; what it cannot say (the sum of
// the lights' intensities, the camera's ray directions, 3.0 not being an
// integer, mesh files that can be read) is in its descriptions, and
// `clrt validate` checks it.
std::string scene_schema_text();

}  // namespace clrt
