// scene_json.cpp - strict, streaming JSON scene loader: one SAX pass over
// the text builds the scene sphere by sphere (no document tree), rejecting
// unknown and duplicate keys, wrong types, non-finite numbers and
// out-of-range values with a one-line message.
#include "scene/scene_json.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <istream>
#include <iterator>
#include <map>
#include <memory>
#include <optional>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string_view>
#include <type_traits>
#include <utility>

#include "clrt_layout.h"
#include "scene/obj_mesh.hpp"
#include "util/doing.hpp"
#include "util/bytes_text.hpp"
#include "util/error.hpp"
#include "util/open_beneath.hpp"

namespace clrt {
namespace {

using json = nlohmann::json;

std::string fmt(double v) {
  std::ostringstream os;
  os << v;
  return os.str();
}

// A string from the file, quoted and escaped as JSON, so that a key such as
// "a\nb" cannot break the one-line message.
// Long strings are cut (a 50 MB key must not be echoed in full).
std::string json_quoted(const std::string& s) {
  constexpr size_t kMaxEcho = 64;
  const std::string shown = json(s.substr(0, kMaxEcho)).dump(-1, ' ', false, json::error_handler_t::replace);
  return s.size() <= kMaxEcho ? shown : shown + "... (" + std::to_string(s.size()) + " bytes)";
}

[[noreturn]] void too_large(const std::string& name, size_t max_bytes) {
  throw UserError(name + ": scene file is larger than " + bytes_text(max_bytes));
}

// What a value in the file is: the key it stands under, or its place.
enum class Slot : unsigned char {
  // keys of the root object
  Camera,
  Background,
  RecursionDepth,
  Epsilon,
  Spheres,
  Lights,
  Planes,
  Triangles,
  Meshes,
  // of the camera
  Position,
  Rotation,
  Viewport,
  Distance,
  Aspect,
  // of a sphere
  Center,
  Radius,
  Color,
  Specular,
  Reflective,
  Transparency,
  RefractiveIndex,
  // of a light
  Type,
  Intensity,
  LightPosition,
  Direction,
  // of a plane
  PlanePoint,
  Normal,
  PlaneColor,
  PlaneSpecular,
  PlaneReflective,
  // of a triangle
  Vertices,
  TriangleColor,
  TriangleSpecular,
  TriangleReflective,
  // of a mesh
  File,
  Translate,
  Rotate,
  Scale,
  MeshColor,
  MeshSpecular,
  MeshReflective,
  // without a key: the whole text, elements of arrays
  Document,
  Sphere,
  Light,
  Row,     // of camera.rotation
  Number,  // of a vector
  PlaneElement,
  TriangleElement,
  MeshElement,
  Vertex,  // of a triangle's vertices
};
// string_view: a key is compared by its length first.
// clang-format off
constexpr std::string_view kKeyNames[] = {
    // root
    "camera", "background", "recursion_depth", "epsilon", "spheres", "lights", "planes", "triangles", "meshes",
    // camera
    "position", "rotation", "viewport", "projection_plane_d", "aspect",
    // sphere
    "center", "radius", "color", "specular", "reflective", "transparency", "refractive_index",
    // light
    "type", "intensity", "position", "direction",
    // plane
    "point", "normal", "color", "specular", "reflective",
    // triangle
    "vertices", "color", "specular", "reflective",
    // mesh
    "file", "translate", "rotate", "scale", "color", "specular", "reflective"};
// clang-format on
static_assert(std::size(kKeyNames) == size_t(Slot::Document));
constexpr uint64_t bit(Slot s) {
  return uint64_t(1) << static_cast<unsigned>(s);
}
static_assert(static_cast<unsigned>(Slot::Document) <= 64, "a key's bit must fit Frame::seen");

// The containers a scene has; each open one is a Frame.
enum class Ctx : unsigned char {
  Root,
  Camera,
  Sphere,
  Light,
  Plane,
  Triangle,
  Mesh,
  Spheres,
  Lights,
  Planes,
  Triangles,
  Meshes,
  Rotation,
  Vertices,
  Numbers
};
constexpr bool is_object(Ctx c) {
  return c <= Ctx::Mesh;
}

struct Frame {
  Ctx ctx = Ctx::Root;
  Slot key = Slot::Document;  // objects: the key whose value is being read
  uint64_t seen = 0;          // objects: bit(key) of every key read
  size_t count = 0;           // arrays: elements read (the index of the one being read)
};

// The keys an object of kind `c` may have: [first, last).
std::pair<Slot, Slot> keys_of(Ctx c) {
  switch (c) {
    case Ctx::Root:
      return {Slot::Camera, Slot::Position};
    case Ctx::Camera:
      return {Slot::Position, Slot::Center};
    case Ctx::Sphere:
      return {Slot::Center, Slot::Type};
    case Ctx::Light:
      return {Slot::Type, Slot::PlanePoint};
    case Ctx::Plane:
      return {Slot::PlanePoint, Slot::Vertices};
    case Ctx::Triangle:
      return {Slot::Vertices, Slot::File};
    default:
      return {Slot::File, Slot::Document};
  }
}

// The numbers in a vector value (a key whose value is an array of numbers),
// 0 for every other slot: the one list start_array and type_error use.
size_t vector_size(Slot s) {
  switch (s) {
    case Slot::Viewport:
      return 2;
    case Slot::Background:
    case Slot::Position:
    case Slot::Row:
    case Slot::Center:
    case Slot::Color:
    case Slot::LightPosition:
    case Slot::Direction:
    case Slot::PlanePoint:
    case Slot::Normal:
    case Slot::PlaneColor:
    case Slot::TriangleColor:
    case Slot::MeshColor:
    case Slot::Translate:
    case Slot::Rotate:
    case Slot::Vertex:
      return 3;
    default:
      return 0;
  }
}

bool light_allows(LightType t, Slot key) {
  if (key == Slot::LightPosition) return t == LightType::Point;
  if (key == Slot::Direction) return t == LightType::Directional;
  return true;
}

// The SAX handler: validates each value as it arrives and writes it into
// the scene; errors throw UserError("<name>: <path>: <problem>"). Memory:
// the scene, one sphere or light being read, and a stack of at most
// kMaxDepth frames (the format nests 4 deep; a container anywhere else is a
// type error, so the parser never goes deeper).
class SceneBuilder final : public nlohmann::json_sax<json> {
 public:
  // `folder`: where mesh files are looked up (the scene file's folder);
  // none for a scene that is not a file (text, standard input, a pipe).
  SceneBuilder(const std::string& name, const SceneLimits& limits, std::optional<std::filesystem::path> folder)
      : name_(name), limits_(limits), folder_(std::move(folder)) {}

