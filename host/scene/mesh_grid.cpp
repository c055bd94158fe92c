// mesh_grid.cpp - see mesh_grid.hpp.
#include "scene/mesh_grid.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>

namespace clrt {

namespace {

// Triangles per torus at most: 20 000 (a tessellated model's size).
constexpr size_t kTorusTriangles = 20000;
constexpr double kPi = 3.14159265358979323846;
// Major and minor radius, and the grid's cell size.
constexpr double kMajor = 1, kMinor = 0.35, kCell = 3;

void append_number(std::string& out, double v) {
  char text[32];
  const auto end = std::to_chars(text, text + sizeof text, v, std::chars_format::general, 6).ptr;
  out.append(text, end);
}

void append_index(std::string& out, size_t v) {
  char text[24];
  const auto end = std::to_chars(text, text + sizeof text, v).ptr;
  out.append(text, end);
}

// One torus of ring x tube quads (two triangles each), turned by the
// angles (about x, then y) and moved to `centre`; vertex indices from
// `first` (1-based, OBJ's).
void append_torus(std::string& obj, size_t ring, size_t tube, double turn_x, double turn_y, const double centre[3],
                  size_t first) {
  const double cx = std::cos(turn_x), sx = std::sin(turn_x), cy = std::cos(turn_y), sy = std::sin(turn_y);
  for (size_t i = 0; i < ring; ++i) {
    const double u = 2 * kPi * double(i) / double(ring);
    for (size_t j = 0; j < tube; ++j) {
      const double v = 2 * kPi * double(j) / double(tube);
      const double x0 = (kMajor + kMinor * std::cos(v)) * std::cos(u);
      const double y0 = (kMajor + kMinor * std::cos(v)) * std::sin(u);
      const double z0 = kMinor * std::sin(v);
      const double y1 = cx * y0 - sx * z0, z1 = sx * y0 + cx * z0;   // about x
      const double x2 = cy * x0 + sy * z1, z2 = -sy * x0 + cy * z1;  // about y
      obj += "v ";
      append_number(obj, centre[0] + x2);
      obj += ' ';
      append_number(obj, centre[1] + y1);
      obj += ' ';
      append_number(obj, centre[2] + z2);
      obj += '\n';
    }
  }
  const auto at = [&](size_t i, size_t j) { return first + (i % ring) * tube + (j % tube); };
  for (size_t i = 0; i < ring; ++i)
    for (size_t j = 0; j < tube; ++j) {
      const size_t c[4] = {at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)};
      for (const size_t* f : {c + 1, c + 2}) {  // faces (c0 c1 c2) and (c0 c2 c3)
        obj += "f ";
        append_index(obj, c[0]);
        obj += ' ';
        append_index(obj, f[0]);
        obj += ' ';
        append_index(obj, f[1]);
        obj += '\n';
      }
    }
}

}  // namespace

MeshGrid torus_grid(size_t triangles, const std::string& obj_name) {
  triangles = std::clamp<size_t>(triangles, 18, kMaxGridTriangles);
  MeshGrid grid;
  grid.tori = (triangles + kTorusTriangles - 1) / kTorusTriangles;
  // Each torus: tube x ring quads, the ring about twice the tube.
  const size_t each = triangles / grid.tori;
  const size_t tube = std::max<size_t>(3, size_t(std::sqrt(double(each) / 4)));
  const size_t ring = std::max<size_t>(3, each / (2 * tube));
  const size_t side = size_t(std::ceil(std::sqrt(double(grid.tori))));
  grid.obj.reserve(grid.tori * ring * tube * 64);
  for (size_t k = 0; k < grid.tori; ++k) {
    const double centre[3] = {(double(k % side) - (double(side) - 1) / 2) * kCell,
                              ((double(side) - 1) / 2 - double(k / side)) * kCell, 0};
    append_torus(grid.obj, ring, tube, 0.7 + 0.37 * double(k), 0.3 + 0.23 * double(k), centre, 1 + k * ring * tube);
  }
  grid.triangles = grid.tori * ring * tube * 2;
  // The camera sees the whole grid (viewport 1 at distance 1: half the
  // distance either side), the floor below it reflects the tori.
  const double half = double(side) * kCell / 2;
  char json[1024];
  std::snprintf(
      json, sizeof json,
      "{\"camera\": {\"position\": [0, 0, %.6g]},\n"
      " \"background\": [25, 35, 60], \"recursion_depth\": 3,\n"
      " \"planes\": [{\"point\": [0, %.6g, 0], \"normal\": [0, 1, 0], \"color\": [220, 210, 180], "
      "\"specular\": 1000, \"reflective\": 0.25}],\n"
      " \"meshes\": [{\"file\": \"%s\", \"color\": [60, 160, 255], \"specular\": 300, \"reflective\": 0.3}],\n"
      " \"lights\": [{\"type\": \"ambient\", \"intensity\": 0.2},\n"
      "  {\"type\": \"point\", \"intensity\": 0.6, \"position\": [%.6g, %.6g, %.6g]},\n"
      "  {\"type\": \"directional\", \"intensity\": 0.2, \"direction\": [1, 4, -4]}]}\n",
      -(2 * half + 2), -(half + 0.5), obj_name.c_str(), half, half, -half);
  grid.scene_json = json;
  return grid;
}

}  // namespace clrt
