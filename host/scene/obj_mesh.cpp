// obj_mesh.cpp - load_obj_mesh: reads an untrusted OBJ file once, checks
// every vertex and face line itself, then lets tinyobjloader triangulate
// the faces from memory (so it never opens a file of its own).
//
// Why a scan of our own before tinyobjloader: its number parser turns what
// it cannot read ("nan", "abc") into 0 without a word, it skips faces with
// bad indices with only a warning, its `t` (tag) lines allocate up to 8192
// values each, and it resolves relative indices without range checks. The
// scan parses the coordinates (std::from_chars: locale-independent and
// correctly rounded; these are the values used), checks and counts the
// faces, and comments out every line other than v, vn, vt and f before the
// text reaches tinyobjloader.
//
// Most large meshes are triangles given by vertex index alone ("f 1 2 3"):
// there is nothing to triangulate, and the scan keeps those faces itself
// (tinyobjloader would emit each as given, in file order: the same mesh).
// tinyobjloader is then not called: it stored every corner and vertex again
// (measured: most of the load time and memory of a 4 million triangle
// file, docs/results/meshes.md). A file with a polygon or a face corner
// with texture or normal indices ("1/2/3") takes the tinyobjloader path.
#include "scene/obj_mesh.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <tiny_obj_loader.h>
#include <unistd.h>

#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <sstream>
#include <type_traits>

#include "util/bytes_text.hpp"
#include "util/error.hpp"

// Debian builds libtinyobjloader_double with real_t = double; the header
// must agree (CMakeLists.txt defines TINYOBJLOADER_USE_DOUBLE for it).
static_assert(std::is_same<tinyobj::real_t, double>::value,
              "compile with TINYOBJLOADER_USE_DOUBLE and link libtinyobjloader_double");

namespace clrt {
namespace {

[[noreturn]] void fail(const std::string& path, const std::string& what) {
  throw UserError(path + ": " + what);
}

std::string num(double v) {
  std::ostringstream os;
  os << v;
  return os.str();
}

// A token from the file for a one-line message: printable ASCII only, cut.
std::string quoted(const char* b, const char* e) {
  constexpr size_t kMaxEcho = 32;
  std::string s = "'";
  for (const char* p = b; p < e && size_t(p - b) < kMaxEcho; ++p) s += (*p >= 0x20 && *p < 0x7f) ? *p : '?';
  if (size_t(e - b) > kMaxEcho) s += "...";
  return s + "'";
}

struct Fd {
  int fd;
  ~Fd() {
    if (fd >= 0) ::close(fd);
  }
};

}  // namespace

std::string read_mesh_file(int fd, const std::string& path, size_t max_bytes) {
  Fd f{fd};
  struct stat st {};
  if (::fstat(f.fd, &st) != 0) fail(path, std::string("cannot read mesh file: ") + std::strerror(errno));
  if (S_ISDIR(st.st_mode)) fail(path, "cannot open mesh file: is a directory");
  if (!S_ISREG(st.st_mode)) fail(path, "cannot open mesh file: not a regular file");
  if (st.st_size < 0 || uint64_t(st.st_size) > max_bytes)
    fail(path, "mesh file is larger than " + bytes_text(max_bytes));
  std::string text;
  text.reserve(size_t(st.st_size));
  char buf[1 << 16];
  for (;;) {  // at most max_bytes + 1 bytes: the file may grow while it is read
    const size_t room = max_bytes - text.size();
    const ssize_t n = ::read(f.fd, buf, room < sizeof buf ? room + 1 : sizeof buf);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) fail(path, std::string("cannot read mesh file: ") + std::strerror(errno));
    if (n == 0) break;
    if (size_t(n) > room) fail(path, "mesh file is larger than " + bytes_text(max_bytes));
    text.append(buf, size_t(n));
  }
  return text;
}

namespace {

// sin and cos of an angle in degrees, exact at multiples of 90.
void sincos_degrees(double degrees, double* s, double* c) {
  double r = std::fmod(degrees, 360.0);
  if (r < 0) r += 360.0;
  if (r == 0 || r == 360) {
    *s = 0, *c = 1;
  } else if (r == 90) {
    *s = 1, *c = 0;
  } else if (r == 180) {
    *s = 0, *c = -1;
  } else if (r == 270) {
    *s = -1, *c = 0;
  } else {
    constexpr double kPi = 3.14159265358979323846;
    const double a = r * (kPi / 180.0);
    *s = std::sin(a), *c = std::cos(a);
  }
}

// v' = translate + Rz Ry Rx (scale v).
struct Placement {
  double scale;
  Vec3 translate;
  double sx, cx, sy, cy, sz, cz;