  // After the parse: the checks that need the whole camera.
  Scene finish() {
    if (depth_ != 0) fail("", "incomplete scene");  // not reached: the parser reports the end of the text
    load_meshes();
    // The camera's ray directions: rotation x (viewport/2, viewport/2, d).
    const Camera& c = scene_.camera;
    const auto& r = c.rotation;
    const double half_w = c.viewport_w / 2, half_h = c.viewport_h / 2, d = c.projection_plane_d;
    for (int row = 0; row < 3; ++row) {
      const double reach =
          std::fabs(r[row * 3]) * half_w + std::fabs(r[row * 3 + 1]) * half_h + std::fabs(r[row * 3 + 2]) * d;
      if (reach > kMaxLength)
        fail("camera", "ray directions reach " + fmt(reach) + " (rotation row " + std::to_string(row) +
                           " times viewport and projection distance), more than " + fmt(kMaxLength) +
                           ", the range clrt renders in float32");
    }
    return std::move(scene_);
  }

  // The meshes' triangles, in the order of "meshes", after the inline
  // "triangles". Each file is opened beneath the scene's folder, never
  // through a link (util/open_beneath.hpp), and read and parsed once however
  // often the scene names it: the triangle limit counts every mention, the
  // byte limit (SceneLimits::mesh_bytes) every distinct file together.
  void load_meshes() {
    if (meshes_.empty()) return;
    if (!folder_)
      fail(meshes_[0].where + ".file", json_quoted(meshes_[0].file) +
                                           ": a scene that is not read from a file (standard input, a pipe, a device, "
                                           "text) has no folder to read mesh files from");
    const int root = ::open(folder_->c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (root < 0)
      fail(meshes_[0].where + ".file", "cannot open the scene's folder " + folder_->string() + ": " + std::strerror(errno));
    struct CloseRoot {
      int fd;
      ~CloseRoot() { ::close(fd); }
    } close_root{root};
    std::map<std::pair<dev_t, ino_t>, ObjMesh> parsed;
    size_t bytes = 0;
    for (const MeshSource& m : meshes_) {
      const std::string shown = (*folder_ / m.file).string();
      const Doing doing("reading the mesh file " + shown);
      const size_t room = limits_.triangles - std::min(limits_.triangles, scene_.triangles.size());
      std::vector<Triangle> faces;
      try {
        check_mesh_transform(shown, m.transform);
        std::string why;
        const int fd = open_beneath(root, m.file, why);
        if (fd < 0) throw UserError(shown + ": cannot open mesh file: " + why);
        struct stat st {};
        if (::fstat(fd, &st) != 0) {
          ::close(fd);
          throw UserError(shown + ": cannot read mesh file: " + std::strerror(errno));
        }
        auto it = parsed.find({st.st_dev, st.st_ino});
        if (it == parsed.end()) {
          const size_t limit = std::min(limits_.mesh_bytes, kMaxMeshBytes);
          if (S_ISREG(st.st_mode) && uint64_t(st.st_size) <= limit && bytes + uint64_t(st.st_size) > limit) {
            ::close(fd);
            throw UserError(shown + ": the scene's mesh files total more than " + bytes_text(limit) +
                            " (the limit for one scene's meshes)");
          }
          std::string text = read_mesh_file(fd, shown, limit - bytes);
          bytes += text.size();
          it = parsed.emplace(std::make_pair(st.st_dev, st.st_ino), parse_obj_mesh(shown, std::move(text), room)).first;
        } else {
          ::close(fd);
        }
        if (it->second.triangles() > room)
          throw UserError(shown + ": " + std::to_string(it->second.triangles()) + " triangles, more than the " +
                          std::to_string(room) + " the scene's limit of " + std::to_string(limits_.triangles) +
                          " leaves for this mesh");
        faces = place_obj_mesh(shown, it->second, m.transform, m.material);
      } catch (const UserError& e) {
        fail(m.where + ".file", e.what());
      }
      scene_.triangles.insert(scene_.triangles.end(), faces.begin(), faces.end());
    }
  }

  // ---- SAX events ----
  bool null() override { type_error(enter_value(), "null"); }
  bool boolean(bool) override { type_error(enter_value(), "boolean"); }
  bool number_integer(number_integer_t v) override { return integer(v); }
  bool number_unsigned(number_unsigned_t v) override { return integer(v); }
  bool number_float(number_float_t v, const string_t&) override {
    const Slot s = enter_value();
    if (s == Slot::RecursionDepth) type_error(s, "number");
    return number(s, v);
  }
  bool binary(binary_t&) override { type_error(enter_value(), "binary"); }
  bool string(string_t& v) override {
    const Slot s = enter_value();
    if (s == Slot::File) {
      mesh_file(v);
      return true;
    }
    if (s == Slot::Aspect) {
      if (v != "viewport" && v != "image")
        fail(value_path(), "unknown aspect " + json_quoted(v) + " (expected viewport or image)");
      scene_.camera.aspect_from_image = v == "image";
      return true;
    }
    if (s != Slot::Type) type_error(s, "string");
    light_type(v);
    return true;
  }

  bool start_object(std::size_t) override {
    const Slot s = enter_value();
    switch (s) {
      case Slot::Document:
        push(Ctx::Root);
        break;
      case Slot::Camera:
        push(Ctx::Camera);
        break;
      case Slot::Sphere:
        sphere_ = Sphere{};
        push(Ctx::Sphere);
        break;
      case Slot::Light:
        light_ = Light{};
        light_typed_ = false;
        push(Ctx::Light);
        break;
      case Slot::PlaneElement:
        plane_ = Plane{};
        material_ = Material{};
        push(Ctx::Plane);
        break;
      case Slot::TriangleElement:
        triangle_ = Triangle{};
        material_ = Material{};
        push(Ctx::Triangle);
        break;
      case Slot::MeshElement:
        mesh_ = MeshSource{};
        material_ = Material{};
        push(Ctx::Mesh);
        break;
      default:
        type_error(s, "object");
    }
    return true;
  }

  bool key(string_t& k) override {
    Frame& f = top();
    const auto [first, last] = keys_of(f.ctx);
    Slot s = Slot::Document;
    for (auto i = static_cast<unsigned>(first); i < static_cast<unsigned>(last); ++i)
      if (std::string_view(k) == kKeyNames[i]) s = static_cast<Slot>(i);
    if (s == Slot::Document || (f.ctx == Ctx::Light && light_typed_ && !light_allows(light_.type, s)))
      fail(path(depth_ - 1), "unknown key " + json_quoted(k));
    // Duplicate keys are ambiguous (JSON parsers disagree on which one wins).
    if (f.seen & bit(s)) fail(path(depth_ - 1), "duplicate key " + json_quoted(k));
    f.seen |= bit(s);
    f.key = s;
    return true;
  }

  bool end_object() override {
    const Frame f = pop();
    if (f.ctx == Ctx::Sphere) finish_sphere(f.seen);
    if (f.ctx == Ctx::Light) finish_light(f.seen);
    if (f.ctx == Ctx::Plane) finish_plane(f.seen);
    if (f.ctx == Ctx::Triangle) finish_triangle(f.seen);
    if (f.ctx == Ctx::Mesh) finish_mesh(f.seen);
    next_element();
    return true;
  }

  bool start_array(std::size_t) override {
    const Slot s = enter_value();
    // The arrays of elements, each a container of its own.
    constexpr std::pair<Slot, Ctx> kContainers[] = {{Slot::Spheres, Ctx::Spheres},   {Slot::Lights, Ctx::Lights},
                                                    {Slot::Rotation, Ctx::Rotation}, {Slot::Planes, Ctx::Planes},
                                                    {Slot::Meshes, Ctx::Meshes},     {Slot::Triangles, Ctx::Triangles},
                                                    {Slot::Vertices, Ctx::Vertices}};
    for (const auto& [slot, ctx] : kContainers)
      if (s == slot) {
        push(ctx);
        return true;
      }
    if (const size_t numbers = vector_size(s)) {
      numbers_size_ = numbers;
      push(Ctx::Numbers);
      return true;
    }
    type_error(s, "array");
  }

  bool end_array() override {
    const Frame f = pop();
    // value_path() and slot() now name the array itself.
    if (f.ctx == Ctx::Numbers) finish_numbers(slot(), f.count);
    if (f.ctx == Ctx::Rotation && f.count != 3) fail(value_path(), "expected a 3x3 array of numbers");
    if (f.ctx == Ctx::Vertices && f.count != 3) fail(value_path(), kVerticesMessage);
    if (f.ctx == Ctx::Lights) {
      double total = 0;
      for (const auto& l : scene_.lights) total += l.intensity;
      if (total > kMaxTotalIntensity)
        fail(value_path(), "the intensities add up to " + fmt(total) + ", more than " + fmt(kMaxTotalIntensity) +
                               " (colours would overflow float32)");
    }
    next_element();
    return true;
  }

  bool parse_error(std::size_t, const std::string&, const nlohmann::detail::exception& e) override {
    std::string msg = e.what();
    // nlohmann prefixes "[json.exception.parse_error.101] "; keep the rest.
    if (const auto pos = msg.find("] "); pos != std::string::npos) msg = msg.substr(pos + 2);
    // "...; last read: '<token>'[; expected ...]": the token may be a whole
    // unterminated string; cut it (not inside a UTF-8 sequence).
    const std::string marker = "; last read: '";
    if (const size_t at = msg.find(marker); at != std::string::npos) {
      constexpr size_t kMaxEcho = 64;
      const size_t start = at + marker.size();
      size_t end = msg.rfind("'; expected ");
      if (end == std::string::npos || end < start) end = msg.back() == '\'' ? msg.size() - 1 : start;
      if (end - start > kMaxEcho) {
        size_t cut = start + kMaxEcho;
        // A UTF-8 sequence has at most 3 continuation bytes.
        while (cut > start + kMaxEcho - 3 && (static_cast<unsigned char>(msg[cut]) & 0xC0) == 0x80) --cut;
        msg = msg.substr(0, cut) + "...' (" + std::to_string(end - start) + " bytes)" + msg.substr(end + 1);
      }
    }
    // A literal such as 1e400 is valid JSON but overflows a double (out_of_range.406).
    const bool overflow = dynamic_cast<const json::out_of_range*>(&e) != nullptr;
    throw UserError(name_ + (overflow ? ": number out of range: " : ": malformed JSON: ") + msg);
  }

 private:
  // root, triangles, triangle, vertices, vertex
  static constexpr size_t kMaxDepth = 5;
  static constexpr const char* kVerticesMessage = "expected 3 vertices of 3 numbers each";

  [[noreturn]] void fail(const std::string& where, const std::string& what) const {
    throw UserError(name_ + ": " + (where.empty() ? "" : where + ": ") + what);
  }

  // The path of the value frame n - 1 is reading ("spheres[3].center"); the
  // frames below it name the containers it is in.
  std::string path(size_t n) const {
    std::string p;
    for (size_t i = 0; i < n; ++i) {
      const Frame& f = stack_[i];
      if (is_object(f.ctx)) {
        if (f.key == Slot::Document) break;  // no key read yet
        if (!p.empty()) p += '.';
        p += kKeyNames[static_cast<unsigned>(f.key)];
      } else {
        p += '[' + std::to_string(f.count) + ']';
      }
    }
    return p;
  }
  std::string value_path() const { return path(depth_); }

  Frame& top() { return stack_[depth_ - 1]; }
  void push(Ctx c) {
    // Not reached: the format nests kMaxDepth deep and every other container is a type error.
    if (depth_ == kMaxDepth) fail(value_path(), "nested deeper than " + std::to_string(kMaxDepth) + " levels");
    stack_[depth_++] = Frame{c};
  }
  Frame pop() { return stack_[--depth_]; }
  // After a value: the next element of its array.
  void next_element() {
    if (depth_ > 0 && !is_object(top().ctx)) ++top().count;
  }

  // What the next value is.
  Slot slot() const {
    if (depth_ == 0) return Slot::Document;
    const Frame& f = stack_[depth_ - 1];
    switch (f.ctx) {
      case Ctx::Spheres:
        return Slot::Sphere;
      case Ctx::Lights:
        return Slot::Light;
      case Ctx::Rotation:
        return Slot::Row;
      case Ctx::Numbers:
        return Slot::Number;
      case Ctx::Planes:
        return Slot::PlaneElement;
      case Ctx::Triangles:
        return Slot::TriangleElement;
      case Ctx::Meshes:
        return Slot::MeshElement;
      case Ctx::Vertices:
        return Slot::Vertex;
      default:
        return f.key;
    }
  }
  // The same, at the start of a value: one element too many is an error.
  Slot enter_value() {
    if (depth_ > 0) {
      const Frame& f = top();
      if (f.ctx == Ctx::Numbers && f.count >= numbers_size_) fail(path(depth_ - 1), numbers_message());
      if (f.ctx == Ctx::Rotation && f.count >= 3) fail(path(depth_ - 1), "expected a 3x3 array of numbers");
      if (f.ctx == Ctx::Spheres && f.count >= limits_.spheres)
        fail(path(depth_ - 1), "more than " + std::to_string(limits_.spheres) + " spheres, the most clrt loads");
      if (f.ctx == Ctx::Lights && f.count >= limits_.lights)
        fail(path(depth_ - 1), "more than " + std::to_string(limits_.lights) + " lights, the most clrt loads");
      if (f.ctx == Ctx::Vertices && f.count >= 3) fail(path(depth_ - 1), kVerticesMessage);
      if (f.ctx == Ctx::Planes && f.count >= limits_.planes)
        fail(path(depth_ - 1), "more than " + std::to_string(limits_.planes) + " planes, the most clrt loads");
      if (f.ctx == Ctx::Triangles && f.count >= limits_.triangles)
        fail(path(depth_ - 1), "more than " + std::to_string(limits_.triangles) + " triangles, the most clrt loads");
      if (f.ctx == Ctx::Meshes && f.count >= limits_.meshes)
        fail(path(depth_ - 1), "more than " + std::to_string(limits_.meshes) + " meshes, the most clrt loads");
    }
    return slot();
  }
  std::string numbers_message() const {
    return numbers_size_ == 2 ? "expected an array of 2 numbers" : "expected an array of 3 numbers";
  }

  // A value of type `got` where slot `s` wants another.
  [[noreturn]] void type_error(Slot s, const std::string& got) const {
    if (vector_size(s) == 3) fail(value_path(), "expected an array of 3 numbers");
    switch (s) {
      case Slot::Document:
      case Slot::Camera:
      case Slot::Sphere:
      case Slot::Light:
      case Slot::PlaneElement:
      case Slot::TriangleElement:
      case Slot::MeshElement:
        fail(value_path(), "expected an object, got " + got);
      case Slot::Spheres:
      case Slot::Lights:
      case Slot::Planes:
      case Slot::Triangles:
      case Slot::Meshes:
        fail(value_path(), "expected an array, got " + got);
      case Slot::Vertices:
        fail(value_path(), kVerticesMessage);
      case Slot::Rotation:
        fail(value_path(), "expected a 3x3 array of numbers");
      case Slot::Viewport:
        fail(value_path(), "expected an array of 2 numbers");
      case Slot::RecursionDepth:
        fail(value_path(), "expected an integer, got " + got);
      case Slot::Type:
      case Slot::File:
      case Slot::Aspect:
        fail(value_path(), "expected a string");
      default:
        fail(value_path(), "expected a number, got " + got);
    }
  }

  template <typename Int>
  bool integer(Int v) {
    const Slot s = enter_value();
    if (s != Slot::RecursionDepth) return number(s, static_cast<double>(v));
    // Compared as read: an unsigned above LLONG_MAX must not wrap.
    bool in_range = v <= static_cast<Int>(CLRT_MAX_DEPTH);
    if constexpr (std::is_signed_v<Int>) in_range = in_range && v >= 0;
    if (!in_range)
      fail(value_path(), "must be in [0, " + std::to_string(CLRT_MAX_DEPTH) + "] (got " + std::to_string(v) + ")");
    scene_.recursion_depth = static_cast<int>(v);
    return true;
  }

  bool number(Slot s, double v) {
    switch (s) {
      case Slot::Number:
      case Slot::Epsilon:
      case Slot::Distance:
      case Slot::Radius:
      case Slot::Specular:
      case Slot::Reflective:
      case Slot::Transparency:
      case Slot::RefractiveIndex:
      case Slot::Intensity:
      case Slot::PlaneSpecular:
      case Slot::PlaneReflective:
      case Slot::TriangleSpecular:
      case Slot::TriangleReflective:
      case Slot::MeshSpecular:
      case Slot::MeshReflective:
      case Slot::Scale:
        break;
      default:
        type_error(s, "number");
    }
    if (!std::isfinite(v)) fail(value_path(), "number is not finite");  // not reached: the parser rejects them
    switch (s) {
      case Slot::Number:
        numbers_[top().count] = v;
        break;
      case Slot::Epsilon:
        scene_.epsilon = in_range(v, 0, kMaxLength);
        break;
      case Slot::Distance:
        scene_.camera.projection_plane_d = size(v);
        break;
      case Slot::Radius:
        sphere_.radius = size(v);
        break;
      case Slot::Specular:
        sphere_.specular = specular(v);
        break;
      case Slot::PlaneSpecular:
      case Slot::TriangleSpecular:
      case Slot::MeshSpecular:
        material_.specular = specular(v);
        break;
      case Slot::PlaneReflective:
      case Slot::TriangleReflective:
      case Slot::MeshReflective:
        material_.reflective = in_range(v, 0, 1);
        break;
      case Slot::Scale:
        mesh_.transform.scale = size(v);
        break;
      case Slot::Reflective:
        sphere_.reflective = in_range(v, 0, 1);
        break;
      case Slot::Transparency:
        sphere_.transparency = in_range(v, 0, 1);
        break;
      case Slot::RefractiveIndex:
        sphere_.refractive_index = in_range(v, kMinRefractiveIndex, kMaxRefractiveIndex);
        break;
      default:  // Slot::Intensity
        light_.intensity = in_range(v, 0, 1e30);
        break;
    }
    next_element();
    return true;
  }

  // ---- checks of one value; `index` names a component of it ----
  double specular(double v) const {
    if (v != -1 && v < 0) fail(value_path(), "must be -1 (matte) or >= 0 (got " + fmt(v) + ")");
    if (v > kMaxSpecular) fail(value_path(), "must be at most " + fmt(kMaxSpecular) + " (got " + fmt(v) + ")");
    return v;
  }
  double in_range(double v, double lo, double hi) const {
    if (v < lo || v > hi) fail(value_path(), "must be in [" + fmt(lo) + ", " + fmt(hi) + "] (got " + fmt(v) + ")");
    return v;
  }
  // A size in [kMinLength, kMaxLength].
  double size(double v, const char* index = "") const {
    if (!(v > 0)) fail(value_path() + index, "must be > 0 (got " + fmt(v) + ")");
    if (v < kMinLength || v > kMaxLength)
      fail(value_path() + index, "must be in [" + fmt(kMinLength) + ", " + fmt(kMaxLength) +
                                     "], the range clrt renders in float32 (got " + fmt(v) + ")");
    return v;
  }
  // A coordinate within the float32-safe range (scene.hpp).
  Vec3 position(Vec3 v) const {
    const double c[3] = {v.x, v.y, v.z};
    for (int k = 0; k < 3; ++k)
      if (std::fabs(c[k]) > kMaxLength)
        fail(value_path() + "[" + std::to_string(k) + "]",
             "must be within ±" + fmt(kMaxLength) + ", the range clrt renders in float32 (got " + fmt(c[k]) + ")");
    return v;
  }
  Vec3 color(Vec3 c) const {
    for (double v : {c.x, c.y, c.z})
      if (v < 0 || v > 255) fail(value_path(), "color components must be in [0, 255] (got " + fmt(v) + ")");
    return c;
  }

  // ---- a container read to its end (value_path() names it) ----
  void finish_numbers(Slot s, size_t count) {
    if (count != numbers_size_) fail(value_path(), numbers_message());
    const Vec3 v{numbers_[0], numbers_[1], numbers_[2]};
    switch (s) {
      case Slot::Background:
        scene_.background = color(v);
        break;
      case Slot::Position:
        scene_.camera.position = position(v);
        break;
      case Slot::Viewport:
        for (int k = 0; k < 2; ++k)
          if (!(numbers_[k] > 0)) fail(value_path(), "sizes must be > 0");
        scene_.camera.viewport_w = size(numbers_[0], "[0]");
        scene_.camera.viewport_h = size(numbers_[1], "[1]");
        break;
      case Slot::Row: {
        const size_t row = top().count;  // of the rotation
        scene_.camera.rotation[row * 3 + 0] = v.x;
        scene_.camera.rotation[row * 3 + 1] = v.y;
        scene_.camera.rotation[row * 3 + 2] = v.z;
        break;
      }
      case Slot::Center:
        sphere_.center = position(v);
        break;
      case Slot::Color:
        sphere_.color = color(v);
        break;
      case Slot::LightPosition:
        light_position_ = position(v);
        break;
      case Slot::PlanePoint:
        plane_.point = position(v);
        break;
      case Slot::Normal:
        plane_.normal = v;
        break;
      case Slot::PlaneColor:
      case Slot::TriangleColor:
      case Slot::MeshColor:
        material_.color = color(v);
        break;
      case Slot::Vertex: {
        const size_t index = top().count;  // of the triangle's vertices
        (index == 0 ? triangle_.v0 : index == 1 ? triangle_.v1 : triangle_.v2) = position(v);
        break;
      }
      case Slot::Translate:
        mesh_.transform.translate = position(v);
        break;
      case Slot::Rotate:
        for (double angle : {v.x, v.y, v.z})
          if (std::fabs(angle) > 1e6) fail(value_path(), "angles must be within ±1e6 degrees (got " + fmt(angle) + ")");
        mesh_.transform.rotate_degrees = v;
        break;
      default:  // Slot::Direction
        light_direction_ = v;
        break;
    }
  }

  // ---- chapter 5's other primitives ----
  void finish_plane(uint64_t seen) {
    if (!(seen & bit(Slot::PlanePoint))) fail(value_path(), "missing \"point\"");
    if (!(seen & bit(Slot::Normal))) fail(value_path(), "missing \"normal\"");
    if (!(seen & bit(Slot::PlaneColor))) fail(value_path(), "missing \"color\"");
    // Rescaled by a power of two, as light directions are, so that its
    // largest component lies in [0.5, 1): exact and idempotent (a scene
    // written back parses to the same values; dividing by the length would
    // not be), and no later length under- or overflows. Every use of the
    // normal is scale-invariant or normalizes it.
    Vec3 n = plane_.normal;
    if (n.x == 0 && n.y == 0 && n.z == 0) fail(value_path() + ".normal", "must not be the zero vector");
    int e = 0;
    (void)std::frexp(std::max({std::fabs(n.x), std::fabs(n.y), std::fabs(n.z)}), &e);
    plane_.normal = {std::ldexp(n.x, -e), std::ldexp(n.y, -e), std::ldexp(n.z, -e)};
    plane_.material = material_;
    scene_.planes.push_back(plane_);
  }

  void finish_triangle(uint64_t seen) {
    if (!(seen & bit(Slot::Vertices))) fail(value_path(), "missing \"vertices\"");
    if (!(seen & bit(Slot::TriangleColor))) fail(value_path(), "missing \"color\"");
    triangle_.material = material_;
    scene_.triangles.push_back(triangle_);
  }

  void mesh_file(const std::string& file) {
    // A scene names files in its own folder or below it: never an absolute
    // path or "..", so that a scene from elsewhere cannot make clrt read
    // files outside the folder it came in.
    const std::filesystem::path p(file);
    if (file.empty()) fail(value_path(), "must not be empty");
    if (p.is_absolute()) fail(value_path(), "must be a path relative to the scene's folder (got an absolute path)");
    for (const auto& part : p)
      if (part == "..") fail(value_path(), "must not leave the scene's folder (\"..\")");
    mesh_.file = file;
  }

  void finish_mesh(uint64_t seen) {
    if (!(seen & bit(Slot::File))) fail(value_path(), "missing \"file\"");
    if (!(seen & bit(Slot::MeshColor))) fail(value_path(), "missing \"color\"");
    mesh_.material = material_;
    mesh_.where = value_path();
    meshes_.push_back(mesh_);
  }

  void finish_sphere(uint64_t seen) {
    if (!(seen & bit(Slot::Center))) fail(value_path(), "missing \"center\"");
    if (!(seen & bit(Slot::Radius))) fail(value_path(), "missing \"radius\"");
    if (!(seen & bit(Slot::Color))) fail(value_path(), "missing \"color\"");
    scene_.spheres.push_back(sphere_);
  }

  void light_type(const std::string& type) {
    if (type == "ambient") {
      light_.type = LightType::Ambient;
    } else if (type == "point") {
      light_.type = LightType::Point;
    } else if (type == "directional") {
      light_.type = LightType::Directional;
    } else {
      fail(value_path(), "unknown light type " + json_quoted(type) + " (expected ambient, point or directional)");
    }
    light_typed_ = true;
    // Keys read before the type (later ones are checked as they come).
    for (Slot k : {Slot::Direction, Slot::LightPosition})
      if ((top().seen & bit(k)) && !light_allows(light_.type, k))
        fail(path(depth_ - 1), "unknown key " + json_quoted(std::string(kKeyNames[static_cast<unsigned>(k)])));
  }

  void finish_light(uint64_t seen) {
    if (!(seen & bit(Slot::Type))) fail(value_path(), "missing \"type\"");
    if (light_.type == LightType::Point) {
      if (!(seen & bit(Slot::LightPosition))) fail(value_path(), "point light needs \"position\"");
      light_.vec = light_position_;
    }
    if (light_.type == LightType::Directional) {
      if (!(seen & bit(Slot::Direction))) fail(value_path(), "directional light needs \"direction\"");
      Vec3 d = light_direction_;
      if (d.x == 0 && d.y == 0 && d.z == 0) fail(value_path() + ".direction", "must not be the zero vector");
      // Rescaled by a power of two so the largest component lies in
      // [0.5, 1): [1e-300, 1e-300, -1e-300] has a squared length of 0 in
      // double, [1e300, 0, 0] one of inf, [0, 1e39, -1e39] overflows float.
      // A power of two is exact (the book's formulas give bit-identical
      // results for the shipped scenes) and idempotent (a scene written back
      // by scene_to_json parses to the same values).
      int e = 0;
      (void)std::frexp(std::max({std::fabs(d.x), std::fabs(d.y), std::fabs(d.z)}), &e);
      light_.vec = {std::ldexp(d.x, -e), std::ldexp(d.y, -e), std::ldexp(d.z, -e)};
      light_.scale_exponent = e;  // the shadow range follows (Light::shadow_t_min)
    }
    if (!(seen & bit(Slot::Intensity))) fail(value_path(), "missing \"intensity\"");
    scene_.lights.push_back(light_);
  }

  const std::string& name_;
  const SceneLimits limits_;
  const std::optional<std::filesystem::path> folder_;
  Scene scene_;
  std::array<Frame, kMaxDepth> stack_;
  size_t depth_ = 0;
  // The vector, sphere and light being read.
  std::array<double, 3> numbers_{};
  size_t numbers_size_ = 3;
  Sphere sphere_;
  Light light_;
  bool light_typed_ = false;
  Vec3 light_position_, light_direction_;
  // The plane, triangle or mesh being read, and its material.
  Plane plane_;
  Triangle triangle_;
  Material material_;
  struct MeshSource {
    std::string file;  // relative to the scene's folder
    MeshTransform transform;
    Material material;
    std::string where;  // "meshes[2]"
  };
  MeshSource mesh_;
  std::vector<MeshSource> meshes_;  // loaded by finish(), after the parse
};

// A stream's bytes in chunks, for the parser: a NUL byte (not JSON; nlohmann
// would take it for the end of the text) or more than max_bytes throw
// UserError as soon as they are read, so that /dev/zero or a huge file
// cannot exhaust memory or time.
class LimitedReader final : public std::streambuf {
 public:
  LimitedReader(std::istream& in, const std::string& name, size_t max_bytes)
      : in_(in), name_(name), max_bytes_(max_bytes), buffer_(new char[kChunk]) {}

