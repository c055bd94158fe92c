// scene_builder.hpp - the streaming scene reader: a SAX handler that checks
// each value against its key's entry in the table (scene_keys.hpp) as it
// arrives and stores it through the key's member, so a file is read in one
// pass without a document tree (memory: the scene, the object being read and
// a stack of at most kMaxDepth frames). The -D overrides are applied as the
// reader reaches their place, as if the file said so; in collect mode
// (`clrt validate`) every problem is reported and the reader goes on.
// Its parts: scene_builder.cpp (events, frames, recovery), scene_values.cpp
// (values and their rules), scene_objects.cpp (objects' keys, the -D
// overrides), scene_meshes.cpp (after the parse: meshes, the camera).
#pragma once
#include <array>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "scene/scene_json.hpp"
#include "scene/scene_keys.hpp"

namespace clrt {

// Where the problems go in collect mode.
using ProblemSink = std::function<void(const std::string& message)>;

class SceneBuilder final : public nlohmann::json_sax<nlohmann::json> {
 public:
  // `folder`: where mesh files are looked up (the scene file's folder); none
  // for a scene that is not a file. `collect`: null to throw UserError at the
  // first problem; else each problem goes there and the reader goes on.
  SceneBuilder(const std::string& name, const SceneLimits& limits, std::optional<std::filesystem::path> folder,
               const SceneOverrides& overrides, const ProblemSink* collect);

  // After the parse: the meshes' files and the checks that need the whole
  // scene (scene_meshes.cpp).
  Scene finish();
  // Collect mode: the text was malformed, the parse stopped.
  bool stopped() const { return stopped_; }

  // ---- SAX events ----
  bool null() override;
  bool boolean(bool) override;
  bool number_integer(number_integer_t v) override;
  bool number_unsigned(number_unsigned_t v) override;
  bool number_float(number_float_t v, const string_t&) override;
  bool binary(binary_t&) override;
  bool string(string_t& v) override;
  bool start_object(std::size_t) override;
  bool key(string_t& k) override;
  bool end_object() override;
  bool start_array(std::size_t) override;
  bool end_array() override;
  bool parse_error(std::size_t, const std::string&, const nlohmann::detail::exception& e) override;

 private:
  // root, triangles, triangle, vertices, vertex
  static constexpr size_t kMaxDepth = 5;

  // An open container.
  enum class FrameKind : unsigned char {
    Object,    // an object of context `ctx`; `key`: the key whose value is being read
    Elements,  // the array of an Objects key
    Rows,      // the array of a Matrix or Vertices key
    Numbers,   // an array of numbers: a Vector key's, or a row of a Matrix or Vertices key
  };
  struct Frame {
    FrameKind kind = FrameKind::Object;
    Ctx ctx = Ctx::Root;
    const Key* key = nullptr;  // Object: the key being read (none yet: null); arrays: the key they are the value of
    uint64_t seen = 0;         // Object: bit key_index(k) of every key read
    uint64_t overridden = 0;   // Object: of those, the keys a -D gave
    int variant = -1;          // Object: the choice its variant key selected, once read
    bool bad = false;          // collect mode: a problem inside it (an element is then not kept)
    size_t count = 0;          // arrays: elements read (the index of the one being read)
  };
  // What the next value is.
  enum class Role : unsigned char { Document, Value, Element, Row, Component };
  struct Target {
    Role role;
    const Key* key;  // Value: its key; Element, Row, Component: the key of the array
  };
  // Collect mode: thrown by fail() after the problem is reported, caught by
  // the event, which skips the rest of the value (whole_array: of the array).
  struct Recover {
    bool whole_array = false;
  };
  // A -D override and whether it has been applied.
  struct Pending {
    const SceneOverride* override;
    bool applied = false;
  };
  // While it lives, messages name override p (null: as they did).
  class Naming {
   public:
    Naming(SceneBuilder& b, const Pending* p) : b_(b), outer_(b.replaying_) {
      if (p) b.replaying_ = p;
    }
    ~Naming() { b_.replaying_ = outer_; }
    Naming(const Naming&) = delete;
    Naming& operator=(const Naming&) = delete;

   private:
    SceneBuilder& b_;
    const Pending* outer_;
  };

  // ---- events (scene_builder.cpp) ----
  template <class Read>
  bool scalar(Read&& read);
  template <class Open>
  bool container(Open&& open);
  bool skip_value(bool container);
  bool end_skipped();
  void skip(size_t containers, bool then_next);
  void recover(const Recover& r, bool container);
  Target enter_value();
  void open_object(const Target& t);
  void open_array(const Target& t);
  [[noreturn]] void type_error(const Target& t, const std::string& got);
  Frame& top() { return stack_[depth_ - 1]; }
  void push(const Frame& f);
  Frame pop() { return stack_[--depth_]; }
  void next_element();
  void* object_of(Ctx c);

  // ---- messages ----
  std::string message(const std::string& where, const std::string& what) const;
  // The problem: thrown as UserError, or (collect mode) reported and thrown as Recover.
  [[noreturn]] void fail(const std::string& where, const std::string& what, bool whole_array = false);
  // The same for a problem after which reading goes on: reported, not thrown, in collect mode.
  void report(const std::string& where, const std::string& what);
  // The path of the value frame n - 1 is reading ("spheres[3].center").
  std::string path(size_t n) const;
  std::string value_path() const { return path(depth_); }

  // ---- values (scene_values.cpp) ----
  template <class Int>
  void integer(const Target& t, Int v);
  void number(const Target& t, double v);
  void text(const Target& t, const std::string& v);
  void choose(const Key& k, const std::string& v);
  void mesh_file(const Key& k, const std::string& file);
  bool number_ok(const Key& k, double v, int component);
  void finish_numbers(const Frame& f);
  bool vector_ok(const Key& k, const std::array<double, 3>& c, size_t n);
  void store_vector(const Key& k, void* object, size_t part, size_t n);
  void finish_array(const Frame& f);

  // ---- objects and overrides (scene_objects.cpp) ----
  void accept_key(Frame& f, const Key& k, const std::string& shown);
  void finish_object(const Frame& f);
  void finish_key(const Frame& f, const Key& k);
  void keep(const Frame& f);
  bool matches(const Pending& p, size_t frames) const;
  bool replace_value();
  void apply(Pending& p);
  void apply_absent();
  void check_indices();
  const Pending* override_of(const Frame& f, size_t object_depth, const Key& k) const;

  // ---- after the parse (scene_meshes.cpp) ----
  void load_meshes();
  void check_camera();

  const std::string& name_;
  const SceneLimits limits_;
  const std::optional<std::filesystem::path> folder_;
  const ProblemSink* collect_;
  std::vector<Pending> overrides_;
  size_t pending_ = 0;                  // overrides not yet applied
  const Pending* replaying_ = nullptr;  // the override whose value is being read
  bool stopped_ = false;
  std::array<Frame, kMaxDepth> stack_;
  size_t depth_ = 0;
  // Skipping: the containers still open in a value being skipped; whether its
  // end counts as an element read; whether the next value is skipped whole.
  size_t skip_depth_ = 0;
  bool skip_then_next_ = false;
  bool skip_next_ = false;
  // The objects being read: the scene (root and camera) and one of each element.
  Scene scene_;
  Sphere sphere_;
  Light light_;
  Plane plane_;
  Triangle triangle_;
  MeshSource mesh_;
  std::vector<MeshSource> meshes_;  // loaded by finish(), after the parse
  std::array<double, 3> numbers_{};  // the array of numbers being read
};

}  // namespace clrt
