// scene_overrides.cpp - `-D PATH=VALUE`: the path resolved against the table
// of keys (scene_keys.hpp) and the value checked as JSON before any scene is
// read; the reader applies them (scene_objects.cpp).
#include <cctype>
#include <set>

#include "scene/scene_json.hpp"
#include "scene/scene_keys.hpp"
#include "scene/scene_text.hpp"
#include "util/edit_distance.hpp"
#include "util/error.hpp"

namespace clrt {

namespace {

// "spheres.2.reflective" or "spheres[2].reflective" -> {spheres, 2, reflective};
// empty on a malformed path.
std::vector<std::string> path_segments(const std::string& path) {
  std::vector<std::string> segments;
  size_t i = 0;
  while (i <= path.size()) {
    const size_t end = std::min(path.find('.', i), path.size());
    const std::string part = path.substr(i, end - i);
    const size_t bracket = part.find('[');
    const std::string name = part.substr(0, bracket);
    if (!name.empty()) segments.push_back(name);
    if (name.empty() && bracket != 0) return {};  // "a..b", ".a", "a."
    for (size_t at = bracket; at != std::string::npos;) {
      const size_t close = part.find(']', at);
      if (close == std::string::npos || close == at + 1) return {};
      segments.push_back(part.substr(at + 1, close - at - 1));
      at = close + 1;
      if (at == part.size()) break;
      if (part[at] != '[') return {};
    }
    i = end + 1;
  }
  return segments;
}

bool is_index(const std::string& s) {
  if (s.empty() || s.size() > 18) return false;
  for (char c : s)
    if (!std::isdigit(static_cast<unsigned char>(c))) return false;
  return true;
}

// The steps of `segments` through the table; `shown` and `dotted` as they go.
void resolve(SceneOverride& o, const std::vector<std::string>& segments, std::string& dotted) {
  auto fail = [&](const std::string& what) {
    throw UserError("-D " + o.text + ": " + (o.shown.empty() ? "" : o.shown + ": ") + what);
  };
  Ctx ctx = Ctx::Root;
  const Key* array = nullptr;  // the Objects key whose index comes next
  const Key* value = nullptr;  // a key whose value is set whole: nothing may follow
  for (const std::string& segment : segments) {
    if (value)
      fail("is one value, set whole (-D " + o.shown + "=...): it has no keys or elements of its own");
    if (array) {
      if (!is_index(segment))
        fail("expected an index into the array (0, 1, ...), got " + json_quoted(segment));
      const size_t index = std::stoull(segment);
      o.steps.push_back({nullptr, index});
      o.shown += "[" + std::to_string(index) + "]";
      dotted += "." + std::to_string(index);
      ctx = array->element;
      array = nullptr;
      continue;
    }
    const Key* k = find_key(ctx, segment);
    if (!k) {
      std::vector<std::string> names;
      for (const Key& known : keys_of(ctx)) names.emplace_back(known.name);
      const std::string near = closest_match(segment, names);
      fail("unknown key " + json_quoted(segment) + (near.empty() ? "" : "; did you mean \"" + near + "\"?"));
    }
    o.steps.push_back({k, 0});
    o.shown += (o.shown.empty() ? "" : ".") + std::string(k->name);
    dotted += (dotted.empty() ? "" : ".") + std::string(k->name);
    if (k->kind == Kind::Objects)
      array = k;
    else if (k->kind == Kind::Object)
      ctx = k->element;
    else
      value = k;
  }
}

// The value as JSON: UserError with nlohmann's message otherwise.
void check_value(const SceneOverride& o) {
  try {
    const nlohmann::json parsed = nlohmann::json::parse(o.value);
    (void)parsed;
  } catch (const nlohmann::detail::exception& e) {
    std::string hint;
    if (!o.value.empty() && std::isalpha(static_cast<unsigned char>(o.value[0])) && o.value != "true" &&
        o.value != "false" && o.value != "null")
      hint = " (a string is quoted: -D '" + o.text.substr(0, o.text.find('=')) + "=\"" + o.value + "\"')";
    throw UserError("-D " + o.text + ": the value is not JSON: " + parse_error_text(e) + hint);
  }
}

}  // namespace

SceneOverrides parse_overrides(const std::vector<std::string>& texts) {
  SceneOverrides out;
  std::set<std::string> paths;
  for (const std::string& text : texts) {
    SceneOverride o;
    o.text = text;
    const size_t eq = text.find('=');
    if (eq == std::string::npos || eq == 0)
      throw UserError("-D " + text + ": expected PATH=VALUE (e.g. -D recursion_depth=5, -D spheres.0.radius=2)");
    const std::vector<std::string> segments = path_segments(text.substr(0, eq));
    if (segments.empty())
      throw UserError("-D " + text + ": malformed path " + json_quoted(text.substr(0, eq)) +
                      " (keys and indices separated by dots: spheres.0.radius)");
    o.value = text.substr(eq + 1);
    std::string dotted;
    resolve(o, segments, dotted);
    check_value(o);
    if (!paths.insert(o.shown).second) throw UserError("-D " + text + ": " + o.shown + " is given twice");
    o.path = dotted;
    out.push_back(std::move(o));
  }
  return out;
}

}  // namespace clrt
