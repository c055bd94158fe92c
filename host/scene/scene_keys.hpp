// scene_keys.hpp - the scene format's keys, each declared once (in the
// manner of pbrt-v4's ParameterDictionary and Mitsuba 3's Properties): per
// object of the format (a context: the root, the camera, a sphere, a light,
// ...), each key's name, the kind of its value, the rule its value must
// keep, its default, whether it is required, and the member of the scene
// model it fills. The streaming reader (scene_builder.hpp), the writer
// (scene_to_json), the -D overrides (scene_overrides.hpp), the JSON Schema
// (scene_schema.hpp) and the tests of the fuzz dictionary and of
// docs/reference/scene-format.md all read this one table (scene_keys.cpp).
#pragma once
#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <type_traits>

#include <nlohmann/json.hpp>

#include "scene/obj_mesh.hpp"
#include "scene/scene.hpp"
#include "scene/scene_json.hpp"

namespace clrt {

// The objects of the format. Each maps to the C++ object its keys fill:
// Root -> Scene, Camera -> Camera, Sphere -> Sphere, Light -> Light, Plane ->
// Plane, Triangle -> Triangle, Mesh -> MeshSource.
enum class Ctx : unsigned char { Root, Camera, Sphere, Light, Plane, Triangle, Mesh };
constexpr size_t kContextCount = 7;

// A mesh as the scene names it; its file is read after the parse.
struct MeshSource {
  std::string file;  // relative to the scene's folder
  MeshTransform transform;
  Material material;
  std::string where;  // "meshes[2]", for messages
};

// The shape of a key's value.
enum class Kind : unsigned char {
  Object,    // an object of context `element` (the camera)
  Objects,   // an array of objects of context `element` (spheres, ...)
  Number,    // any JSON number
  Integer,   // an integer literal (3, not 3.0)
  Vector,    // an array of `size` numbers (2 or 3)
  Matrix,    // 3 arrays of 3 numbers, row-major (camera.rotation)
  Vertices,  // 3 arrays of 3 numbers, each a point (a triangle's vertices)
  Choice,    // one of the strings in `choices`
  Path,      // a file name relative to the scene's folder
};

// The rule a value keeps, with the bounds lo and hi where it has them.
enum class Rule : unsigned char {
  None,          // any finite number (camera.rotation: see RayReach)
  Range,         // in [lo, hi]
  Size,          // in [lo, hi] = [kMinLength, kMaxLength]; "must be > 0" below 0
  Specular,      // -1 (matte) or in [lo, hi]
  Coordinate,    // each component within [lo, hi]
  Color,         // each component in [lo, hi]
  Angles,        // each component within [lo, hi] degrees
  Direction,     // not the zero vector; rescaled by a power of two, the exponent kept (Light::scale_exponent)
  Normal,        // not the zero vector; rescaled by a power of two
  IntensitySum,  // (lights) the elements' intensities add up to at most hi
  RayReach,      // (camera) each rotation row x (viewport / 2, d) reaches at most hi
};

// Whether scene_to_json writes the key.
enum class Write : unsigned char { Always, UnlessDefault, Never };

// The C++ type of a key's member (checked against the kind at compile time).
enum class FieldType : unsigned char { None, Double, Int, Vec3, Bool, LightType, String };
template <class T>
constexpr FieldType field_type_of() {
  if constexpr (std::is_same_v<T, double>) return FieldType::Double;
  if constexpr (std::is_same_v<T, int>) return FieldType::Int;
  if constexpr (std::is_same_v<T, Vec3>) return FieldType::Vec3;
  if constexpr (std::is_same_v<T, bool>) return FieldType::Bool;
  if constexpr (std::is_same_v<T, LightType>) return FieldType::LightType;
  if constexpr (std::is_same_v<T, std::string>) return FieldType::String;
  return FieldType::None;
}

// The member a key fills, in the object of its context: `at` gives its
// address in an object being read, `get` in one being written. `part`
// numbers the parts of a value held in several members: a viewport's two
// sizes (double each), a rotation's rows (the first of each row's 3
// doubles), a triangle's vertices (Vec3 each); 0 for the others.
struct Field {
  void* (*at)(void* object, size_t part) = nullptr;
  const void* (*get)(const void* object, size_t part) = nullptr;
  FieldType type = FieldType::None;
};
// CLRT_FIELD(Sphere, double, o.radius): `o` is the object, `part` the part.
#define CLRT_FIELD(Object, Type, member)                            \
  ::clrt::Field {                                                   \
    [](void* object_, size_t part) -> void* {                       \
      Object& o = *static_cast<Object*>(object_);                   \
      (void)part;                                                   \
      Type& value_ = (member);                                      \
      return &value_;                                               \
    },                                                              \
        [](const void* object_, size_t part) -> const void* {       \
          const Object& o = *static_cast<const Object*>(object_);   \
          (void)part;                                               \
          const Type& value_ = (member);                            \
          return &value_;                                           \
        },                                                          \
        ::clrt::field_type_of<Type>()                               \
  }

// One key of one context.
struct Key {
  Ctx ctx = Ctx::Root;
  std::string_view name;
  Kind kind = Kind::Number;
  unsigned char size = 0;       // Vector: its numbers
  Ctx element = Ctx::Root;      // Object, Objects: the context of the value or of its elements
  Rule rule = Rule::None;
  double lo = 0, hi = 0;        // the rule's bounds
  bool required = false;
  // The values of the object's Choice key ("type") this key belongs to, bit
  // i for choice i; 0: every object of the context has it.
  unsigned char variants = 0;
  std::string_view fallback;    // the default, as JSON text; "" where there is none
  Write write = Write::Always;
  Field field;                  // value keys; none for Object and Objects
  size_t SceneLimits::*limit = nullptr;  // Objects: the most elements
  std::array<std::string_view, 3> choices{};  // Choice: the strings, in the order of the member's values
  std::string_view noun;        // Choice: what a value is called in messages ("light type")
  std::string_view about;       // one line: what the key is (the schema's description)

