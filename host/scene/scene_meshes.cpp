// scene_meshes.cpp - the reader after the parse: the meshes' OBJ files, read
// beneath the scene's folder, and the rules that need the whole scene.
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstring>
#include <map>
#include <stdexcept>

#include "scene/scene_builder.hpp"
#include "scene/scene_text.hpp"
#include "util/bytes_text.hpp"
#include "util/doing.hpp"
#include "util/error.hpp"
#include "util/open_beneath.hpp"

namespace clrt {

Scene SceneBuilder::finish() {
  if (stopped_) return {};
  if (depth_ != 0) fail("", "incomplete scene");  // not reached: the parser reports the end of the text
  // Every override has found its place, or been reported (collect mode:
  // or lies in a value skipped after a problem).
  if (pending_ != 0 && !collect_) throw std::logic_error("a -D override was not applied");
  load_meshes();
  check_camera();
  return std::move(scene_);
}

// The camera key's rule: its ray directions, rotation x (viewport / 2, d),
// stay in range.
void SceneBuilder::check_camera() {
  const Key& camera = *find_key(Ctx::Root, "camera");
  const Camera& c = scene_.camera;
  const auto& r = c.rotation;
  const double half_w = c.viewport_w / 2, half_h = c.viewport_h / 2, d = c.projection_plane_d;
  for (int row = 0; row < 3; ++row) {
    const double reach =
        std::fabs(r[row * 3]) * half_w + std::fabs(r[row * 3 + 1]) * half_h + std::fabs(r[row * 3 + 2]) * d;
    if (reach > camera.hi)
      report("camera", "ray directions reach " + fmt(reach) + " (rotation row " + std::to_string(row) +
                           " times viewport and projection distance), more than " + fmt(camera.hi) +
                           ", the range clrt renders in float32");
  }
}

namespace {

// The bytes of the mesh file `file` beneath the folder open at `root`, read
// once per distinct file (`parsed`, by device and inode): the byte limit
// counts every distinct file together (`bytes`), the triangle limit every
// mention (`room`: what the scene's limit leaves).
const ObjMesh& read_mesh(int root, const std::string& file, const std::string& shown, size_t room, size_t byte_limit,
                         size_t& bytes, std::map<std::pair<dev_t, ino_t>, ObjMesh>& parsed) {
  std::string why;
  const int fd = open_beneath(root, file, why);
  if (fd < 0) throw UserError(shown + ": cannot open mesh file: " + why);
  struct stat st {};
  if (::fstat(fd, &st) != 0) {
    ::close(fd);
    throw UserError(shown + ": cannot read mesh file: " + std::strerror(errno));
  }
  auto it = parsed.find({st.st_dev, st.st_ino});
  if (it != parsed.end()) {
    ::close(fd);
    return it->second;
  }
  if (S_ISREG(st.st_mode) && uint64_t(st.st_size) <= byte_limit && bytes + uint64_t(st.st_size) > byte_limit) {
    ::close(fd);
    throw UserError(shown + ": the scene's mesh files total more than " + bytes_text(byte_limit) +
                    " (the limit for one scene's meshes)");
  }
  std::string text = read_mesh_file(fd, shown, byte_limit - bytes);
  bytes += text.size();
  return parsed.emplace(std::make_pair(st.st_dev, st.st_ino), parse_obj_mesh(shown, std::move(text), room))
      .first->second;
}

}  // namespace

// The meshes' triangles, in the order of "meshes", after the inline
// "triangles". Each file is opened beneath the scene's folder, never
// through a link (util/open_beneath.hpp), and read and parsed once however
// often the scene names it: the triangle limit counts every mention, the
// byte limit (SceneLimits::mesh_bytes) every distinct file together.
void SceneBuilder::load_meshes() {
  if (meshes_.empty()) return;
  if (!folder_)
    return report(meshes_[0].where + ".file",
                  json_quoted(meshes_[0].file) +
                      ": a scene that is not read from a file (standard input, a pipe, a device, text) has no "
                      "folder to read mesh files from");
  const int root = ::open(folder_->c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (root < 0)
    return report(meshes_[0].where + ".file",
                  "cannot open the scene's folder " + folder_->string() + ": " + std::strerror(errno));
  struct CloseRoot {
    int fd;
    ~CloseRoot() { ::close(fd); }
  } close_root{root};
  std::map<std::pair<dev_t, ino_t>, ObjMesh> parsed;
  size_t bytes = 0;
  const size_t byte_limit = std::min(limits_.mesh_bytes, kMaxMeshBytes);
  for (const MeshSource& m : meshes_) {
    const std::string shown = (*folder_ / m.file).string();
    const Doing doing("reading the mesh file " + shown);
    const size_t room = limits_.triangles - std::min(limits_.triangles, scene_.triangles.size());
    std::vector<Triangle> faces;
    try {
      check_mesh_transform(shown, m.transform);
      const ObjMesh& mesh = read_mesh(root, m.file, shown, room, byte_limit, bytes, parsed);
      if (mesh.triangles() > room)
        throw UserError(shown + ": " + std::to_string(mesh.triangles()) + " triangles, more than the " +
                        std::to_string(room) + " the scene's limit of " + std::to_string(limits_.triangles) +
                        " leaves for this mesh");
      faces = place_obj_mesh(shown, mesh, m.transform, m.material);
    } catch (const UserError& e) {
      report(m.where + ".file", e.what());
      continue;
    }
    // The first mesh's faces become the scene's (no copy: a copy held both
    // at once, twice a large mesh's memory at the peak).
    if (scene_.triangles.empty())
      scene_.triangles = std::move(faces);
    else
      scene_.triangles.insert(scene_.triangles.end(), faces.begin(), faces.end());
  }
}

}  // namespace clrt
