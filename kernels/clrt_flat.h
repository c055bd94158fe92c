/* clrt_flat.h - chapter 5's flat primitives: infinite planes and triangles
 * (inline or from OBJ meshes) and their ray tests, one primitive at a time.
 *
 * A ray leaving a flat primitive cannot meet it again, so the queries skip
 * its own id (`self`) outright (clrt_query_all.h, clrt_bvh.h); spheres keep
 * their self roots (clrt_sphere.h). */
#ifndef CLRT_FLAT_H
#define CLRT_FLAT_H

#include "clrt_scene.h"

/* Distance along D to plane `p` (dot(n, P0 - O) / dot(n, D)), per lane;
 * infinity for a ray parallel to it. */
CLRT_INLINE lreal plane_distance(const vec3* O, const vec3* D, __global const clrt_plane* p) {
  const vec3 n = VEC3_FROM_HI_LO(p->normal, p->normal_lo);
  const vec3 point = VEC3_FROM_HI_LO(p->point, p->point_lo);
  const lreal along = vdot(n, *D);
  const lreal t = vdot(n, vsub(point, *O)) / along;
  return along == 0 ? (lreal)REAL_INFINITY : t;
}

#if CLRT_HAS_TRIANGLES
/* ---- watertight ray-triangle test ----------------------------------------
 * Woop, Benthin and Wald, "Watertight Ray/Triangle Intersection" (JCGT
 * 2013): the vertices are moved into the ray's frame (the ray along +z from
 * the origin, by a shear along its dominant axis kz), and the three 2-D edge
 * functions U, V, W of the sheared vertices decide the hit by their signs. A
 * shared edge is the same two sheared vertices in both triangles and its
 * edge function is the same difference of products with the operands
 * swapped, which rounds to exactly the negated value: so a ray on the edge
 * is inside at least one of the two triangles, never in neither (no rays
 * leak between faces). That needs the products rounded one by one: FMA
 * contraction (allowed by default in OpenCL C) would break the symmetry, so
 * it is off in these functions. Zero edge functions count as inside (a ray
 * through an edge or a vertex hits all faces there, at the same distance);
 * the paper's double-precision recomputation of zero edge functions is not
 * done (fp64 is optional in OpenCL): it only refines which of those faces
 * is reported. */
typedef struct {
  lint kx, ky, kz; /* axis permutation per lane: kz the largest |D| component */
  lreal sx, sy, sz;
} ray_shear;

/* Component k (0 x, 1 y, 2 z) of (x, y, z): per lane, or one k for all. */
#define PICK_AXIS(x, y, z, k) ((k) == 0 ? (x) : ((k) == 1 ? (y) : (z)))

CLRT_INLINE lreal pick_axis(const vec3 v, const lint k) {
  return PICK_AXIS(v.x, v.y, v.z, k);
}

CLRT_INLINE ray_shear shear_of(const vec3* Dp) {
#pragma OPENCL FP_CONTRACT OFF
  const vec3 D = *Dp;
  const lreal ax = fabs(D.x), ay = fabs(D.y), az = fabs(D.z);
  ray_shear s;
  s.kz = (ax > ay) ? ((ax > az) ? (lint)0 : (lint)2) : ((ay > az) ? (lint)1 : (lint)2);
  const lint kx = s.kz == (lint)2 ? (lint)0 : s.kz + (lint)1;
  const lint ky = kx == (lint)2 ? (lint)0 : kx + (lint)1;
  const lreal dz = pick_axis(D, s.kz);
  /* a negative dz mirrors the frame: swapping x and y keeps the winding */
  const lint mirror = dz < 0;
  s.kx = mirror ? ky : kx;
  s.ky = mirror ? kx : ky;
  s.sx = pick_axis(D, s.kx) / dz;
  s.sy = pick_axis(D, s.ky) / dz;
  s.sz = 1 / dz;
  return s;
}

/* The test itself, from the vertices minus the ray origin (A, B, C, by
 * component) and the ray's shear (axes kx, ky, kz, factors sx, sy, sz):
 * declares `t`, the distance (infinity on a miss), of type T with masks of
 * type M. A macro, so that the two tests that take it - one triangle
 * against each lane's ray (triangle_distance()) and one ray against a
 * triangle in each lane (clrt_leaf_alone.h) - do the same operations in the
 * same order and round alike. Its user turns FMA contraction off. */
#define WATERTIGHT_DISTANCE(T, M, Ax, Ay, Az, Bx, By, Bz, Cx, Cy, Cz, kx, ky, kz, sx, sy, sz, t)                \
  const T a_z_ = PICK_AXIS(Ax, Ay, Az, kz), b_z_ = PICK_AXIS(Bx, By, Bz, kz), c_z_ = PICK_AXIS(Cx, Cy, Cz, kz); \
  const T a_x_ = PICK_AXIS(Ax, Ay, Az, kx) - (sx)*a_z_, a_y_ = PICK_AXIS(Ax, Ay, Az, ky) - (sy)*a_z_;           \
  const T b_x_ = PICK_AXIS(Bx, By, Bz, kx) - (sx)*b_z_, b_y_ = PICK_AXIS(Bx, By, Bz, ky) - (sy)*b_z_;           \
  const T c_x_ = PICK_AXIS(Cx, Cy, Cz, kx) - (sx)*c_z_, c_y_ = PICK_AXIS(Cx, Cy, Cz, ky) - (sy)*c_z_;           \
  const T u_ = c_x_ * b_y_ - c_y_ * b_x_;                                                                       \
  const T v_ = a_x_ * c_y_ - a_y_ * c_x_;                                                                       \
  const T w_ = b_x_ * a_y_ - b_y_ * a_x_;                                                                       \
  const M outside_ = ((u_ < 0) | (v_ < 0) | (w_ < 0)) & ((u_ > 0) | (v_ > 0) | (w_ > 0));                       \
  const T det_ = u_ + v_ + w_;                                                                                  \
  const T hit_ = (u_ * ((sz)*a_z_) + v_ * ((sz)*b_z_) + w_ * ((sz)*c_z_)) / det_;                               \
  const T t = (outside_ | (det_ == 0)) ? (T)REAL_INFINITY : hit_

/* Distance along D to triangle `tri` per lane; infinity on a miss. */
CLRT_INLINE lreal triangle_distance(const vec3* O, const ray_shear* s, __global const clrt_triangle* tri,
                                    __global const clrt_triangle_lo* lo) {
#pragma OPENCL FP_CONTRACT OFF
  const vec3 A = vsub(VEC3_FROM_HI_LO(tri->v0, lo->v0_lo), *O);
  const vec3 B = vsub(VEC3_FROM_HI_LO(tri->v1, lo->v1_lo), *O);
  const vec3 C = vsub(VEC3_FROM_HI_LO(tri->v2, lo->v2_lo), *O);
  WATERTIGHT_DISTANCE(lreal, lint, A.x, A.y, A.z, B.x, B.y, B.z, C.x, C.y, C.z, s->kx, s->ky, s->kz, s->sx, s->sy,
                      s->sz, t);
  return t;
}
#endif

#endif /* CLRT_FLAT_H */
