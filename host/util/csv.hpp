// csv.hpp - one CSV field as RFC 4180 writes it, for every CSV clrt writes:
// quoted when it holds a comma, a double quote, CR or LF, with each double
// quote doubled; as it is otherwise (so numbers and plain names stay bare).
#pragma once
#include <string>

namespace clrt {

inline std::string csv_field(const std::string& value) {
  if (value.find_first_of(",\"\r\n") == std::string::npos) return value;
  std::string out = "\"";
  for (char c : value) {
    if (c == '"') out += '"';
    out += c;
  }
  return out + "\"";
}

}  // namespace clrt
