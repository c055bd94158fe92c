// csv.hpp - CSV as clrt writes it (RFC 4180), the one helper every CSV goes
// through: a field is quoted when it holds a comma, a double quote, CR or LF,
// with each double quote doubled, and bare otherwise (so numbers and plain
// names stay bare); a record is its fields joined by commas, ending in LF.
// CsvTable names each value as it is added, so a header and its rows cannot
// drift apart: every row has the header's columns, in the header's order,
// and a column a row does not set is an empty field.
#pragma once
#include <sstream>
#include <string>
#include <vector>

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

// One record: every field through csv_field, joined by commas, then LF.
inline std::string csv_record(const std::vector<std::string>& fields) {
  std::string out;
  for (size_t k = 0; k < fields.size(); ++k) out += (k ? "," : "") + csv_field(fields[k]);
  return out + "\n";
}

// A number as CSV holds it: the stream's default form (6 significant digits).
template <class T>
std::string csv_number(const T& v) {
  std::ostringstream o;
  o << v;
  return o.str();
}

class CsvTable {
 public:
  // Starts a row; set() then fills it by column name.
  void row() { rows_.emplace_back(names_.size()); }
  // The column NAME of the current row; the first row's calls fix the column
  // order (later rows may only name columns the first row named).
  void set(const std::string& name, const std::string& value) {
    size_t k = 0;
    while (k < names_.size() && names_[k] != name) ++k;
    if (k == names_.size()) {
      names_.push_back(name);
      for (auto& r : rows_) r.resize(names_.size());
    }
    rows_.back()[k] = value;
  }
  template <class T>
  void set_number(const std::string& name, const T& v) {
    set(name, csv_number(v));
  }
  const std::vector<std::string>& names() const { return names_; }
  std::string text() const {
    std::string out = csv_record(names_);
    for (const auto& r : rows_) out += csv_record(r);
    return out;
  }

 private:
  std::vector<std::string> names_;
  std::vector<std::vector<std::string>> rows_;
};

}  // namespace clrt
