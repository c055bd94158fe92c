// test_util.hpp - shared helpers for the test suite.
#pragma once
#include <string>

#include "scene.hpp"

namespace clrt_test {

inline std::string source_path(const std::string& rel) { return std::string(CLRT_SOURCE_DIR) + "/" + rel; }
inline clrt::Scene load(const std::string& rel) { return clrt::load_scene(source_path(rel)); }

}  // namespace clrt_test
