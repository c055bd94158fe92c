// scene_values.cpp - the reader's values: each checked by its key's rule
// (scene_keys.hpp) and stored through its key's member.
#include <cmath>
#include <filesystem>
#include <type_traits>

#include "scene/scene_builder.hpp"
#include "scene/scene_text.hpp"

namespace clrt {

template <class Int>
void SceneBuilder::integer(const Target& t, Int v) {
  if (t.role != Role::Value || t.key->kind != Kind::Integer) return number(t, static_cast<double>(v));
  const Key& k = *t.key;
  // Compared as read: an unsigned above LLONG_MAX must not wrap.
  const auto lo = static_cast<long long>(k.lo), hi = static_cast<long long>(k.hi);
  bool in_range = v <= static_cast<Int>(hi);
  if constexpr (std::is_signed_v<Int>) in_range = in_range && v >= static_cast<Int>(lo);
  if (!in_range) {
    report(value_path(),
           "must be in [" + std::to_string(lo) + ", " + std::to_string(hi) + "] (got " + std::to_string(v) + ")");
    return;
  }
  *static_cast<int*>(k.field.at(object_of(k.ctx), 0)) = static_cast<int>(v);
}
template void SceneBuilder::integer(const Target&, number_integer_t);
template void SceneBuilder::integer(const Target&, number_unsigned_t);

void SceneBuilder::number(const Target& t, double v) {
  const bool component = t.role == Role::Component;
  if (!component && (t.role != Role::Value || t.key->kind != Kind::Number)) type_error(t, "number");
  if (!std::isfinite(v)) fail(value_path(), "number is not finite");  // not reached: the parser rejects them
  if (component) {
    numbers_[top().count] = v;
    return;
  }
  if (number_ok(*t.key, v, -1)) *static_cast<double*>(t.key->field.at(object_of(t.key->ctx), 0)) = v;
}

// A number of key k (or its component `component`, >= 0) by the key's rule:
// reported, and false, where it breaks it.
bool SceneBuilder::number_ok(const Key& k, double v, int component) {
  // (The path only for a message: most numbers are fine.)
  const auto where = [&] { return value_path() + (component < 0 ? "" : "[" + std::to_string(component) + "]"); };
  switch (k.rule) {
    case Rule::Range:
      if (v >= k.lo && v <= k.hi) return true;
      report(where(), "must be in [" + fmt(k.lo) + ", " + fmt(k.hi) + "] (got " + fmt(v) + ")");
      return false;
    case Rule::Specular:
      if (v != -1 && v < 0) {
        report(where(), "must be -1 (matte) or >= 0 (got " + fmt(v) + ")");
        return false;
      }
      if (v <= k.hi) return true;
      report(where(), "must be at most " + fmt(k.hi) + " (got " + fmt(v) + ")");
      return false;
    case Rule::Size:
      if (!(v > 0)) {
        report(where(), "must be > 0 (got " + fmt(v) + ")");
        return false;
      }
      if (v >= k.lo && v <= k.hi) return true;
      report(where(), "must be in [" + fmt(k.lo) + ", " + fmt(k.hi) + "], the range clrt renders in float32 (got " +
                          fmt(v) + ")");
      return false;
    case Rule::Coordinate:
      if (std::fabs(v) <= k.hi) return true;
      report(where(), "must be within ±" + fmt(k.hi) + ", the range clrt renders in float32 (got " + fmt(v) + ")");
      return false;
    default:
      return true;
  }
}

void SceneBuilder::text(const Target& t, const std::string& v) {
  if (t.role != Role::Value) type_error(t, "string");
  if (t.key->kind == Kind::Choice) return choose(*t.key, v);
  if (t.key->kind == Kind::Path) return mesh_file(*t.key, v);
  type_error(t, "string");
}

void SceneBuilder::choose(const Key& k, const std::string& v) {
  size_t i = 0;
  while (i < k.choices.size() && (k.choices[i].empty() || k.choices[i] != v)) ++i;
  if (i == k.choices.size()) {
    std::string list;  // "a, b or c"
    size_t n = 0;
    while (n < k.choices.size() && !k.choices[n].empty()) ++n;
    for (size_t j = 0; j < n; ++j) list += (j == 0 ? "" : j + 1 == n ? " or " : ", ") + std::string(k.choices[j]);
    report(value_path(), "unknown " + std::string(k.noun) + " " + json_quoted(v) + " (expected " + list + ")");
    return;
  }
  void* member = k.field.at(object_of(k.ctx), 0);
  if (k.field.type == FieldType::Bool)
    *static_cast<bool*>(member) = i != 0;
  else
    *static_cast<LightType*>(member) = static_cast<LightType>(i);
  if (&k != variant_key(k.ctx)) return;
  // The variant's keys read before it (later ones are checked as they come).
  Frame& f = top();
  f.variant = static_cast<int>(i);
  for (const Key& other : keys_of(k.ctx))
    if (other.variants && (f.seen >> key_index(other) & 1) && !(other.variants >> i & 1))
      report(path(depth_ - 1), "unknown key " + json_quoted(std::string(other.name)));
}

void SceneBuilder::mesh_file(const Key& k, const std::string& file) {
  // A scene names files in its own folder or below it: never an absolute
  // path or "..", so that a scene from elsewhere cannot make clrt read
  // files outside the folder it came in.
  const std::filesystem::path p(file);
  if (file.empty()) return report(value_path(), "must not be empty");
  if (p.is_absolute())
    return report(value_path(), "must be a path relative to the scene's folder (got an absolute path)");
  for (const auto& part : p)
    if (part == "..") return report(value_path(), "must not leave the scene's folder (\"..\")");
  *static_cast<std::string*>(k.field.at(object_of(k.ctx), 0)) = file;
}

// ---- arrays read to their end (value_path() names the array) ----
void SceneBuilder::finish_numbers(const Frame& f) {
  const Key& k = *f.key;
  // A row of a rotation or a vertex of a triangle, or the key's whole value.
  const bool row = depth_ > 0 && top().kind == FrameKind::Rows;
  const size_t n = row || k.kind != Kind::Vector ? 3 : k.size;
  if (f.count != n) return report(value_path(), "expected an array of " + std::to_string(n) + " numbers");
  if (!vector_ok(k, numbers_, n)) return;
  store_vector(k, object_of(k.ctx), row ? top().count : 0, n);
}

// The components of a vector value by its key's rule: the first problem is
// reported (one a value), and false.
bool SceneBuilder::vector_ok(const Key& k, const std::array<double, 3>& c, size_t n) {
  switch (k.rule) {
    case Rule::Color:
      for (size_t i = 0; i < n; ++i)
        if (c[i] < k.lo || c[i] > k.hi) {
          report(value_path(), "color components must be in [" + fmt(k.lo) + ", " + fmt(k.hi) + "] (got " +
                                   fmt(c[i]) + ")");
          return false;
        }
      return true;
    case Rule::Angles:
      for (size_t i = 0; i < n; ++i)
        if (std::fabs(c[i]) > k.hi) {
          report(value_path(), "angles must be within ±1e6 degrees (got " + fmt(c[i]) + ")");
          return false;
        }
      return true;
    case Rule::Size:
      for (size_t i = 0; i < n; ++i)
        if (!(c[i] > 0)) {
          report(value_path(), "sizes must be > 0");
          return false;
        }
      [[fallthrough]];
    case Rule::Coordinate:
      for (size_t i = 0; i < n; ++i)
        if (!number_ok(k, c[i], static_cast<int>(i))) return false;
      return true;
    default:  // None; Direction and Normal: when the object ends
      return true;
  }
}

void SceneBuilder::store_vector(const Key& k, void* object, size_t part, size_t n) {
  const double* c = numbers_.data();
  if (k.kind == Kind::Matrix) {
    double* row = static_cast<double*>(k.field.at(object, part));
    row[0] = c[0], row[1] = c[1], row[2] = c[2];
  } else if (n == 2) {
    *static_cast<double*>(k.field.at(object, 0)) = c[0];
    *static_cast<double*>(k.field.at(object, 1)) = c[1];
  } else {
    *static_cast<Vec3*>(k.field.at(object, part)) = Vec3{c[0], c[1], c[2]};
  }
}

// The array of an Objects key read to its end: its rule over the elements.
void SceneBuilder::finish_array(const Frame& f) {
  if (f.key->rule != Rule::IntensitySum) return;
  double total = 0;
  for (const auto& l : scene_.lights) total += l.intensity;
  if (total > f.key->hi)
    report(value_path(), "the intensities add up to " + fmt(total) + ", more than " + fmt(f.key->hi) +
                             " (colours would overflow float32)");
}

}  // namespace clrt
