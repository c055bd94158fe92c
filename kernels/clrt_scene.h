/* clrt_scene.h - the scene's buffers as one struct, which every query and
 * shading function takes, and the one id space over all primitives
 * (clrt_layout.h): spheres 0..S-1, planes S..S+P-1, triangles S+P... */
#ifndef CLRT_SCENE_H
#define CLRT_SCENE_H

#include "clrt_math.h"

/* The buffers of the scene, in one place. */
typedef struct scene_data {
  __global const clrt_params* params;
  __global const clrt_sphere* spheres;
  __global const clrt_light* lights;
  __global const clrt_wide_node* nodes;
  __global const int* primitives;
  __global const clrt_leaf_sphere* leaf_spheres;
  __global const clrt_plane* planes;
  __global const clrt_triangle* triangles;
  __global const clrt_triangle_lo* triangles_lo;
  __global const int* triangle_slots;
  __global const clrt_material* materials;
} scene_data;

/* Counts of the flat primitives: constants 0 where the build leaves a kind
 * out (CLRT_HAS_PLANES / CLRT_HAS_TRIANGLES 0), so their loops vanish. */
#if CLRT_HAS_PLANES
#define CLRT_PLANE_COUNT(params) ((params)->n_planes)
#else
#define CLRT_PLANE_COUNT(params) 0
#endif
#if CLRT_HAS_TRIANGLES
#define CLRT_TRIANGLE_COUNT(params) ((params)->n_triangles)
#else
#define CLRT_TRIANGLE_COUNT(params) 0
#endif
/* The place of the triangle with index i in the scene's list among the
 * triangle records: in the hierarchy's order where the kernel walks one
 * (clrt_layout.h). */
#ifdef CLRT_BVH
#define TRIANGLE_SLOT(scene, i) ((scene)->triangle_slots[i])
#else
#define TRIANGLE_SLOT(scene, i) (i)
#endif
/* The lo parts of the triangle record at `slot`, where the variant reads
 * them (CLRT_READS_TRIANGLE_LO); elsewhere a null that is never read: the
 * variants without them are float ones, whose VEC3_FROM_HI_LO drops lo. */
#if CLRT_READS_TRIANGLE_LO(CLRT_PRECISION)
#define TRIANGLE_LO(scene, slot) (&(scene)->triangles_lo[slot])
#else
#define TRIANGLE_LO(scene, slot) ((__global const clrt_triangle_lo*)0)
#endif
/* The first id of each flat kind. */
#define PLANE_ID0(params) CLRT_SPHERE_COUNT(params)
#define TRIANGLE_ID0(params) (CLRT_SPHERE_COUNT(params) + CLRT_PLANE_COUNT(params))

#endif /* CLRT_SCENE_H */
