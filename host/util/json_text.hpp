// json_text.hpp - JSON as clrt prints it: indented by 2, and never throwing
// on strings that are not UTF-8 (a scene path or --cl-options from the user):
// such bytes become U+FFFD instead of an exception after all the work.
// Reports are nlohmann::ordered_json: keys in the order the code adds them
// (the report header first, docs/guide/output.md).
#pragma once
#include <nlohmann/json.hpp>
#include <string>

namespace clrt {

inline std::string json_text(const nlohmann::json& j) {
  return j.dump(2, ' ', false, nlohmann::json::error_handler_t::replace);
}
inline std::string json_text(const nlohmann::ordered_json& j) {
  return j.dump(2, ' ', false, nlohmann::ordered_json::error_handler_t::replace);
}

}  // namespace clrt
