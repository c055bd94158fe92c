// scene_builder.cpp - the reader's events: which value comes next, the
// containers it opens, the types a key refuses, the messages, and (collect
// mode) how reading goes on after a problem.
#include "scene/scene_builder.hpp"

#include "scene/scene_text.hpp"
#include "util/error.hpp"

namespace clrt {

SceneBuilder::SceneBuilder(const std::string& name, const SceneLimits& limits,
                           std::optional<std::filesystem::path> folder, const SceneOverrides& overrides,
                           const ProblemSink* collect)
    : name_(name), limits_(limits), folder_(std::move(folder)), collect_(collect), scene_(prototypes().scene) {
  for (const SceneOverride& o : overrides) overrides_.push_back({&o});
  pending_ = overrides_.size();
}

// ---- SAX events ----
// Every value: skipped (the rest of a value in error, a value a -D replaced),
// replaced by an override, or read.
template <class Read>
bool SceneBuilder::scalar(Read&& read) {
  if (skip_value(false)) return true;
  try {
    const Target t = enter_value();
    if (replace_value()) return true;  // (the override's value was counted)
    read(t);
    next_element();
  } catch (const Recover& r) {
    recover(r, false);
  }
  return true;
}

template <class Open>
bool SceneBuilder::container(Open&& open) {
  if (skip_value(true)) return true;
  try {
    const Target t = enter_value();
    if (replace_value()) {
      skip(1, /*then_next=*/false);
      return true;
    }
    open(t);
  } catch (const Recover& r) {
    recover(r, true);
  }
  return true;
}

bool SceneBuilder::null() {
  return scalar([&](const Target& t) { type_error(t, "null"); });
}
bool SceneBuilder::boolean(bool) {
  return scalar([&](const Target& t) { type_error(t, "boolean"); });
}
bool SceneBuilder::number_integer(number_integer_t v) {
  return scalar([&](const Target& t) { integer(t, v); });
}
bool SceneBuilder::number_unsigned(number_unsigned_t v) {
  return scalar([&](const Target& t) { integer(t, v); });
}
bool SceneBuilder::number_float(number_float_t v, const string_t&) {
  return scalar([&](const Target& t) {
    if (t.role == Role::Value && t.key->kind == Kind::Integer) type_error(t, "number");
    number(t, v);
  });
}
bool SceneBuilder::binary(binary_t&) {
  return scalar([&](const Target& t) { type_error(t, "binary"); });
}
bool SceneBuilder::string(string_t& v) {
  return scalar([&](const Target& t) { text(t, v); });
}
bool SceneBuilder::start_object(std::size_t) {
  return container([&](const Target& t) { open_object(t); });
}
bool SceneBuilder::start_array(std::size_t) {
  return container([&](const Target& t) { open_array(t); });
}

bool SceneBuilder::key(string_t& k) {
  if (skip_depth_ > 0) return true;
  try {
    Frame& f = top();  // (an object's: the parser sends keys in objects only)
    const Key* key = find_key(f.ctx, k);
    if (!key) fail(path(depth_ - 1), "unknown key " + json_quoted(k));
    accept_key(f, *key, k);
  } catch (const Recover&) {
    skip_next_ = true;  // the key's value
  }
  return true;
}

bool SceneBuilder::end_object() {
  if (end_skipped()) return true;
  apply_absent();  // the -D keys this object's text does not have
  const Frame f = pop();
  finish_object(f);  // value_path() now names the object itself
  next_element();
  return true;
}

bool SceneBuilder::end_array() {
  if (end_skipped()) return true;
  if (top().kind == FrameKind::Elements) check_indices();  // -D indices past the end
  const Frame f = pop();
  // value_path() now names the array itself.
  if (f.kind == FrameKind::Numbers) finish_numbers(f);
  if (f.kind == FrameKind::Rows && f.count != 3)
    report(value_path(),
           f.key->kind == Kind::Matrix ? "expected a 3x3 array of numbers" : "expected 3 vertices of 3 numbers each");
  if (f.kind == FrameKind::Elements) finish_array(f);
  next_element();
  return true;
}

bool SceneBuilder::parse_error(std::size_t, const std::string&, const nlohmann::detail::exception& e) {
  const std::string what = name_ + ": " + parse_error_text(e);
  if (!collect_) throw UserError(what);
  (*collect_)(what);
  stopped_ = true;
  return false;  // the text cannot be read on
}

// ---- skipping ----
bool SceneBuilder::skip_value(bool container) {
  if (skip_depth_ > 0) {
    if (container) ++skip_depth_;
    return true;
  }
  if (!skip_next_) return false;
  skip_next_ = false;
  if (container) skip(1, /*then_next=*/false);  // (a key's value: nothing to count)
  return true;
}

bool SceneBuilder::end_skipped() {
  if (skip_depth_ == 0) return false;
  if (--skip_depth_ == 0 && skip_then_next_) next_element();
  return true;
}

void SceneBuilder::skip(size_t containers, bool then_next) {
  skip_depth_ = containers;
  skip_then_next_ = then_next;
}

// Collect mode, after a problem in a value: the rest of the value is skipped
// (one problem a value), with the arrays it is part of up to its key (a
// vector, a rotation) or, for an array over its limit, the whole array.
void SceneBuilder::recover(const Recover& r, bool container) {
  size_t open = container ? 1 : 0;
  while (depth_ > 0 && (top().kind == FrameKind::Numbers || top().kind == FrameKind::Rows)) {
    --depth_;
    ++open;
  }
  if (r.whole_array && depth_ > 0 && top().kind == FrameKind::Elements) {
    --depth_;
    ++open;
  }
  if (open == 0)
    next_element();
  else
    skip(open, /*then_next=*/true);
}

// ---- frames ----
// What the next value is; one element too many is an error.
SceneBuilder::Target SceneBuilder::enter_value() {
  if (depth_ == 0) return {Role::Document, nullptr};
  const Frame& f = top();
  switch (f.kind) {
    case FrameKind::Object:
      return {Role::Value, f.key};
    case FrameKind::Elements: {
      const size_t limit = limits_.*(f.key->limit);
      if (f.count >= limit)
        fail(path(depth_ - 1),
             "more than " + std::to_string(limit) + " " + std::string(f.key->name) + ", the most clrt loads",
             /*whole_array=*/true);
      return {Role::Element, f.key};
    }
    case FrameKind::Rows:
      if (f.count >= 3)
        fail(path(depth_ - 1), f.key->kind == Kind::Matrix ? "expected a 3x3 array of numbers"
                                                           : "expected 3 vertices of 3 numbers each");
      return {Role::Row, f.key};
    case FrameKind::Numbers:
    default: {
      const size_t n = f.key->kind == Kind::Vector ? f.key->size : 3;
      if (f.count >= n) fail(path(depth_ - 1), "expected an array of " + std::to_string(n) + " numbers");
      return {Role::Component, f.key};
    }
  }
}

void SceneBuilder::open_object(const Target& t) {
  Ctx c = Ctx::Root;
  if (t.role == Role::Document) {
    scene_ = prototypes().scene;
  } else if ((t.role == Role::Value && t.key->kind == Kind::Object) || t.role == Role::Element) {
    c = t.key->element;
  } else {
    type_error(t, "object");
  }
  // Each object starts from the table's defaults.
  const Prototypes& p = prototypes();
  if (c == Ctx::Camera) scene_.camera = p.scene.camera;
  if (c == Ctx::Sphere) sphere_ = p.sphere;
  if (c == Ctx::Light) light_ = p.light;
  if (c == Ctx::Plane) plane_ = p.plane;
  if (c == Ctx::Triangle) triangle_ = p.triangle;
  if (c == Ctx::Mesh) mesh_ = p.mesh;
  Frame f;
  f.kind = FrameKind::Object;
  f.ctx = c;
  push(f);
}

void SceneBuilder::open_array(const Target& t) {
  Frame f;
  f.key = t.key;
  if (t.role == Role::Row) {
    f.kind = FrameKind::Numbers;
  } else if (t.role != Role::Value) {
    type_error(t, "array");
  } else if (t.key->kind == Kind::Objects) {
    f.kind = FrameKind::Elements;
  } else if (t.key->kind == Kind::Vector) {
    f.kind = FrameKind::Numbers;
  } else if (t.key->kind == Kind::Matrix || t.key->kind == Kind::Vertices) {
    f.kind = FrameKind::Rows;
  } else {
    type_error(t, "array");
  }
  push(f);
}

// A value of type `got` where the target wants another.
void SceneBuilder::type_error(const Target& t, const std::string& got) {
  std::string expected = "a number, got " + got;
  if (t.role == Role::Document || t.role == Role::Element) expected = "an object, got " + got;
  if (t.role == Role::Row) expected = "an array of 3 numbers";
  if (t.role == Role::Value) {
    switch (t.key->kind) {
      case Kind::Object:
        expected = "an object, got " + got;
        break;
      case Kind::Objects:
        expected = "an array, got " + got;
        break;
      case Kind::Vector:
        expected = "an array of " + std::to_string(t.key->size) + " numbers";
        break;
      case Kind::Matrix:
        expected = "a 3x3 array of numbers";
        break;
      case Kind::Vertices:
        expected = "3 vertices of 3 numbers each";
        break;
      case Kind::Integer:
        expected = "an integer, got " + got;
        break;
      case Kind::Choice:
      case Kind::Path:
        expected = "a string";
        break;
      case Kind::Number:
        break;
    }
  }
  fail(value_path(), "expected " + expected);
}

void SceneBuilder::push(const Frame& f) {
  // Not reached: the format nests kMaxDepth deep and every other container is a type error.
  if (depth_ == kMaxDepth) fail(value_path(), "nested deeper than " + std::to_string(kMaxDepth) + " levels");
  stack_[depth_++] = f;
}

// After a value: the next element of its array.
void SceneBuilder::next_element() {
  if (depth_ > 0 && top().kind != FrameKind::Object) ++top().count;
}

void* SceneBuilder::object_of(Ctx c) {
  switch (c) {
    case Ctx::Root:
      return &scene_;
    case Ctx::Camera:
      return &scene_.camera;
    case Ctx::Sphere:
      return &sphere_;
    case Ctx::Light:
      return &light_;
    case Ctx::Plane:
      return &plane_;
    case Ctx::Triangle:
      return &triangle_;
    case Ctx::Mesh:
    default:
      return &mesh_;
  }
}

// ---- messages ----
// "<name>: <where>: <what>"; while an override's value is read, "-D <text>:
// <where>: <what>" (<where> left out where it is the override's own path).
std::string SceneBuilder::message(const std::string& where, const std::string& what) const {
  if (replaying_) {
    const SceneOverride& o = *replaying_->override;
    return "-D " + o.text + ": " + (where.empty() || where == o.shown ? "" : where + ": ") + what;
  }
  return name_ + ": " + (where.empty() ? "" : where + ": ") + what;
}

void SceneBuilder::fail(const std::string& where, const std::string& what, bool whole_array) {
  if (!collect_) throw UserError(message(where, what));
  report(where, what);
  throw Recover{whole_array};
}

void SceneBuilder::report(const std::string& where, const std::string& what) {
  if (!collect_) throw UserError(message(where, what));
  (*collect_)(message(where, what));
  for (size_t i = 0; i < depth_; ++i) stack_[i].bad = true;
}

std::string SceneBuilder::path(size_t n) const {
  std::string p;
  for (size_t i = 0; i < n; ++i) {
    const Frame& f = stack_[i];
    if (f.kind == FrameKind::Object) {
      if (!f.key) break;  // no key read yet
      if (!p.empty()) p += '.';
      p += f.key->name;
    } else {
      p += '[' + std::to_string(f.count) + ']';
    }
  }
  return p;
}

std::string parse_error_text(const nlohmann::detail::exception& e) {
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
  const bool overflow = dynamic_cast<const nlohmann::json::out_of_range*>(&e) != nullptr;
  return (overflow ? "number out of range: " : "malformed JSON: ") + msg;
}

}  // namespace clrt