  Placement(const std::string& path, const MeshTransform& t) : scale(t.scale), translate(t.translate) {
    if (!std::isfinite(t.scale) || t.scale <= 0)
      fail(path, "mesh transform: scale must be finite and > 0 (got " + num(t.scale) + ")");
    const Vec3& r = t.rotate_degrees;
    if (!std::isfinite(r.x) || !std::isfinite(r.y) || !std::isfinite(r.z))
      fail(path, "mesh transform: rotation angles must be finite");
    for (double v : {t.translate.x, t.translate.y, t.translate.z})
      if (!(std::fabs(v) <= kMaxLength))
        fail(path, "mesh transform: translate " + num(v) + " is outside ±" + num(kMaxLength));
    sincos_degrees(r.x, &sx, &cx);
    sincos_degrees(r.y, &sy, &cy);
    sincos_degrees(r.z, &sz, &cz);
  }

  Vec3 apply(Vec3 p) const {
    p = scale * p;
    p = {p.x, cx * p.y - sx * p.z, sx * p.y + cx * p.z};   // Rx
    p = {cy * p.x + sy * p.z, p.y, -sy * p.x + cy * p.z};  // Ry
    p = {cz * p.x - sz * p.y, sz * p.x + cz * p.y, p.z};   // Rz
    return translate + p;
  }
};

bool is_space(char c) {
  return c == ' ' || c == '\t';
}

// The next token of [*p, e) separated by spaces/tabs, or false at the end.
bool next_token(const char** p, const char* e, const char** tb, const char** te) {
  while (*p < e && is_space(**p)) ++*p;
  if (*p == e) return false;
  *tb = *p;
  while (*p < e && !is_space(**p)) ++*p;
  *te = *p;
  return true;
}

struct Scan {
  std::vector<Vec3> vertices;   // as in the file
  std::vector<uint32_t> lines;  // each vertex's line
  size_t faces = 0, triangles = 0;
  long long max_index = 0;  // the largest positive (1-based) face index, and its line
  size_t max_index_line = 0;
  // While every face so far is a triangle of plain vertex indices: its
  // corners (0-based, relative indices resolved; positive ones checked at
  // the end against max_index); emptied at the first other face.
  bool plain_triangles = true;
  std::vector<uint32_t> corners;
};

// Checks and reads the v and f lines (see the top of the file) and turns
// every other line except vn and vt into a comment, in place.
Scan scan(const std::string& path, std::string& text, size_t max_triangles) {
  Scan out;
  const size_t nul = text.find('\0');
  if (nul != std::string::npos) fail(path, "not a text file (NUL byte at offset " + std::to_string(nul) + ")");
  char* const base = &text[0];
  const char* const end = base + text.size();
  size_t line = 0;
  for (char* b = base; b < end;) {
    char* e = b;
    while (e < end && *e != '\n' && *e != '\r') ++e;  // lines end as tinyobjloader ends them: \n, \r or \r\n
    char* const next = e < end && *e == '\r' && e + 1 < end && e[1] == '\n' ? e + 2 : e + 1;
    ++line;
    auto at = [line] { return "line " + std::to_string(line) + ": "; };
    char* p = b;
    while (p < e && is_space(*p)) ++p;
    const char* q = p + 1;
    const char *tb, *te;
    if (p + 1 < e && (p[0] == 'v' || p[0] == 'f') && is_space(p[1])) {
      // A comment after the values ("f 1 2 3 # top"): blanked for tinyobjloader.
      for (char* c = p + 2; c < e; ++c)
        if (*c == '#' && is_space(c[-1])) {
          std::memset(c, ' ', size_t(e - c));
          break;
        }
    }
    if (p + 1 < e && p[0] == 'v' && is_space(p[1])) {
      double xyz[3];
      for (double& v : xyz) {
        if (!next_token(&q, e, &tb, &te)) fail(path, at() + "a vertex needs 3 coordinates");
        const char* nb = tb;
        if (nb + 1 < te && *nb == '+' && nb[1] != '-' && nb[1] != '+') ++nb;
        const auto r = std::from_chars(nb, te, v);
        if (r.ec == std::errc::result_out_of_range && r.ptr == te) {
          // Underflow (1e-400) reads as 0; overflow is out of range.
          const std::string t(tb, te);
          if (t.find("e-") == std::string::npos && t.find("E-") == std::string::npos)
            fail(path, at() + "vertex coordinate " + quoted(tb, te) + " is out of range");
          v = 0;
        } else if (r.ec != std::errc() || r.ptr != te) {
          fail(path, at() + "malformed vertex coordinate " + quoted(tb, te));
        }
        if (!std::isfinite(v)) fail(path, at() + "non-finite vertex coordinate " + quoted(tb, te));
      }
      if (line > std::numeric_limits<uint32_t>::max()) fail(path, at() + "too many lines");
      out.vertices.push_back({xyz[0], xyz[1], xyz[2]});
      out.lines.push_back(uint32_t(line));
    } else if (p + 1 < e && p[0] == 'f' && is_space(p[1])) {
      size_t n = 0;
      uint32_t corner[3];
      bool plain = true;
      while (next_token(&q, e, &tb, &te)) {
        const char* ie = static_cast<const char*>(std::memchr(tb, '/', size_t(te - tb)));
        if (ie) plain = false;
        if (!ie) ie = te;
        const char* nb = tb;
        if (nb + 1 < ie && *nb == '+' && nb[1] != '-' && nb[1] != '+') ++nb;
        long long idx = 0;
        const auto r = std::from_chars(nb, ie, idx);
        if (r.ec == std::errc::result_out_of_range ||
            (r.ec == std::errc() && r.ptr == ie &&
             (idx > std::numeric_limits<int>::max() || idx < -std::numeric_limits<int>::max())))
          fail(path, at() + "face index " + quoted(tb, ie) + " is out of range");
        if (r.ec != std::errc() || r.ptr != ie || idx == 0)
          fail(path, at() + "malformed face vertex " + quoted(tb, te));
        if (idx < 0 && -idx > static_cast<long long>(out.vertices.size()))
          fail(path, at() + "face index " + std::to_string(idx) + " is out of range (vertex count before this line: " +
                         std::to_string(out.vertices.size()) + ")");
        if (idx > out.max_index) out.max_index = idx, out.max_index_line = line;
        if (n < 3) corner[n] = uint32_t(idx > 0 ? idx - 1 : static_cast<long long>(out.vertices.size()) + idx);
        if (++n > kMaxFaceVertices)
          fail(path, at() + "a face has more than " + std::to_string(kMaxFaceVertices) + " vertices");
      }
      if (n < 3) fail(path, at() + "a face needs at least 3 vertices (has " + std::to_string(n) + ")");
      if (out.plain_triangles && (!plain || n != 3)) {
        out.plain_triangles = false;
        out.corners = std::vector<uint32_t>();
      }
      if (out.plain_triangles) out.corners.insert(out.corners.end(), corner, corner + 3);
      ++out.faces;
      out.triangles += n - 2;
      if (out.triangles > max_triangles)
        fail(path,
             "more than " + std::to_string(max_triangles) + " triangles (what the scene's limit leaves for this mesh)");
    } else if (p + 2 < e && p[0] == 'v' && (p[1] == 'n' || p[1] == 't') && is_space(p[2])) {
      // normals and texture coordinates: left to tinyobjloader (faces may refer to them), unused
    } else if (p < e) {
      *p = '#';  // mtllib, usemtl, g, o, s, l, p, t, vw, ...: ignored
    }
    b = next;
  }
  if (out.faces == 0) fail(path, "no faces (an OBJ mesh needs at least one `f` line)");
  if (out.max_index > static_cast<long long>(out.vertices.size()))
    fail(path, "line " + std::to_string(out.max_index_line) + ": face index " + std::to_string(out.max_index) +
                   " is out of range (vertex count: " + std::to_string(out.vertices.size()) + ")");
  return out;
}

std::string first_line(const std::string& s) {
  std::string l = s.substr(0, s.find('\n'));
  while (!l.empty() && (l.back() == '\r' || l.back() == ' ' || l.back() == '.')) l.pop_back();
  return l.empty() ? "unknown error" : l;
}

}  // namespace

