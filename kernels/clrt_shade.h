/* clrt_shade.h - shading at a hit point: the hit sphere's material, the
 * book's ComputeLighting with its shadow rays, and the reflection of a ray. */
#ifndef CLRT_SHADE_H
#define CLRT_SHADE_H

#include "clrt_intersect.h"

/* 2 (N.R) N - R */
#define reflect_ray(R, N) vsub(vscale(2 * vdot((N), (R)), (N)), (R))

/* Light types: a specialized build knows each light's type (CLRT_LIGHT_TYPES,
 * e.g. "0,1,2"), so the type tests of the light loop fold away. */
#if defined(CLRT_SPECIALIZED) && defined(CLRT_LIGHT_TYPES) && CLRT_N_LIGHTS > 0
__constant int clrt_light_types[CLRT_N_LIGHTS] = {CLRT_LIGHT_TYPES};
#define LIGHT_TYPE(index, light) (clrt_light_types[index])
#else
#define LIGHT_TYPE(index, light) ((light)->type)
#endif

/* The hit sphere's centre, colour, specular exponent and reflectivity, per
 * lane (`hit` is each lane's sphere index, -1 for none: zeros). Lanes may
 * hit different spheres. Testing every sphere, each one is read (a uniform
 * load) and selected per lane: few spheres, no gathers. With the hierarchy
 * that loop would cost as much as testing every sphere, so each distinct
 * index among the lanes is read once (one pass per sphere the lanes hit,
 * at most CLRT_LANES). */
CLRT_INLINE void hit_material(lint hit, __global const clrt_params* params, __global const clrt_sphere* spheres,
                              vec3* center_out, vec3* color_out, lreal* specular_out, lreal* reflective_out) {
  vec3 C = v3(0, 0, 0), color = v3(0, 0, 0);
  lreal specular = 0, reflective = 0;
#ifdef CLRT_BVH
  lint pending = hit >= 0;
  while (ANY(pending)) {
    const int i = LANE_MIN(pending ? hit : (lint)INT_MAX);
#else
  for (int i = 0; i < CLRT_SPHERE_COUNT(params); ++i) {
#endif
    __global const clrt_sphere* sphere = &spheres[i];
    lint is_hit = hit == i;
    C = vsel(is_hit, VEC3_FROM_HI_LO(sphere->center, sphere->center_lo), C);
    color = vsel(is_hit, v3(sphere->color[0], sphere->color[1], sphere->color[2]), color);
    specular = is_hit ? (lreal)sphere->specular : specular;
    reflective = is_hit ? (lreal)sphere->reflective : reflective;
#ifdef CLRT_BVH
    pending = pending & !is_hit;
#endif
  }
  *center_out = C;
  *color_out = color;
  *specular_out = specular;
  *reflective_out = reflective;
}

/* The book's ComputeLighting, per lane, at the hit point Pt of sphere `hit`
 * with normal N, seen along V (= -D), for the lanes of `alive`: ambient
 * light, plus diffuse and specular terms of every point and directional
 * light that no sphere blocks (a shadow ray from Pt). Where `classify` is
 * set (the primary ray of a pixel's first sample, trace.cl) the lights
 * blocked in a lane set its bits of *shadow_mask (the first 32 lights). */
CLRT_INLINE lreal compute_lighting(const vec3* point, const vec3* normal, const vec3* view, lreal specular, lint hit,
                                   lint alive, real epsilon, int classify, __global const clrt_params* params,
                                   __global const clrt_sphere* spheres, __global const clrt_light* lights,
                                   __global const clrt_bvh_node* nodes, __global const int* primitives,
                                   lint* shadow_mask, lane_ray_counts* counts) {
  const vec3 Pt = *point, N = *normal, V = *view;
  lreal intensity = 0;
  const lreal length_n = vlen(N);
  const lreal length_v = vlen(V);
  CLRT_UNROLL for (int light_index = 0; light_index < CLRT_LIGHT_COUNT(params); ++light_index) {
    __global const clrt_light* light = &lights[light_index];
    const int type = LIGHT_TYPE(light_index, light);
    const real light_intensity = light->intensity;
#if CLRT_HAS_AMBIENT
    if (type == CLRT_LIGHT_AMBIENT) {
      intensity += light_intensity;
      continue;
    }
#endif
#if CLRT_HAS_POINT || CLRT_HAS_DIRECTIONAL
    const vec3 light_vector = VEC3_FROM_HI_LO(light->vec, light->vec_lo);
    vec3 L;
    real tmax;
#if CLRT_HAS_POINT && CLRT_HAS_DIRECTIONAL
    if (type == CLRT_LIGHT_POINT) {
      L = vsub(light_vector, Pt);
      tmax = 1;
    } else {
      L = light_vector;
      tmax = REAL_INFINITY;
    }
#elif CLRT_HAS_POINT
    L = vsub(light_vector, Pt);
    tmax = 1;
#else
    L = light_vector;
    tmax = REAL_INFINITY;
#endif
    COUNT_IN_LANES(counts->shadow, alive, 1);
    lint tests = 0;
    const lint blocked =
        any_intersection(&Pt, &L, epsilon, tmax, hit, alive, params, spheres, nodes, primitives, &tests);
    COUNT_IN_LANES(counts->sphere_tests, alive, tests);
    if (classify && light_index < 32) *shadow_mask |= (blocked & alive) ? (lint)(int)(1u << light_index) : (lint)0;
    const lint lit = alive & !blocked;
    const lreal n_dot_l = vdot(N, L);
    intensity =
        (lit & (n_dot_l > 0)) ? intensity + light_intensity * REAL_DIVIDE(n_dot_l, length_n * vlen(L)) : intensity;
#if CLRT_HAS_SPECULAR
    const lint shiny = lit & (specular != -1);
    if (ANY(shiny)) {
      const vec3 R = reflect_ray(L, N);
      const lreal r_dot_v = vdot(R, V);
      const lint toward_eye = shiny & (r_dot_v > 0);
      intensity = toward_eye
                      ? intensity + light_intensity * REAL_POW(REAL_DIVIDE(r_dot_v, vlen(R) * length_v), specular)
                      : intensity;
    }
#endif
#endif
  }
  return intensity;
}

#endif /* CLRT_SHADE_H */