  // Modifiers, for the table's one-line entries. (with() before its callers:
  // clang 15 does not instantiate a member template defined later in the
  // class for the table's constant expression.)
  template <class T>
  constexpr Key with(T Key::*member, T value) const {
    Key k = *this;
    k.*member = value;
    return k;
  }
  constexpr Key need() const { return with(&Key::required, true); }
  constexpr Key or_else(std::string_view json) const { return with(&Key::fallback, json); }
  constexpr Key written(Write w) const { return with(&Key::write, w); }
  constexpr Key only_for(unsigned char choice_bits) const { return with(&Key::variants, choice_bits); }
  constexpr Key described(std::string_view text) const { return with(&Key::about, text); }
};

// An object of the format: its keys are keys_of(ctx).
struct Context {
  Ctx ctx;
  std::string_view noun;   // "sphere": messages ("the scene has 1 sphere", "point light needs")
  std::string_view title;  // the heading of its table in docs/reference/scene-format.md
};

// Every key, grouped by context in the order of Ctx; within a context, in
// the order missing keys are reported and the documentation lists them.
struct KeyList {
  const Key* first;
  size_t count;
  const Key* begin() const { return first; }
  const Key* end() const { return first + count; }
  size_t size() const { return count; }
  const Key& operator[](size_t i) const { return first[i]; }
};
KeyList all_keys();
KeyList keys_of(Ctx c);
const Context& context(Ctx c);
// The key `name` of context c; nullptr when it has none.
const Key* find_key(Ctx c, std::string_view name);
// A key's index within its context (its bit in a set of keys read).
size_t key_index(const Key& k);
// The context's Choice key that selects its variants ("type" of a light); nullptr if none.
const Key* variant_key(Ctx c);

// The objects every value starts from: the table's defaults, stored through
// the keys' members (a sphere without "specular" has the table's -1).
struct Prototypes {
  Scene scene;  // with the camera's defaults
  Sphere sphere;
  Light light;
  Plane plane;
  Triangle triangle;
  MeshSource mesh;
};
const Prototypes& prototypes();

// The index in k.choices of a Choice key's value in `object`.
size_t choice_index(const Key& k, const void* object);
// A key's value in `object` (of the key's context) as a scene file gives it
// (a light's direction as given, not rescaled): what scene_to_json writes.
nlohmann::json value_json(const Key& k, const void* object);
// `value` (valid for the key) stored into `object`: the prototypes' defaults.
void store_json(const Key& k, void* object, const nlohmann::json& value);

}  // namespace clrt
