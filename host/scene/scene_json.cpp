// scene_json.cpp - strict JSON scene loader: unknown keys, wrong types,
// non-finite numbers and out-of-range values are all rejected with a one-line
// message.
#include "scene/scene_json.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <nlohmann/json.hpp>
#include <sstream>
#include <unordered_set>

#include "clrt_layout.h"
#include "util/error.hpp"

namespace clrt {
namespace {

using json = nlohmann::json;

class Parser {
 public:
  explicit Parser(std::string name) : name_(std::move(name)) {}

  [[noreturn]] void fail(const std::string& where, const std::string& what) const {
    throw UserError(name_ + ": " + (where.empty() ? "" : where + ": ") + what);
  }

  void only_keys(const json& obj, const std::string& where, std::initializer_list<const char*> keys) const {
    if (!obj.is_object()) fail(where, "expected an object, got " + type_of(obj));
    for (auto it = obj.begin(); it != obj.end(); ++it) {
      bool known = false;
      for (const char* k : keys) known = known || it.key() == k;
      if (!known) fail(where, "unknown key " + quoted(it.key()));
    }
  }

  double number(const json& j, const std::string& where) const {
    if (!j.is_number()) fail(where, "expected a number, got " + type_of(j));
    double v = j.get<double>();
    if (!std::isfinite(v)) fail(where, "number is not finite");
    return v;
  }

  double number_in(const json& j, const std::string& where, double lo, double hi) const {
    double v = number(j, where);
    if (v < lo || v > hi) fail(where, "must be in [" + fmt(lo) + ", " + fmt(hi) + "] (got " + fmt(v) + ")");
    return v;
  }

  Vec3 vec3(const json& j, const std::string& where) const {
    if (!j.is_array() || j.size() != 3) fail(where, "expected an array of 3 numbers");
    return {number(j[0], where + "[0]"), number(j[1], where + "[1]"), number(j[2], where + "[2]")};
  }

  // A coordinate within the float32-safe range (scene.hpp).
  Vec3 position(const json& j, const std::string& where) const {
    Vec3 v = vec3(j, where);
    const double c[3] = {v.x, v.y, v.z};
    for (int k = 0; k < 3; ++k)
      if (std::fabs(c[k]) > kMaxLength)
        fail(where + "[" + std::to_string(k) + "]",
             "must be within ±" + fmt(kMaxLength) + ", the range clrt renders in float32 (got " + fmt(c[k]) + ")");
    return v;
  }

  // A size in [kMinLength, kMaxLength]; `positive_message` for <= 0.
  double size(const json& j, const std::string& where, const std::string& positive_message) const {
    const double v = number(j, where);
    if (!(v > 0)) fail(where, positive_message + " (got " + fmt(v) + ")");
    if (v < kMinLength || v > kMaxLength)
      fail(where, "must be in [" + fmt(kMinLength) + ", " + fmt(kMaxLength) +
                      "], the range clrt renders in float32 (got " + fmt(v) + ")");
    return v;
  }

  Vec3 color(const json& j, const std::string& where) const {
    Vec3 c = vec3(j, where);
    for (double v : {c.x, c.y, c.z})
      if (v < 0 || v > 255) fail(where, "color components must be in [0, 255] (got " + fmt(v) + ")");
    return c;
  }

  static std::string type_of(const json& j) { return j.type_name(); }
  // A string from the file, quoted and escaped as JSON, so that a key such as
  // "a\nb" cannot break the one-line message.
  // Long strings are cut (a 50 MB key must not be echoed in full).
  static std::string quoted(const std::string& s) {
    constexpr size_t kMaxEcho = 64;
    const std::string shown = json(s.substr(0, kMaxEcho)).dump(-1, ' ', false, json::error_handler_t::replace);
    return s.size() <= kMaxEcho ? shown : shown + "... (" + std::to_string(s.size()) + " bytes)";
  }
  static std::string fmt(double v) {
    std::ostringstream os;
    os << v;
    return os.str();
  }

