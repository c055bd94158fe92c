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

CLRT_INLINE lreal pick_axis(const vec3 v, const lint k) {
  return k == (lint)0 ? v.x : (k == (lint)1 ? v.y : v.z);
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

/* Distance along D to triangle `tri` per lane; infinity on a miss. */
CLRT_INLINE lreal triangle_distance(const vec3* O, const ray_shear* s, __global const clrt_triangle* tri,
                                    __global const clrt_triangle_lo* lo) {
#pragma OPENCL FP_CONTRACT OFF
  const vec3 A = vsub(VEC3_FROM_HI_LO(tri->v0, lo->v0_lo), *O);
  const vec3 B = vsub(VEC3_FROM_HI_LO(tri->v1, lo->v1_lo), *O);
  const vec3 C = vsub(VEC3_FROM_HI_LO(tri->v2, lo->v2_lo), *O);
  const lreal a_z = pick_axis(A, s->kz), b_z = pick_axis(B, s->kz), c_z = pick_axis(C, s->kz);
  const lreal a_x = pick_axis(A, s->kx) - s->sx * a_z, a_y = pick_axis(A, s->ky) - s->sy * a_z;
  const lreal b_x = pick_axis(B, s->kx) - s->sx * b_z, b_y = pick_axis(B, s->ky) - s->sy * b_z;
  const lreal c_x = pick_axis(C, s->kx) - s->sx * c_z, c_y = pick_axis(C, s->ky) - s->sy * c_z;
  const lreal u = c_x * b_y - c_y * b_x;
  const lreal v = a_x * c_y - a_y * c_x;
  const lreal w = b_x * a_y - b_y * a_x;
  const lint outside = ((u < 0) | (v < 0) | (w < 0)) & ((u > 0) | (v > 0) | (w > 0));
  const lreal det = u + v + w;
  const lreal t = (u * (s->sz * a_z) + v * (s->sz * b_z) + w * (s->sz * c_z)) / det;
  return (outside | (det == 0)) ? (lreal)REAL_INFINITY : t;
}
#endif

#endif /* CLRT_FLAT_H */