ObjMesh parse_obj_mesh(const std::string& path, std::string text, size_t max_triangles) {
  Scan s = scan(path, text, max_triangles);
  ObjMesh out;
  if (s.plain_triangles) {  // nothing to triangulate: the scan's faces (see the top of the file)
    out.faces = std::move(s.corners);
    out.vertices = std::move(s.vertices);
    out.lines = std::move(s.lines);
    return out;
  }

  tinyobj::ObjReaderConfig config;
  config.triangulate = true;
  config.vertex_color = false;
  tinyobj::ObjReader reader;
  // From memory with an empty material text: `mtllib` opens nothing (and
  // the scan has commented it out anyway).
  if (!reader.ParseFromString(text, "", config) || !reader.Error().empty())
    fail(path, "malformed OBJ: " + first_line(reader.Error()));
  text = std::string();  // free it before the triangles are made
  for (const char* lost : {"Degenerated face", "invalid vertex index", "Vertex indices out of bounds"})
    if (reader.Warning().find(lost) != std::string::npos) fail(path, "malformed OBJ: " + first_line(reader.Warning()));
  if (reader.GetAttrib().vertices.size() != 3 * s.vertices.size())
    fail(path, "unsupported OBJ syntax (tinyobjloader read " + std::to_string(reader.GetAttrib().vertices.size() / 3) +
                   " vertices, not " + std::to_string(s.vertices.size()) + ")");

  out.faces.reserve(3 * s.triangles);
  for (const tinyobj::shape_t& shape : reader.GetShapes()) {
    const auto& idx = shape.mesh.indices;
    if (idx.size() % 3 != 0) fail(path, "malformed OBJ: a face was not triangulated");
    for (const tinyobj::index_t& corner : idx) {
      const int vi = corner.vertex_index;
      if (vi < 0 || size_t(vi) >= s.vertices.size()) fail(path, "face index out of range");
      out.faces.push_back(uint32_t(vi));
    }
  }
  if (out.faces.size() != 3 * s.triangles)
    fail(path,
         "a polygon could not be triangulated (self-intersecting or degenerate?): " + std::to_string(s.triangles) +
             " triangles expected, tinyobjloader made " + std::to_string(out.faces.size() / 3));
  out.vertices = std::move(s.vertices);
  out.lines = std::move(s.lines);
  return out;
}