  Scene parse(const json& root) const {
    Scene s;
    only_keys(root, "", {"camera", "background", "recursion_depth", "epsilon", "spheres", "lights"});
    if (root.contains("camera")) parse_camera(root["camera"], s.camera);
    if (root.contains("background")) s.background = color(root["background"], "background");
    if (root.contains("recursion_depth")) {
      const json& d = root["recursion_depth"];
      if (!d.is_number_integer()) fail("recursion_depth", "expected an integer, got " + type_of(d));
      // Unsigned first: get<long long>() of a value above LLONG_MAX wraps.
      bool in_range = d.is_number_unsigned() ? d.get<unsigned long long>() <= CLRT_MAX_DEPTH
                                             : d.get<long long>() >= 0 && d.get<long long>() <= CLRT_MAX_DEPTH;
      if (!in_range)
        fail("recursion_depth", "must be in [0, " + std::to_string(CLRT_MAX_DEPTH) + "] (got " + d.dump() + ")");
      s.recursion_depth = static_cast<int>(d.get<long long>());
    }
    if (root.contains("epsilon")) s.epsilon = number_in(root["epsilon"], "epsilon", 0, kMaxLength);
    if (root.contains("spheres")) {
      const json& arr = root["spheres"];
      if (!arr.is_array()) fail("spheres", "expected an array, got " + type_of(arr));
      for (size_t i = 0; i < arr.size(); ++i)
        s.spheres.push_back(parse_sphere(arr[i], "spheres[" + std::to_string(i) + "]"));
    }
    if (root.contains("lights")) {
      const json& arr = root["lights"];
      if (!arr.is_array()) fail("lights", "expected an array, got " + type_of(arr));
      for (size_t i = 0; i < arr.size(); ++i)
        s.lights.push_back(parse_light(arr[i], "lights[" + std::to_string(i) + "]"));
      double total = 0;
      for (const auto& l : s.lights) total += l.intensity;
      if (total > kMaxTotalIntensity)
        fail("lights", "the intensities add up to " + fmt(total) + ", more than " + fmt(kMaxTotalIntensity) +
                           " (colours would overflow float32)");
    }
    // The camera's ray directions: rotation x (viewport/2, viewport/2, d).
    const auto& r = s.camera.rotation;
    const double half_w = s.camera.viewport_w / 2, half_h = s.camera.viewport_h / 2, d = s.camera.projection_plane_d;
    for (int row = 0; row < 3; ++row) {
      const double reach =
          std::fabs(r[row * 3]) * half_w + std::fabs(r[row * 3 + 1]) * half_h + std::fabs(r[row * 3 + 2]) * d;
      if (reach > kMaxLength)
        fail("camera", "ray directions reach " + fmt(reach) + " (rotation row " + std::to_string(row) +
                           " times viewport and projection distance), more than " + fmt(kMaxLength) +
                           ", the range clrt renders in float32");
    }
    return s;
  }

  void parse_camera(const json& j, Camera& c) const {
    only_keys(j, "camera", {"position", "rotation", "viewport", "projection_plane_d"});
    if (j.contains("position")) c.position = position(j["position"], "camera.position");
    if (j.contains("rotation")) {
      const json& r = j["rotation"];
      if (!r.is_array() || r.size() != 3) fail("camera.rotation", "expected a 3x3 array of numbers");
      for (int row = 0; row < 3; ++row) {
        Vec3 v = vec3(r[row], "camera.rotation[" + std::to_string(row) + "]");
        c.rotation[row * 3 + 0] = v.x;
        c.rotation[row * 3 + 1] = v.y;
        c.rotation[row * 3 + 2] = v.z;
      }
    }
    if (j.contains("viewport")) {
      const json& v = j["viewport"];
      if (!v.is_array() || v.size() != 2) fail("camera.viewport", "expected an array of 2 numbers");
      for (int k = 0; k < 2; ++k)
        if (!(number(v[k], "camera.viewport[" + std::to_string(k) + "]") > 0))
          fail("camera.viewport", "sizes must be > 0");
      c.viewport_w = size(v[0], "camera.viewport[0]", "must be > 0");
      c.viewport_h = size(v[1], "camera.viewport[1]", "must be > 0");
    }
    if (j.contains("projection_plane_d")) {
      c.projection_plane_d = size(j["projection_plane_d"], "camera.projection_plane_d", "must be > 0");
    }
  }

