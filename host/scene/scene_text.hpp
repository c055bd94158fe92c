// scene_text.hpp - how the scene reader's messages write numbers, strings
// from the file and JSON syntax errors (shared by the reader, the -D
// overrides and the schema).
#pragma once
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

namespace clrt {

// A number as the messages show it: 6 significant digits ("1e+08", "0.001").
inline std::string fmt(double v) {
  std::ostringstream os;
  os << v;
  return os.str();
}

// A string from the file, quoted and escaped as JSON, so that a key such as
// "a\nb" cannot break the one-line message. Long strings are cut (a 50 MB
// key must not be echoed in full).
inline std::string json_quoted(const std::string& s) {
  using json = nlohmann::json;
  constexpr size_t kMaxEcho = 64;
  const std::string shown = json(s.substr(0, kMaxEcho)).dump(-1, ' ', false, json::error_handler_t::replace);
  return s.size() <= kMaxEcho ? shown : shown + "... (" + std::to_string(s.size()) + " bytes)";
}

// nlohmann's parse error as one short line: "malformed JSON: parse error at
// line 1, column 4: ...", or "number out of range: ..." for a literal such
// as 1e400 (valid JSON that overflows a double).
std::string parse_error_text(const nlohmann::detail::exception& e);

}  // namespace clrt