void check_mesh_transform(const std::string& path, const MeshTransform& transform) {
  (void)Placement(path, transform);
}

std::vector<Triangle> place_obj_mesh(const std::string& path, const ObjMesh& mesh, const MeshTransform& transform,
                                     const Material& material) {
  const Placement place(path, transform);
  std::vector<Triangle> out;
  out.reserve(mesh.triangles());
  // Only the vertices faces use: each mention of a file costs its triangles,
  // not its vertex count.
  auto placed = [&](uint32_t vi) {
    const Vec3 v = mesh.vertices[vi], w = place.apply(v);
    for (double c : {w.x, w.y, w.z})
      if (!(std::fabs(c) <= kMaxLength))
        fail(path, "line " + std::to_string(mesh.lines[vi]) + ": vertex (" + num(v.x) + ", " + num(v.y) + ", " +
                       num(v.z) + ") lies outside ±" + num(kMaxLength) + " once transformed (coordinate " + num(c) +
                       ")");
    return w;
  };
  for (size_t i = 0; i + 2 < mesh.faces.size(); i += 3)
    out.push_back(Triangle{placed(mesh.faces[i]), placed(mesh.faces[i + 1]), placed(mesh.faces[i + 2]), material});
  return out;
}

std::vector<Triangle> load_obj_mesh(const std::string& path, const MeshTransform& transform, const Material& material,
                                    size_t max_triangles, size_t max_bytes) {
  check_mesh_transform(path, transform);
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NOCTTY | O_NONBLOCK);
  if (fd < 0) fail(path, std::string("cannot open mesh file: ") + std::strerror(errno));
  return place_obj_mesh(path, parse_obj_mesh(path, read_mesh_file(fd, path, max_bytes), max_triangles), transform,
                        material);
}

}  // namespace clrt
