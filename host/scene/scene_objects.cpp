// scene_objects.cpp - the reader's objects: the keys an object may have and
// must have, the rules that wait for its end, where its element goes; and the
// -D overrides, applied where the reader reaches their place.
#include <algorithm>
#include <cmath>

#include "scene/scene_builder.hpp"
#include "scene/scene_text.hpp"

namespace clrt {

// Key k read in the object of frame f (`shown`: as the text spells it): a
// key of the other variant ("direction" on a point light) is unknown, and a
// key read twice is ambiguous (JSON parsers disagree on which one wins).
void SceneBuilder::accept_key(Frame& f, const Key& k, const std::string& shown) {
  if (f.variant >= 0 && k.variants && !(k.variants >> f.variant & 1)) {
    // (A -D that set the variant is named: it is why the key is unknown.)
    const Naming naming(*this, replaying_ ? nullptr : override_of(f, depth_ - 1, *variant_key(f.ctx)));
    fail(path(depth_ - 1), "unknown key " + json_quoted(shown));
  }
  const uint64_t bit = uint64_t(1) << key_index(k);
  if (f.seen & bit) fail(path(depth_ - 1), "duplicate key " + json_quoted(shown));
  f.seen |= bit;
  f.key = &k;
}

// The object of frame f read to its end (value_path() names it): its
// required keys, in the table's order, a variant's keys with the key that
// selects the variant, then the rules that need the whole object.
void SceneBuilder::finish_object(const Frame& f) {
  const Key* selector = variant_key(f.ctx);
  for (const Key& k : keys_of(f.ctx)) {
    if (k.variants) continue;
    if (!(f.seen >> key_index(k) & 1)) {
      if (k.required) report(value_path(), "missing \"" + std::string(k.name) + "\"");
      continue;
    }
    if (&k != selector || f.variant < 0) continue;
    for (const Key& v : keys_of(f.ctx)) {
      if (!(v.variants >> f.variant & 1)) continue;
      if (f.seen >> key_index(v) & 1) {
        finish_key(f, v);
      } else if (v.required) {
        const Naming naming(*this, replaying_ ? nullptr : override_of(f, depth_, k));  // a -D chose the variant
        report(value_path(), std::string(k.choices[size_t(f.variant)]) + " " + std::string(context(f.ctx).noun) +
                                 " needs \"" + std::string(v.name) + "\"");
      }
    }
  }
  for (const Key& k : keys_of(f.ctx))
    if (!k.variants && (f.seen >> key_index(k) & 1)) finish_key(f, k);
  keep(f);
}

// The rule of key k that waits for the end of its object: a direction or
// normal must not be the zero vector; it is rescaled by a power of two so
// that its largest component lies in [0.5, 1): [1e-300, 1e-300, -1e-300]
// has a squared length of 0 in double, [1e300, 0, 0] one of inf, [0, 1e39,
// -1e39] overflows float. A power of two is exact (the book's formulas give
// bit-identical results for the shipped scenes) and idempotent (a scene
// written back by scene_to_json parses to the same values). Every use of a
// plane's normal is scale-invariant or normalizes it; a light keeps the
// exponent, since the book's shadow ray is measured in the direction's units
// (Light::shadow_t_min).
void SceneBuilder::finish_key(const Frame& f, const Key& k) {
  if (k.rule != Rule::Direction && k.rule != Rule::Normal) return;
  void* object = object_of(f.ctx);
  Vec3& v = *static_cast<Vec3*>(k.field.at(object, 0));
  if (v.x == 0 && v.y == 0 && v.z == 0) {
    const Naming naming(*this, replaying_ ? nullptr : override_of(f, depth_, k));  // a -D gave it: name the -D
    return report(value_path() + "." + std::string(k.name), "must not be the zero vector");
  }
  int e = 0;
  (void)std::frexp(std::max({std::fabs(v.x), std::fabs(v.y), std::fabs(v.z)}), &e);
  v = {std::ldexp(v.x, -e), std::ldexp(v.y, -e), std::ldexp(v.z, -e)};
  if (k.rule == Rule::Direction) static_cast<Light*>(object)->scale_exponent = e;  // (lights only: the table's rule)
}

// An element read to its end goes to the scene (meshes: to the list loaded
// after the parse). Collect mode: not an element with a problem.
void SceneBuilder::keep(const Frame& f) {
  if (f.bad) return;
  // (The root and the camera are read in place.)
  if (f.ctx == Ctx::Sphere) scene_.spheres.push_back(sphere_);
  if (f.ctx == Ctx::Light) scene_.lights.push_back(light_);
  if (f.ctx == Ctx::Plane) scene_.planes.push_back(plane_);
  if (f.ctx == Ctx::Triangle) scene_.triangles.push_back(triangle_);
  if (f.ctx == Ctx::Mesh) {
    mesh_.where = value_path();
    meshes_.push_back(mesh_);
  }
}

// ---- -D overrides ----
// Whether the first `frames` frames are the path of override p: each
// object's key and each array's index as p's steps say.
bool SceneBuilder::matches(const Pending& p, size_t frames) const {
  const auto& steps = p.override->steps;
  if (steps.size() < frames) return false;
  for (size_t i = 0; i < frames; ++i) {
    const Frame& f = stack_[i];
    if (f.kind == FrameKind::Object ? f.key != steps[i].key
                                    : f.kind != FrameKind::Elements || steps[i].key || f.count != steps[i].index)
      return false;
  }
  return true;
}

// A value about to be read whose place an override names: the override's
// value is read instead (then the text's is skipped).
bool SceneBuilder::replace_value() {
  if (pending_ == 0) return false;
  for (Pending& p : overrides_)
    if (!p.applied && p.override->steps.size() == depth_ && matches(p, depth_)) {
      apply(p);
      return true;
    }
  return false;
}

// Reads override p's value at the reader's place, as if the text had it
// there (overrides of places inside it apply in turn).
void SceneBuilder::apply(Pending& p) {
  p.applied = true;
  --pending_;
  if (depth_ > 0 && top().kind == FrameKind::Object) top().overridden |= uint64_t(1) << key_index(*top().key);
  const Naming naming(*this, &p);
  nlohmann::json::sax_parse(p.override->value, this);  // (the value was checked as JSON by parse_overrides)
}

// At the end of an object (its frame on top): the overrides of keys its text
// does not have. A key of the object's own is added with the override's value;
// a path through an absent object (the camera) adds the object; a path into
// an absent array names an element the scene does not have.
void SceneBuilder::apply_absent() {
  if (pending_ == 0) return;
  for (const bool exact : {true, false})
    for (Pending& p : overrides_) {
      const auto& steps = p.override->steps;
      if (p.applied || steps.size() < depth_ || (steps.size() == depth_) != exact || !matches(p, depth_ - 1)) continue;
      const Key& k = *steps[depth_ - 1].key;  // (an object's step: a key)
      Frame& f = top();
      if (k.ctx != f.ctx || (f.seen >> key_index(k) & 1)) continue;  // in the text: applied where it is
      try {
        if (!exact && k.kind == Kind::Objects) {
          p.applied = true;
          --pending_;
          const Naming naming(*this, &p);
          report("", "the scene has 0 " + std::string(k.name));
        } else {
          {
            const Naming naming(*this, &p);
            accept_key(f, k, std::string(k.name));
          }
          if (exact) {
            apply(p);
          } else {  // an object (the camera) the text does not have: an empty one, which the override fills
            start_object(0);
            end_object();
          }
        }
      } catch (const Recover&) {  // (collect mode: reported)
        if (!p.applied) --pending_;
        p.applied = true;
      }
    }
}

// At the end of an array of elements (its frame on top): overrides of
// elements past its end.
void SceneBuilder::check_indices() {
  if (pending_ == 0) return;
  const Frame& f = top();
  for (Pending& p : overrides_) {
    if (p.applied || p.override->steps.size() < depth_ || !matches(p, depth_ - 1)) continue;
    const size_t n = f.count;
    p.applied = true;
    --pending_;
    const Naming naming(*this, &p);
    report("", "the scene has " + std::to_string(n) + " " +
                   (n == 1 ? std::string(context(f.key->element).noun) : std::string(f.key->name)));
  }
}

// The override that gave key k of the object of frame f, if one did; the
// object's place is the first `object_depth` frames (its parent's key or
// index last).
const SceneBuilder::Pending* SceneBuilder::override_of(const Frame& f, size_t object_depth, const Key& k) const {
  if (!(f.overridden >> key_index(k) & 1)) return nullptr;
  for (const Pending& p : overrides_) {
    const auto& steps = p.override->steps;
    if (steps.size() == object_depth + 1 && steps[object_depth].key == &k && matches(p, object_depth)) return &p;
  }
  return nullptr;
}

}  // namespace clrt
