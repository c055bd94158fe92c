// scene_keys.cpp - the table of the scene format's keys (scene_keys.hpp):
// the one place a key is declared.
#include "scene/scene_keys.hpp"

#include <nlohmann/json.hpp>

#include "clrt_layout.h"

namespace clrt {

// (A named namespace, not an anonymous one: clrt_core is a unity build, and
// these short names must not meet another file's.)
namespace key_table {

// A rule and its bounds.
struct Check {
  Rule rule = Rule::None;
  double lo = 0, hi = 0;
};
constexpr Check in(double lo, double hi) {
  return {Rule::Range, lo, hi};
}
constexpr Check kAny{};
constexpr Check kSize{Rule::Size, kMinLength, kMaxLength};
constexpr Check kSpecular{Rule::Specular, 0, kMaxSpecular};
constexpr Check kCoordinate{Rule::Coordinate, -kMaxLength, kMaxLength};
constexpr Check kColor{Rule::Color, 0, 255};
constexpr Check kAngles{Rule::Angles, -1e6, 1e6};
constexpr Check kDirection{Rule::Direction};
constexpr Check kNormal{Rule::Normal};

constexpr Key make(Ctx c, std::string_view name, Kind kind, Field f, Check check) {
  Key k;
  k.ctx = c;
  k.name = name;
  k.kind = kind;
  k.field = f;
  k.rule = check.rule;
  k.lo = check.lo;
  k.hi = check.hi;
  return k;
}
constexpr Key number(Ctx c, std::string_view name, Field f, Check check) {
  return make(c, name, Kind::Number, f, check);
}
constexpr Key integer(Ctx c, std::string_view name, Field f, Check check) {
  return make(c, name, Kind::Integer, f, check);
}
constexpr Key vector(Ctx c, std::string_view name, unsigned char size, Field f, Check check) {
  Key k = make(c, name, Kind::Vector, f, check);
  k.size = size;
  return k;
}
constexpr Key rows(Ctx c, std::string_view name, Kind kind, Field f, Check check) {
  Key k = make(c, name, kind, f, check);
  k.size = 3;
  return k;
}
constexpr Key choice(Ctx c, std::string_view name, Field f, std::string_view noun,
                     std::array<std::string_view, 3> choices) {
  Key k = make(c, name, Kind::Choice, f, kAny);
  k.noun = noun;
  k.choices = choices;
  return k;
}
constexpr Key object(Ctx c, std::string_view name, Ctx element, Check check) {
  Key k = make(c, name, Kind::Object, Field{}, check);
  k.element = element;
  return k;
}
constexpr Key objects(Ctx c, std::string_view name, Ctx element, size_t SceneLimits::*limit, Check check = kAny) {
  Key k = make(c, name, Kind::Objects, Field{}, check);
  k.element = element;
  k.limit = limit;
  k.fallback = "[]";
  return k;
}

constexpr unsigned char kPointOnly = 1 << static_cast<int>(LightType::Point);
constexpr unsigned char kDirectionalOnly = 1 << static_cast<int>(LightType::Directional);
// A light's "type" choices are LightType's values, in order.
static_assert(static_cast<int>(LightType::Ambient) == 0 && static_cast<int>(LightType::Point) == 1 &&
              static_cast<int>(LightType::Directional) == 2);

using W = Write;
// The keys of a plane's, triangle's or mesh's Material.
#define CLRT_MATERIAL_KEYS(context, Object)                                                                   \
  vector(context, "color", 3, CLRT_FIELD(Object, Vec3, o.material.color), kColor).need()                     \
      .described("its colour, 0-255 per channel"),                                                            \
  number(context, "specular", CLRT_FIELD(Object, double, o.material.specular), kSpecular).or_else("-1")      \
      .described("its specular exponent; -1: matte"),                                                         \
  number(context, "reflective", CLRT_FIELD(Object, double, o.material.reflective), in(0, 1)).or_else("0")    \
      .described("the share of light it reflects")
// clang-format off
constexpr Key kKeys[] = {
    // ---- the root object (Scene) ----
    object(Ctx::Root, "camera", Ctx::Camera, {Rule::RayReach, 0, kMaxLength})
        .described("the camera; its keys default to the book's camera"),
    vector(Ctx::Root, "background", 3, CLRT_FIELD(Scene, Vec3, o.background), kColor).or_else("[0, 0, 0]")
        .described("the colour of rays that hit nothing"),
    integer(Ctx::Root, "recursion_depth", CLRT_FIELD(Scene, int, o.recursion_depth), in(0, CLRT_MAX_DEPTH)).or_else("3")
        .described("reflections and refractions followed per ray when the command line gives no --depth"),
    number(Ctx::Root, "epsilon", CLRT_FIELD(Scene, double, o.epsilon), in(0, kMaxLength)).or_else("0.001")
        .described("the start of every secondary ray's range"),
    objects(Ctx::Root, "spheres", Ctx::Sphere, &SceneLimits::spheres).described("the spheres"),
    objects(Ctx::Root, "lights", Ctx::Light, &SceneLimits::lights, {Rule::IntensitySum, 0, kMaxTotalIntensity})
        .described("the lights"),
    objects(Ctx::Root, "planes", Ctx::Plane, &SceneLimits::planes).written(W::UnlessDefault)
        .described("infinite two-sided planes"),
    objects(Ctx::Root, "triangles", Ctx::Triangle, &SceneLimits::triangles).written(W::UnlessDefault)
        .described("flat-shaded triangles; with every mesh's faces at most 4 000 000"),
    objects(Ctx::Root, "meshes", Ctx::Mesh, &SceneLimits::meshes).written(W::Never)
        .described("Wavefront OBJ meshes; scene_to_json writes their faces as triangles"),
    // ---- camera (Camera) ----
    vector(Ctx::Camera, "position", 3, CLRT_FIELD(Camera, Vec3, o.position), kCoordinate).or_else("[0, 0, 0]")
        .described("the camera's position"),
    rows(Ctx::Camera, "rotation", Kind::Matrix, CLRT_FIELD(Camera, double, o.rotation[part * 3]), kAny)
        .or_else("[[1, 0, 0], [0, 1, 0], [0, 0, 1]]")
        .described("the camera's rotation, 3 rows of 3 numbers, row-major"),
    vector(Ctx::Camera, "viewport", 2, CLRT_FIELD(Camera, double, part == 0 ? o.viewport_w : o.viewport_h), kSize)
        .or_else("[1, 1]").described("the viewport's width and height, [Vw, Vh]"),
    number(Ctx::Camera, "projection_plane_d", CLRT_FIELD(Camera, double, o.projection_plane_d), kSize).or_else("1")
        .described("the distance from the camera to the viewport"),
    choice(Ctx::Camera, "aspect", CLRT_FIELD(Camera, bool, o.aspect_from_image), "aspect", {"viewport", "image"})
        .or_else("\"viewport\"").written(W::UnlessDefault)
        .described("viewport: the viewport as given, stretched to the image; image: fitted to the image"),
    // ---- a sphere (Sphere) ----
    vector(Ctx::Sphere, "center", 3, CLRT_FIELD(Sphere, Vec3, o.center), kCoordinate).need().described("its centre"),
    number(Ctx::Sphere, "radius", CLRT_FIELD(Sphere, double, o.radius), kSize).need().described("its radius"),
    vector(Ctx::Sphere, "color", 3, CLRT_FIELD(Sphere, Vec3, o.color), kColor).need()
        .described("its colour, 0-255 per channel"),
    number(Ctx::Sphere, "specular", CLRT_FIELD(Sphere, double, o.specular), kSpecular).or_else("-1")
        .described("its specular exponent; -1: matte"),
    number(Ctx::Sphere, "reflective", CLRT_FIELD(Sphere, double, o.reflective), in(0, 1)).or_else("0")
        .described("the share of light it reflects"),
    number(Ctx::Sphere, "transparency", CLRT_FIELD(Sphere, double, o.transparency), in(0, 1)).or_else("0")
        .written(W::UnlessDefault).described("the share of the light it does not reflect that passes through it"),
    number(Ctx::Sphere, "refractive_index", CLRT_FIELD(Sphere, double, o.refractive_index),
           in(kMinRefractiveIndex, kMaxRefractiveIndex)).or_else("1").written(W::UnlessDefault)
        .described("the refractive index of its inside; 1: no bending"),
    // ---- a light (Light); "type" selects which of direction and position it has ----
    choice(Ctx::Light, "type", CLRT_FIELD(Light, LightType, o.type), "light type", {"ambient", "point", "directional"})
        .need().described("ambient, point or directional"),
    number(Ctx::Light, "intensity", CLRT_FIELD(Light, double, o.intensity), in(0, kMaxTotalIntensity)).need()
        .described("its intensity"),
    vector(Ctx::Light, "direction", 3, CLRT_FIELD(Light, Vec3, o.vec), kDirection).need().only_for(kDirectionalOnly)
        .described("the direction the light comes from (directional lights)"),
    vector(Ctx::Light, "position", 3, CLRT_FIELD(Light, Vec3, o.vec), kCoordinate).need().only_for(kPointOnly)
        .described("its position (point lights)"),
    // ---- a plane (Plane) ----
    vector(Ctx::Plane, "point", 3, CLRT_FIELD(Plane, Vec3, o.point), kCoordinate).need()
        .described("a point of the plane"),
    vector(Ctx::Plane, "normal", 3, CLRT_FIELD(Plane, Vec3, o.normal), kNormal).need()
        .described("its normal, any length but 0"),
    CLRT_MATERIAL_KEYS(Ctx::Plane, Plane),
    // ---- a triangle (Triangle) ----
    rows(Ctx::Triangle, "vertices", Kind::Vertices,
         CLRT_FIELD(Triangle, Vec3, part == 0 ? o.v0 : part == 1 ? o.v1 : o.v2), kCoordinate).need()
        .described("its 3 vertices"),
    CLRT_MATERIAL_KEYS(Ctx::Triangle, Triangle),
    // ---- a mesh (MeshSource) ----
    make(Ctx::Mesh, "file", Kind::Path, CLRT_FIELD(MeshSource, std::string, o.file), kAny).need()
        .described("a Wavefront OBJ file, relative to the scene file's folder, without '..'"),
    CLRT_MATERIAL_KEYS(Ctx::Mesh, MeshSource),
    vector(Ctx::Mesh, "translate", 3, CLRT_FIELD(MeshSource, Vec3, o.transform.translate), kCoordinate)
        .or_else("[0, 0, 0]").described("added to every vertex, after rotate and scale"),
    vector(Ctx::Mesh, "rotate", 3, CLRT_FIELD(MeshSource, Vec3, o.transform.rotate_degrees), kAngles)
        .or_else("[0, 0, 0]").described("degrees about x, then y, then z"),
    number(Ctx::Mesh, "scale", CLRT_FIELD(MeshSource, double, o.transform.scale), kSize).or_else("1")
        .described("multiplies every vertex"),
};
#undef CLRT_MATERIAL_KEYS
// clang-format on
constexpr size_t kKeyCount = sizeof(kKeys) / sizeof(kKeys[0]);

// What each kind stores, so that a key's member has the type its value needs.
constexpr bool field_fits(const Key& k) {
  switch (k.kind) {
    case Kind::Object:
    case Kind::Objects:
      return k.field.type == FieldType::None;
    case Kind::Number:
    case Kind::Matrix:  // (a row: the first of its 3 doubles)
      return k.field.type == FieldType::Double;
    case Kind::Integer:
      return k.field.type == FieldType::Int;
    case Kind::Vector:
      return k.field.type == (k.size == 2 ? FieldType::Double : FieldType::Vec3);
    case Kind::Vertices:
      return k.field.type == FieldType::Vec3;
    case Kind::Choice:
      return k.field.type == FieldType::Bool || k.field.type == FieldType::LightType;
    case Kind::Path:
      return k.field.type == FieldType::String;
  }
  return false;
}

// The table's invariants: grouped by context in Ctx's order, at most 64 keys
// a context (Frame::seen), members that fit their kinds, Direction on lights
// only (it keeps Light::scale_exponent), a variant key's context with a Choice.
constexpr bool table_is_consistent() {
  size_t per_context[kContextCount] = {};
  for (size_t i = 0; i < kKeyCount; ++i) {
    const Key& k = kKeys[i];
    if (i > 0 && k.ctx < kKeys[i - 1].ctx) return false;
    if (++per_context[static_cast<size_t>(k.ctx)] > 64) return false;
    if (!field_fits(k)) return false;
    if (k.rule == Rule::Direction && k.ctx != Ctx::Light) return false;
    if (k.kind == Kind::Vector && k.size != 2 && k.size != 3) return false;
  }
  return true;
}
static_assert(table_is_consistent(), "the scene key table breaks one of its invariants (table_is_consistent)");

// Each context's keys: [first, first + count) of kKeys.
struct KeySpan {
  size_t first = 0, count = 0;
};
constexpr std::array<KeySpan, kContextCount> context_ranges() {
  std::array<KeySpan, kContextCount> r{};
  for (size_t i = kKeyCount; i-- > 0;) {
    KeySpan& range = r[static_cast<size_t>(kKeys[i].ctx)];
    range.first = i;
    ++range.count;
  }
  return r;
}
constexpr std::array<KeySpan, kContextCount> kRanges = context_ranges();

constexpr Context kContexts[kContextCount] = {
    {Ctx::Root, "scene", "The root object"}, {Ctx::Camera, "camera", "Camera"},
    {Ctx::Sphere, "sphere", "Spheres"},      {Ctx::Light, "light", "Lights"},
    {Ctx::Plane, "plane", "Planes"},         {Ctx::Triangle, "triangle", "Triangles"},
    {Ctx::Mesh, "mesh", "Meshes"},
};

// The prototypes: default-constructed objects with every fallback of the
// table stored through the keys' members.
Prototypes make_prototypes() {
  Prototypes p;
  void* objects[kContextCount] = {&p.scene, &p.scene.camera, &p.sphere, &p.light, &p.plane, &p.triangle, &p.mesh};
  for (const Key& k : all_keys())
    if (!k.fallback.empty() && k.kind != Kind::Object && k.kind != Kind::Objects)
      store_json(k, objects[static_cast<size_t>(k.ctx)], nlohmann::json::parse(k.fallback));
  return p;
}

}  // namespace key_table

KeyList all_keys() {
  return {key_table::kKeys, key_table::kKeyCount};
}

KeyList keys_of(Ctx c) {
  const key_table::KeySpan& r = key_table::kRanges[static_cast<size_t>(c)];
  return {key_table::kKeys + r.first, r.count};
}

const Context& context(Ctx c) {
  return key_table::kContexts[static_cast<size_t>(c)];
}

const Key* find_key(Ctx c, std::string_view name) {
  for (const Key& k : keys_of(c))
    if (k.name == name) return &k;
  return nullptr;
}

size_t key_index(const Key& k) {
  return static_cast<size_t>(&k - keys_of(k.ctx).first);
}

const Key* variant_key(Ctx c) {
  // (Found once: the reader asks at every object.)
  static const std::array<const Key*, kContextCount> selectors = [] {
    std::array<const Key*, kContextCount> s{};
    for (const Key& k : all_keys())
      if (k.variants)
        for (const Key& selector : keys_of(k.ctx))
          if (selector.kind == Kind::Choice) s[static_cast<size_t>(k.ctx)] = &selector;
    return s;
  }();
  return selectors[static_cast<size_t>(c)];
}

size_t choice_index(const Key& k, const void* object) {
  const void* member = k.field.get(object, 0);
  return k.field.type == FieldType::Bool ? size_t(*static_cast<const bool*>(member))
                                         : size_t(*static_cast<const LightType*>(member));
}

nlohmann::json value_json(const Key& k, const void* object) {
  using json = nlohmann::json;
  auto v3 = [](const Vec3& v) { return json::array({v.x, v.y, v.z}); };
  auto part = [&](size_t i) { return k.field.get(object, i); };
  switch (k.kind) {
    case Kind::Number:
      return *static_cast<const double*>(part(0));
    case Kind::Integer:
      return *static_cast<const int*>(part(0));
    case Kind::Vector:
      if (k.size == 2) return json::array({*static_cast<const double*>(part(0)), *static_cast<const double*>(part(1))});
      // (Direction: on lights only, table_is_consistent)
      if (k.rule == Rule::Direction) return v3(static_cast<const Light*>(object)->given_vec());
      return v3(*static_cast<const Vec3*>(part(0)));
    case Kind::Matrix: {
      json rows = json::array();
      for (size_t r = 0; r < 3; ++r) {
        const double* row = static_cast<const double*>(part(r));
        rows.push_back(json::array({row[0], row[1], row[2]}));
      }
      return rows;
    }
    case Kind::Vertices:
      return json::array({v3(*static_cast<const Vec3*>(part(0))), v3(*static_cast<const Vec3*>(part(1))),
                          v3(*static_cast<const Vec3*>(part(2)))});
    case Kind::Choice:
      return std::string(k.choices[choice_index(k, object)]);
    case Kind::Path:
      return *static_cast<const std::string*>(part(0));
    default:  // Object, Objects: written by scene_to_json, element by element
      return nullptr;
  }
}

void store_json(const Key& k, void* object, const nlohmann::json& value) {
  auto part = [&](size_t i) { return k.field.at(object, i); };
  auto vec3 = [](const nlohmann::json& v) { return Vec3{v.at(0).get<double>(), v.at(1).get<double>(), v.at(2).get<double>()}; };
  switch (k.kind) {
    case Kind::Number:
      *static_cast<double*>(part(0)) = value.get<double>();
      break;
    case Kind::Integer:
      *static_cast<int*>(part(0)) = value.get<int>();
      break;
    case Kind::Vector:
      if (k.size == 2) {
        *static_cast<double*>(part(0)) = value.at(0).get<double>();
        *static_cast<double*>(part(1)) = value.at(1).get<double>();
      } else {
        *static_cast<Vec3*>(part(0)) = vec3(value);
      }
      break;
    case Kind::Matrix:
      for (size_t r = 0; r < 3; ++r)
        for (size_t c = 0; c < 3; ++c) static_cast<double*>(part(r))[c] = value.at(r).at(c).get<double>();
      break;
    case Kind::Vertices:
      for (size_t v = 0; v < 3; ++v) *static_cast<Vec3*>(part(v)) = vec3(value.at(v));
      break;
    case Kind::Choice:
      for (size_t i = 0; i < k.choices.size(); ++i)
        if (!k.choices[i].empty() && value.get<std::string>() == k.choices[i]) {
          if (k.field.type == FieldType::Bool)
            *static_cast<bool*>(part(0)) = i != 0;
          else
            *static_cast<LightType*>(part(0)) = static_cast<LightType>(i);
        }
      break;
    case Kind::Path:
      *static_cast<std::string*>(part(0)) = value.get<std::string>();
      break;
    default:
      break;
  }
}

const Prototypes& prototypes() {
  static const Prototypes p = key_table::make_prototypes();
  return p;
}

}  // namespace clrt