 protected:
  int_type underflow() override {
    if (gptr() < egptr()) return traits_type::to_int_type(*gptr());
    in_.read(buffer_.get(), kChunk);
    const auto n = static_cast<size_t>(in_.gcount());
    if (in_.bad()) throw UserError(name_ + ": cannot read scene file");
    if (n == 0) return traits_type::eof();
    if (const void* nul = std::memchr(buffer_.get(), 0, n))
      throw UserError(name_ + ": malformed JSON: NUL byte at offset " +
                      std::to_string(read_ + size_t(static_cast<const char*>(nul) - buffer_.get())));
    read_ += n;
    if (read_ > max_bytes_) too_large(name_, max_bytes_);
    setg(buffer_.get(), buffer_.get(), buffer_.get() + n);
    return traits_type::to_int_type(*gptr());
  }

 private:
  static constexpr size_t kChunk = size_t(1) << 16;
  std::istream& in_;
  const std::string& name_;
  const size_t max_bytes_;
  size_t read_ = 0;
  std::unique_ptr<char[]> buffer_;
};

}  // namespace

Scene parse_scene(const std::string& text, const std::string& name, const SceneLimits& limits) {
  if (text.size() > limits.bytes) too_large(name, limits.bytes);
  // A NUL byte is not JSON; nothing after one may be silently dropped.
  if (const void* nul = std::memchr(text.data(), 0, text.size()))
    throw UserError(name + ": malformed JSON: NUL byte at offset " +
                    std::to_string(static_cast<const char*>(nul) - text.data()));
  SceneBuilder builder(name, limits, std::nullopt);
  if (!json::sax_parse(text, &builder)) throw UserError(name + ": malformed JSON");  // not reached: errors throw
  return builder.finish();
}

namespace {

Scene parse_stream(std::istream& in, const std::string& name, const SceneLimits& limits,
                   const std::optional<std::filesystem::path>& folder) {
  LimitedReader reader(in, name, limits.bytes);
  std::istream stream(&reader);
  SceneBuilder builder(name, limits, folder);
  if (!json::sax_parse(stream, &builder)) throw UserError(name + ": malformed JSON");  // not reached: errors throw
  return builder.finish();
}

}  // namespace

Scene parse_scene(std::istream& in, const std::string& name, const SceneLimits& limits) {
  return parse_stream(in, name, limits, std::nullopt);
}

Scene load_scene(const std::string& path, const SceneLimits& limits) {
  const Doing doing("loading the scene " + path);
  std::error_code ec;
  const std::filesystem::file_status status = std::filesystem::status(path, ec);
  if (std::filesystem::is_directory(status)) throw UserError(path + ": cannot open scene file: is a directory");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw UserError(path + ": cannot open scene file: " + std::strerror(errno));
  // A regular file over the limit fails before it is read; anything else (a
  // FIFO, /dev/zero) is counted as it is read.
  if (std::filesystem::is_regular_file(status)) {
    const auto bytes = std::filesystem::file_size(path, ec);
    if (!ec && bytes > limits.bytes) too_large(path, limits.bytes);
  }
  // Mesh files are read from the scene file's folder; a scene that is not a
  // regular file (a pipe, /dev/stdin) has none: under /dev or /proc anyone
  // could have planted a file by the name it gives.
  if (!std::filesystem::is_regular_file(status)) return parse_stream(in, path, limits, std::nullopt);
  const std::filesystem::path folder = std::filesystem::path(path).parent_path();
  return parse_stream(in, path, limits, folder.empty() ? std::filesystem::path(".") : folder);
}

std::string scene_to_json(const Scene& s, JsonStyle style) {
  const bool pretty = style == JsonStyle::Pretty;
  auto v3 = [](Vec3 v) { return json::array({v.x, v.y, v.z}); };
  json root;
  const auto& r = s.camera.rotation;
  root["camera"] = {{"position", v3(s.camera.position)},
                    {"rotation", json::array({json::array({r[0], r[1], r[2]}), json::array({r[3], r[4], r[5]}),
                                              json::array({r[6], r[7], r[8]})})},
                    {"viewport", json::array({s.camera.viewport_w, s.camera.viewport_h})},
                    {"projection_plane_d", s.camera.projection_plane_d}};
  if (s.camera.aspect_from_image) root["camera"]["aspect"] = "image";
  root["background"] = v3(s.background);
  root["recursion_depth"] = s.recursion_depth;
  root["epsilon"] = s.epsilon;
  root["lights"] = json::array();
  for (const auto& l : s.lights) {
    json jl = {{"intensity", l.intensity}};
    if (l.type == LightType::Ambient) jl["type"] = "ambient";
    if (l.type == LightType::Point) jl["type"] = "point", jl["position"] = v3(l.vec);
    if (l.type == LightType::Directional) jl["type"] = "directional", jl["direction"] = v3(l.given_vec());
    root["lights"].push_back(jl);
  }
  auto material = [&v3](json& item, const Material& m) {
    item["color"] = v3(m.color);
    item["specular"] = m.specular;
    item["reflective"] = m.reflective;
  };
  // Chapter 5's other primitives, only when the scene has them; a mesh's
  // faces are written as its triangles (the scene then needs no OBJ file).
  if (!s.planes.empty()) {
    root["planes"] = json::array();
    for (const Plane& plane : s.planes) {
      json item = {{"point", v3(plane.point)}, {"normal", v3(plane.normal)}};
      material(item, plane.material);
      root["planes"].push_back(item);
    }
  }
  if (!s.triangles.empty()) {
    root["triangles"] = json::array();
    for (const Triangle& t : s.triangles) {
      json item = {{"vertices", json::array({v3(t.v0), v3(t.v1), v3(t.v2)})}};
      material(item, t.material);
      root["triangles"].push_back(item);
    }
  }
  // The spheres are written one at a time (a document tree of a million
  // spheres takes about 1.4 GB), with the same text json::dump gives, in
  // place of a marker (no other string of a scene can be this one).
  constexpr const char* kMarker = "@clrt-spheres@";
  root["spheres"] = s.spheres.empty() ? json::array() : json(kMarker);
  std::string text = pretty ? root.dump(2) : root.dump();
  if (s.spheres.empty()) return text;
  const std::string quoted_marker = std::string("\"") + kMarker + "\"";
  const size_t at = text.find(quoted_marker);
  const std::string tail = text.substr(at + quoted_marker.size());
  text.resize(at);
  text += '[';
  json item = json::object();
  for (size_t i = 0; i < s.spheres.size(); ++i) {
    const Sphere& sp = s.spheres[i];
    item["center"] = v3(sp.center);
    item["radius"] = sp.radius;
    item["color"] = v3(sp.color);
    item["specular"] = sp.specular;
    item["reflective"] = sp.reflective;
    // Written only where they differ from the defaults, so scenes of the
    // book's chapters 2-4 keep their text.
    item.erase("transparency");
    item.erase("refractive_index");
    if (sp.transparency != 0) item["transparency"] = sp.transparency;
    if (sp.refractive_index != 1) item["refractive_index"] = sp.refractive_index;
    if (pretty) {
      // An element of the root's "spheres": indented two levels deeper.
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
  return text + tail;
}

}  // namespace clrt
