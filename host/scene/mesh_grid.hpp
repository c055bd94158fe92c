// mesh_grid.hpp - mesh scenes of a given size for `clrt scaling --triangles`:
// a square grid of tori, each turned its own way, written as one OBJ file
// (the vertices already placed, as a large scanned mesh comes) and a scene
// that names it, above a reflective floor, lit by the book's three kinds of
// light. The same count gives the same files on every machine.
#pragma once
#include <cstddef>
#include <string>

namespace clrt {

// Most triangles a grid scene has: the scene parser's limit (obj_mesh.hpp).
constexpr size_t kMaxGridTriangles = 4000000;

struct MeshGrid {
  std::string obj;         // the OBJ text: every torus's vertices and faces
  std::string scene_json;  // the scene, naming the OBJ as `obj_name`
  size_t triangles = 0;    // at most the count asked for; from 2 000 on, at most 3% fewer
  size_t tori = 0;
};

// A grid of at most `triangles` triangles (in [1, kMaxGridTriangles]; at
// least 18: one torus of 3 x 3 quads).
MeshGrid torus_grid(size_t triangles, const std::string& obj_name);

}  // namespace clrt