  Sphere parse_sphere(const json& j, const std::string& w) const {
    only_keys(j, w, {"center", "radius", "color", "specular", "reflective"});
    Sphere s;
    if (!j.contains("center")) fail(w, "missing \"center\"");
    if (!j.contains("radius")) fail(w, "missing \"radius\"");
    if (!j.contains("color")) fail(w, "missing \"color\"");
    s.center = position(j["center"], w + ".center");
    s.radius = size(j["radius"], w + ".radius", "must be > 0");
    s.color = color(j["color"], w + ".color");
    if (j.contains("specular")) {
      s.specular = number(j["specular"], w + ".specular");
      if (s.specular != -1 && s.specular < 0)
        fail(w + ".specular", "must be -1 (matte) or >= 0 (got " + fmt(s.specular) + ")");
      if (s.specular > kMaxSpecular)
        fail(w + ".specular", "must be at most " + fmt(kMaxSpecular) + " (got " + fmt(s.specular) + ")");
    }
    if (j.contains("reflective")) s.reflective = number_in(j["reflective"], w + ".reflective", 0, 1);
    return s;
  }

  Light parse_light(const json& j, const std::string& w) const {
    if (!j.is_object()) fail(w, "expected an object, got " + type_of(j));
    if (!j.contains("type")) fail(w, "missing \"type\"");
    if (!j["type"].is_string()) fail(w + ".type", "expected a string");
    const std::string type = j["type"].get<std::string>();
    Light l;
    if (type == "ambient") {
      only_keys(j, w, {"type", "intensity"});
      l.type = LightType::Ambient;
    } else if (type == "point") {
      only_keys(j, w, {"type", "intensity", "position"});
      l.type = LightType::Point;
      if (!j.contains("position")) fail(w, "point light needs \"position\"");
      l.vec = position(j["position"], w + ".position");
    } else if (type == "directional") {
      only_keys(j, w, {"type", "intensity", "direction"});
      l.type = LightType::Directional;
      if (!j.contains("direction")) fail(w, "directional light needs \"direction\"");
      l.vec = vec3(j["direction"], w + ".direction");
      if (l.vec.x == 0 && l.vec.y == 0 && l.vec.z == 0) fail(w + ".direction", "must not be the zero vector");
      // Rescaled by a power of two so the largest component lies in
      // [0.5, 1): [1e-300, 1e-300, -1e-300] has a squared length of 0 in
      // double, [1e300, 0, 0] one of inf, [0, 1e39, -1e39] overflows float.
      // A power of two is exact (the book's formulas give bit-identical
      // results for the shipped scenes) and idempotent (a scene written back
      // by scene_to_json parses to the same values).
      int e = 0;
      (void)std::frexp(std::max({std::fabs(l.vec.x), std::fabs(l.vec.y), std::fabs(l.vec.z)}), &e);
      l.vec = {std::ldexp(l.vec.x, -e), std::ldexp(l.vec.y, -e), std::ldexp(l.vec.z, -e)};
    } else {
      fail(w + ".type", "unknown light type " + quoted(type) + " (expected ambient, point or directional)");
    }
    if (!j.contains("intensity")) fail(w, "missing \"intensity\"");
    l.intensity = number_in(j["intensity"], w + ".intensity", 0, 1e30);
    return l;
  }

 private:
  std::string name_;
};

// Finds the first key that an object repeats (stops there, or at a syntax
// error, which json::parse then reports).
struct DuplicateKeys : json::json_sax_t {
  std::vector<std::unordered_set<std::string>> open_objects;
  std::string duplicate;  // the first repeated key, "" if none

