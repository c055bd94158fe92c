// wire.cpp - scenes and rows as bytes.
#include "dist/wire.hpp"

#include "util/error.hpp"

namespace clrt::dist {

const uint8_t* Reader::take(size_t n) {
  if (n > bytes_.size() - at_) fail();
  const uint8_t* p = bytes_.data() + at_;
  at_ += n;
  return p;
}

void Reader::fail() const {
  throw DeviceError("MPI: a malformed message between ranks (" + std::to_string(bytes_.size()) + " bytes)");
}

namespace {

void put_vec(Writer& w, const Vec3& v) {
  w.put(v.x), w.put(v.y), w.put(v.z);
}
Vec3 get_vec(Reader& r) {
  Vec3 v;
  v.x = r.get<double>(), v.y = r.get<double>(), v.z = r.get<double>();
  return v;
}
void put_material(Writer& w, const Material& m) {
  put_vec(w, m.color), w.put(m.specular), w.put(m.reflective);
}
Material get_material(Reader& r) {
  Material m;
  m.color = get_vec(r), m.specular = r.get<double>(), m.reflective = r.get<double>();
  return m;
}

// The least a sphere, light, plane and triangle take on the wire (counts
// are checked against the bytes left before anything is allocated).
constexpr size_t kSphereBytes = 12 * 8, kLightBytes = 4 + 4 * 8 + 4, kPlaneBytes = 11 * 8, kTriangleBytes = 14 * 8;

}  // namespace

Bytes encode_scene(const Scene& s) {
  Writer w;
  put_vec(w, s.camera.position);
  for (double v : s.camera.rotation) w.put(v);
  w.put(s.camera.viewport_w), w.put(s.camera.viewport_h), w.put(s.camera.projection_plane_d);
  w.put<uint8_t>(s.camera.aspect_from_image);
  put_vec(w, s.background);
  w.put<int32_t>(s.recursion_depth);
  w.put(s.epsilon);
  w.put<uint64_t>(s.spheres.size());
  for (const Sphere& p : s.spheres) {
    put_vec(w, p.center), w.put(p.radius), put_vec(w, p.color);
    w.put(p.specular), w.put(p.reflective), w.put(p.transparency), w.put(p.refractive_index);
  }
  w.put<uint64_t>(s.lights.size());
  for (const Light& l : s.lights)
    w.put<int32_t>(int32_t(l.type)), w.put(l.intensity), put_vec(w, l.vec), w.put<int32_t>(l.scale_exponent);
  w.put<uint64_t>(s.planes.size());
  for (const Plane& p : s.planes) put_vec(w, p.point), put_vec(w, p.normal), put_material(w, p.material);
  w.put<uint64_t>(s.triangles.size());
  for (const Triangle& t : s.triangles)
    put_vec(w, t.v0), put_vec(w, t.v1), put_vec(w, t.v2), put_material(w, t.material);
  return std::move(w.bytes);
}

Scene decode_scene(const Bytes& b) {
  Reader r(b);
  Scene s;
  s.camera.position = get_vec(r);
  for (double& v : s.camera.rotation) v = r.get<double>();
  s.camera.viewport_w = r.get<double>(), s.camera.viewport_h = r.get<double>();
  s.camera.projection_plane_d = r.get<double>();
  s.camera.aspect_from_image = r.get<uint8_t>() != 0;
  s.background = get_vec(r);
  s.recursion_depth = r.get<int32_t>();
  s.epsilon = r.get<double>();
  s.spheres.resize(r.get_count(kSphereBytes));
  for (Sphere& p : s.spheres) {
    p.center = get_vec(r), p.radius = r.get<double>(), p.color = get_vec(r);
    p.specular = r.get<double>(), p.reflective = r.get<double>(), p.transparency = r.get<double>();
    p.refractive_index = r.get<double>();
  }
  s.lights.resize(r.get_count(kLightBytes));
  for (Light& l : s.lights) {
    const int32_t type = r.get<int32_t>();
    if (type < 0 || type > int32_t(LightType::Directional)) throw DeviceError("MPI: a scene with a bad light type");
    l.type = LightType(type), l.intensity = r.get<double>(), l.vec = get_vec(r);
    l.scale_exponent = r.get<int32_t>();
    if (l.scale_exponent < -1100 || l.scale_exponent > 1100) throw DeviceError("MPI: a scene with a bad light scale");
  }
  s.planes.resize(r.get_count(kPlaneBytes));
  for (Plane& p : s.planes) p.point = get_vec(r), p.normal = get_vec(r), p.material = get_material(r);
  s.triangles.resize(r.get_count(kTriangleBytes));
  for (Triangle& t : s.triangles) t.v0 = get_vec(r), t.v1 = get_vec(r), t.v2 = get_vec(r), t.material = get_material(r);
  if (!r.done()) throw DeviceError("MPI: a scene message with bytes left over");
  return s;
}

size_t row_pixel_bytes(const FrameContents& c) {
  const size_t colour = c.pixels == PixelFormat::Float  ? 3 * sizeof(double)
                        : c.pixels == PixelFormat::Unit ? 3 * sizeof(float)
                                                        : 4;
  return colour + (c.classes ? 2 * sizeof(int32_t) : 0);
}

std::vector<Span> row_pieces(Image& img, int y0, int y1) {
  const size_t first = size_t(y0) * img.width, count = size_t(y1 - y0) * img.width;
  std::vector<Span> pieces;
  if (img.contents.pixels == PixelFormat::Float)
    pieces.push_back({img.rgb.data() + first * 3, count * 3 * sizeof(double)});
  else if (img.contents.pixels == PixelFormat::Unit)
    pieces.push_back({img.unit.data() + first * 3, count * 3 * sizeof(float)});
  else
    pieces.push_back({img.rgba8.data() + first * 4, count * 4});
  if (img.contents.classes) {
    pieces.push_back({img.hit.data() + first, count * sizeof(int32_t)});
    pieces.push_back({img.shadowed.data() + first, count * sizeof(int32_t)});
  }
  return pieces;
}

Bytes encode_rows(const Image& img, int y0, int y1) {
  Writer w;
  w.put<int32_t>(y0), w.put<int32_t>(y1);
  // The pieces are only read here (row_pieces() serves receives too).
  for (const Span& p : row_pieces(const_cast<Image&>(img), y0, y1)) w.put_raw(p.data, p.bytes);
  return std::move(w.bytes);
}

void decode_rows(const Bytes& b, Image& img, int& y0, int& y1) {
  Reader r(b);
  y0 = r.get<int32_t>(), y1 = r.get<int32_t>();
  if (y0 < 0 || y1 < y0 || y1 > img.height) throw DeviceError("MPI: rows out of the frame in a message");
  for (const Span& p : row_pieces(img, y0, y1)) r.get_raw(p.data, p.bytes);
  if (!r.done()) throw DeviceError("MPI: a rows message with bytes left over");
}

}  // namespace clrt::dist
