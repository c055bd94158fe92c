// scene_schema.cpp - the JSON Schema of scene files, key by key from the
// table (scene_keys.hpp).
#include "scene/scene_schema.hpp"

#include <cmath>
#include <nlohmann/json.hpp>

#include "scene/scene_keys.hpp"
#include "scene/scene_text.hpp"

namespace clrt {

// (A named namespace: clrt_core is a unity build.)
namespace scene_schema {

using ojson = nlohmann::ordered_json;

// A bound as JSON: an integer where it is one (255, not 255.0).
ojson bound(double v) {
  if (v == std::floor(v) && std::fabs(v) < 1e15) return static_cast<long long>(v);
  return v;
}

ojson number_schema(Rule rule, double lo, double hi) {
  switch (rule) {
    case Rule::Range:
    case Rule::Size:
    case Rule::Coordinate:
    case Rule::Color:
    case Rule::Angles:
      return {{"type", "number"}, {"minimum", bound(lo)}, {"maximum", bound(hi)}};
    case Rule::Specular:
      return {{"anyOf",
               ojson::array({{{"const", -1}}, {{"type", "number"}, {"minimum", bound(lo)}, {"maximum", bound(hi)}}})}};
    default:
      return {{"type", "number"}};
  }
}

ojson array_of(const ojson& items, size_t n) {
  return {{"type", "array"}, {"minItems", n}, {"maxItems", n}, {"items", items}};
}

ojson ref(Ctx c) {
  return {{"$ref", "#/$defs/" + std::string(context(c).noun)}};
}

ojson value_schema(const Key& k) {
  switch (k.kind) {
    case Kind::Number:
      return number_schema(k.rule, k.lo, k.hi);
    case Kind::Integer:
      return {{"type", "integer"}, {"minimum", static_cast<long long>(k.lo)}, {"maximum", static_cast<long long>(k.hi)}};
    case Kind::Vector: {
      ojson s = array_of(number_schema(k.rule, k.lo, k.hi), k.size);
      if (k.rule == Rule::Direction || k.rule == Rule::Normal) s["not"] = {{"const", {0, 0, 0}}};
      return s;
    }
    case Kind::Matrix:
      return array_of(array_of({{"type", "number"}}, 3), 3);
    case Kind::Vertices:
      return array_of(array_of(number_schema(k.rule, k.lo, k.hi), 3), 3);
    case Kind::Choice: {
      ojson choices = ojson::array();
      for (std::string_view c : k.choices)
        if (!c.empty()) choices.push_back(std::string(c));
      return {{"enum", choices}};
    }
    case Kind::Path:
      // Relative, without "..": no leading '/', no ".." component.
      return {{"type", "string"},
              {"minLength", 1},
              {"not", {{"anyOf", ojson::array({{{"pattern", "^/"}}, {{"pattern", "(^|/)\\.\\.(/|$)"}}})}}}};
    case Kind::Object:
      return ref(k.element);
    case Kind::Objects:
    default:
      return {{"type", "array"}, {"maxItems", SceneLimits{}.*(k.limit)}, {"items", ref(k.element)}};
  }
}

// What the schema cannot say of a key, in words (clrt validate checks it).
std::string beyond_schema(const Key& k) {
  switch (k.rule) {
    case Rule::IntensitySum:
      return "; clrt also checks that the intensities add up to at most " + fmt(k.hi);
    case Rule::RayReach:
      return "; clrt also checks that for each row r of the rotation |r0| Vw/2 + |r1| Vh/2 + |r2| d is at most " +
             fmt(k.hi);
    default:
      break;
  }
  if (k.kind == Kind::Integer) return "; an integer literal (3, not 3.0)";
  if (k.kind == Kind::Path) return "; clrt also checks that the file can be read and parsed";
  return "";
}

ojson key_schema(const Key& k) {
  ojson s = {{"description", std::string(k.about) + beyond_schema(k)}};
  s.update(value_schema(k));
  if (!k.fallback.empty()) s["default"] = ojson::parse(k.fallback);
  return s;
}

// The keys a variant (a light's "type") requires and the ones it does not have.
ojson variants_schema(Ctx c, const Key& selector) {
  ojson all = ojson::array();
  for (size_t i = 0; i < selector.choices.size() && !selector.choices[i].empty(); ++i) {
    ojson required = ojson::array(), absent = ojson::object();
    for (const Key& k : keys_of(c)) {
      if (!k.variants) continue;
      if (k.variants >> i & 1) {
        if (k.required) required.push_back(std::string(k.name));
      } else {
        absent[std::string(k.name)] = false;
      }
    }
    ojson then = ojson::object();
    if (!required.empty()) then["required"] = required;
    if (!absent.empty()) then["properties"] = absent;
    all.push_back({{"if",
                    {{"properties", {{std::string(selector.name), {{"const", std::string(selector.choices[i])}}}}},
                     {"required", ojson::array({std::string(selector.name)})}}},
                   {"then", then}});
  }
  return all;
}

ojson object_schema(Ctx c, const std::string& description) {
  ojson properties = ojson::object(), required = ojson::array();
  for (const Key& k : keys_of(c)) {
    properties[std::string(k.name)] = key_schema(k);
    if (k.required && !k.variants) required.push_back(std::string(k.name));
  }
  ojson s = {{"description", description}, {"type", "object"}, {"properties", properties}};
  if (!required.empty()) s["required"] = required;
  s["additionalProperties"] = false;
  if (const Key* selector = variant_key(c)) s["allOf"] = variants_schema(c, *selector);
  return s;
}

}  // namespace scene_schema

std::string scene_schema_text() {
  using namespace scene_schema;
  ojson schema = {
      {"$schema", "https://json-schema.org/draft/2020-12/schema"},
      {"title", "clrt scene"},
  };
  schema.update(object_schema(
      Ctx::Root,
      "A scene of clrt, the OpenCL Whitted ray tracer (docs/reference/scene-format.md). Made from the table of "
      "keys (host/scene/scene_keys.cpp) by `clrt validate --schema`; `clrt validate SCENE...` checks a file against "
      "the same rules and the few this schema cannot state. Keys are unique in every object."));
  ojson defs = ojson::object();
  for (Ctx c : {Ctx::Camera, Ctx::Sphere, Ctx::Light, Ctx::Plane, Ctx::Triangle, Ctx::Mesh})
    defs[std::string(context(c).noun)] = object_schema(c, "a " + std::string(context(c).noun));
  schema["$defs"] = defs;
  return schema.dump(2) + "\n";
}

}  // namespace clrt