  bool null() override { return true; }
  bool boolean(bool) override { return true; }
  bool number_integer(number_integer_t) override { return true; }
  bool number_unsigned(number_unsigned_t) override { return true; }
  bool number_float(number_float_t, const string_t&) override { return true; }
  bool string(string_t&) override { return true; }
  bool binary(binary_t&) override { return true; }
  bool start_object(std::size_t) override {
    open_objects.emplace_back();
    return true;
  }
  bool key(string_t& name) override {
    if (open_objects.empty() || open_objects.back().insert(name).second) return true;
    duplicate = name;
    return false;
  }
  bool end_object() override {
    if (!open_objects.empty()) open_objects.pop_back();
    return true;
  }
  bool start_array(std::size_t) override { return true; }
  bool end_array() override { return true; }
  bool parse_error(std::size_t, const std::string&, const nlohmann::detail::exception&) override { return false; }
};

}  // namespace

Scene parse_scene(const std::string& text, const std::string& name) {
  // A NUL byte is not JSON; nothing after one may be silently dropped.
  if (const size_t nul = text.find('\0'); nul != std::string::npos)
    throw UserError(name + ": malformed JSON: NUL byte at offset " + std::to_string(nul));
  // Duplicate keys are ambiguous (JSON parsers disagree on which one wins):
  // reject them, per object, in a SAX pass of their own (nlohmann's parse
  // with a callback is quadratic in the size of an array: 52 s instead of
  // 0.6 s for 400 000 spheres).
  DuplicateKeys duplicates;
  json::sax_parse(text, &duplicates);
  if (!duplicates.duplicate.empty()) throw UserError(name + ": duplicate key " + Parser::quoted(duplicates.duplicate));
  json root;
  try {
    root = json::parse(text);
  } catch (const json::exception& e) {
    std::string msg = e.what();
    // nlohmann prefixes "[json.exception.parse_error.101] "; keep the rest.
    auto pos = msg.find("] ");
    if (pos != std::string::npos) msg = msg.substr(pos + 2);
    // A literal such as 1e400 parses but overflows a double (out_of_range.406).
    bool overflow = dynamic_cast<const json::out_of_range*>(&e) != nullptr;
    throw UserError(name + (overflow ? ": number out of range: " : ": malformed JSON: ") + msg);
  }
  return Parser(name).parse(root);
}

Scene load_scene(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) throw UserError(path + ": cannot open scene file: is a directory");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw UserError(path + ": cannot open scene file: " + std::strerror(errno));
  // Read in chunks and stop past kMaxSceneBytes, so that /dev/zero or a huge
  // file cannot exhaust memory.
  std::string text;
  char chunk[1 << 16];
  while (in.read(chunk, sizeof chunk) || in.gcount() > 0) {
    text.append(chunk, static_cast<size_t>(in.gcount()));
    if (text.size() > kMaxSceneBytes)
      throw UserError(path + ": scene file is larger than " + std::to_string(kMaxSceneBytes >> 20) + " MiB");
  }
  if (in.bad()) throw UserError(path + ": cannot read scene file");
  return parse_scene(text, path);
}

std::string scene_to_json(const Scene& s, JsonStyle style) {
  auto v3 = [](Vec3 v) { return json::array({v.x, v.y, v.z}); };
  json root;
  const auto& r = s.camera.rotation;
  root["camera"] = {{"position", v3(s.camera.position)},
                    {"rotation", json::array({json::array({r[0], r[1], r[2]}), json::array({r[3], r[4], r[5]}),
                                              json::array({r[6], r[7], r[8]})})},
                    {"viewport", json::array({s.camera.viewport_w, s.camera.viewport_h})},
                    {"projection_plane_d", s.camera.projection_plane_d}};
  root["background"] = v3(s.background);
  root["recursion_depth"] = s.recursion_depth;
  root["epsilon"] = s.epsilon;
  root["spheres"] = json::array();
  for (const auto& sp : s.spheres)
    root["spheres"].push_back({{"center", v3(sp.center)},
                               {"radius", sp.radius},
                               {"color", v3(sp.color)},
                               {"specular", sp.specular},
                               {"reflective", sp.reflective}});
  root["lights"] = json::array();
  for (const auto& l : s.lights) {
    json jl = {{"intensity", l.intensity}};
    if (l.type == LightType::Ambient) jl["type"] = "ambient";
    if (l.type == LightType::Point) jl["type"] = "point", jl["position"] = v3(l.vec);
    if (l.type == LightType::Directional) jl["type"] = "directional", jl["direction"] = v3(l.vec);
    root["lights"].push_back(jl);
  }
  return style == JsonStyle::Pretty ? root.dump(2) : root.dump();
}

}  // namespace clrt
