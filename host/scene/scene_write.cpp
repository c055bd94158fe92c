// scene_write.cpp - scene_to_json: a scene written back as the table
// (scene_keys.hpp) says, key by key, each array element by element.
#include <string>
#include <vector>

#include "scene/scene_json.hpp"
#include "scene/scene_keys.hpp"

namespace clrt {

namespace {

using json = nlohmann::json;

// Per key of the table (by its place in all_keys()): its name as a
// std::string and its default as JSON, made once (a million spheres would
// otherwise make them a million times).
struct KeyTexts {
  std::vector<std::string> names;
  std::vector<json> defaults;
};
const KeyTexts& key_texts() {
  static const KeyTexts texts = [] {
    KeyTexts t;
    for (const Key& k : all_keys()) {
      t.names.emplace_back(k.name);
      t.defaults.push_back(k.fallback.empty() ? json() : json::parse(k.fallback));
    }
    return t;
  }();
  return texts;
}

// The keys of `object` (of context c) that are values, into `item` (reused
// from element to element): a variant's keys only on its variant, the keys
// written unless default only where they differ.
void fill_object(json& item, Ctx c, const void* object) {
  const KeyTexts& texts = key_texts();
  const Key* selector = variant_key(c);
  const size_t variant = selector ? choice_index(*selector, object) : 0;
  const size_t base = size_t(keys_of(c).first - all_keys().first);
  for (const Key& k : keys_of(c)) {
    if (k.kind == Kind::Object || k.kind == Kind::Objects) continue;
    const size_t i = base + key_index(k);
    bool written = k.write != Write::Never;
    if (written && k.variants) written = k.variants >> variant & 1;
    json value = written ? value_json(k, object) : json();
    if (written && k.write == Write::UnlessDefault) written = value != texts.defaults[i];
    if (written)
      item[texts.names[i]] = std::move(value);
    else
      item.erase(texts.names[i]);
  }
}

// The elements of the scene's array of context c.
struct Elements {
  size_t count = 0;
  const void* (*at)(const Scene& s, size_t i) = nullptr;
};
Elements elements_of(const Scene& s, Ctx c) {
  switch (c) {
    case Ctx::Sphere:
      return {s.spheres.size(), [](const Scene& scene, size_t i) -> const void* { return &scene.spheres[i]; }};
    case Ctx::Light:
      return {s.lights.size(), [](const Scene& scene, size_t i) -> const void* { return &scene.lights[i]; }};
    case Ctx::Plane:
      return {s.planes.size(), [](const Scene& scene, size_t i) -> const void* { return &scene.planes[i]; }};
    case Ctx::Triangle:
      return {s.triangles.size(), [](const Scene& scene, size_t i) -> const void* { return &scene.triangles[i]; }};
    default:  // meshes: written as their faces, in "triangles"
      return {};
  }
}

// The array of Objects key k, appended to `text` element by element, with the
// text json::dump gives for it as an element of the root (a document tree of
// a million spheres would take about 1.4 GB).
void append_elements(std::string& text, const Scene& s, const Key& k, bool pretty) {
  const Elements elements = elements_of(s, k.element);
  text += '[';
  json item = json::object();
  for (size_t i = 0; i < elements.count; ++i) {
    fill_object(item, k.element, elements.at(s, i));
    if (pretty) {
      // An element of a key of the root: indented two levels deeper.
      text += i == 0 ? "\n    " : ",\n    ";
      for (char c : item.dump(2)) {
        text += c;
        if (c == '\n') text += "    ";
      }
    } else {
      if (i > 0) text += ',';
      text += item.dump();
    }
  }
  text += pretty ? "\n  ]" : "]";
}

// The marker that stands for key k's elements in the root's text (no string
// of a scene can be one).
std::string marker_of(const Key& k) {
  return "\"@clrt-" + std::string(k.name) + "@\"";
}

}  // namespace

std::string scene_to_json(const Scene& s, JsonStyle style) {
  const bool pretty = style == JsonStyle::Pretty;
  json root = json::object();
  fill_object(root, Ctx::Root, &s);
  std::vector<const Key*> streamed;
  for (const Key& k : keys_of(Ctx::Root)) {
    if (k.kind == Kind::Object) {
      json item = json::object();
      fill_object(item, k.element, &s.camera);  // (the root's one object: the camera)
      root[std::string(k.name)] = item;
    }
    if (k.kind != Kind::Objects || k.write == Write::Never) continue;
    const size_t count = elements_of(s, k.element).count;
    if (count == 0 && k.write == Write::UnlessDefault) continue;
    root[std::string(k.name)] = count == 0 ? json::array() : json(marker_of(k).substr(1, marker_of(k).size() - 2));
    if (count > 0) streamed.push_back(&k);
  }
  const std::string skeleton = pretty ? root.dump(2) : root.dump();
  // The skeleton with each marker replaced by its array.
  std::string text;
  size_t from = 0;
  while (true) {
    size_t at = std::string::npos;
    const Key* next = nullptr;
    for (const Key* k : streamed) {
      const size_t found = skeleton.find(marker_of(*k), from);
      if (found < at) at = found, next = k;
    }
    if (!next) break;
    text.append(skeleton, from, at - from);
    append_elements(text, s, *next, pretty);
    from = at + marker_of(*next).size();
  }
  text.append(skeleton, from, std::string::npos);
  return text;
}

}  // namespace clrt
