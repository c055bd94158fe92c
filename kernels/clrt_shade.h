/* clrt_shade.h - shading at a hit point: the hit sphere's material, the
 * book's ComputeLighting with its shadow rays, and the reflection of a ray. */
#ifndef CLRT_SHADE_H
#define CLRT_SHADE_H

#include "clrt_query.h"

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

#define CLRT_HAS_FLAT (CLRT_HAS_PLANES || CLRT_HAS_TRIANGLES)

/* What shading needs of the primitive a lane hit. */
typedef struct hit_surface {
  vec3 center, color;
  lreal specular, reflective;
#if CLRT_HAS_TRANSPARENT
  lreal transparency, refractive_index, outside_index; /* chapter 5 (spheres; 0, 1, 1 for the others) */
#endif
#if CLRT_HAS_FLAT
  lint flat;         /* a plane or triangle: */
  vec3 flat_normal;  /* its normal, not normalized nor turned */
#endif
} hit_surface;

#if CLRT_HAS_FLAT
/* The material and normal of flat primitive `id` into the lanes of `is_hit`. */
CLRT_INLINE void flat_surface(int id, lint is_hit, const scene_data* scene, hit_surface* out) {
  __global const clrt_params* params = scene->params;
  vec3 n;
  int material;
  if (id < TRIANGLE_ID0(params)) {
    __global const clrt_plane* p = &scene->planes[id - PLANE_ID0(params)];
    n = VEC3_FROM_HI_LO(p->normal, p->normal_lo);
    material = p->material;
  } else {
#if CLRT_HAS_TRIANGLES
    const int slot = TRIANGLE_SLOT(scene, id - TRIANGLE_ID0(params));
    __global const clrt_triangle* tri = &scene->triangles[slot];
    __global const clrt_triangle_lo* lo = TRIANGLE_LO(scene, slot);
    const vec3 v0 = VEC3_FROM_HI_LO(tri->v0, lo->v0_lo);
    const vec3 e1 = vsub(VEC3_FROM_HI_LO(tri->v1, lo->v1_lo), v0), e2 = vsub(VEC3_FROM_HI_LO(tri->v2, lo->v2_lo), v0);
    n = v3(e1.y * e2.z - e1.z * e2.y, e1.z * e2.x - e1.x * e2.z, e1.x * e2.y - e1.y * e2.x);
    material = tri->material;
#else
    n = v3(0, 0, 1);
    material = 0;
#endif
  }
  __global const clrt_material* m = &scene->materials[material];
  out->flat = out->flat | is_hit;
  out->flat_normal = vsel(is_hit, n, out->flat_normal);
  out->color = vsel(is_hit, v3(m->color[0], m->color[1], m->color[2]), out->color);
  out->specular = is_hit ? (lreal)m->specular : out->specular;
  out->reflective = is_hit ? (lreal)m->reflective : out->reflective;
}
#endif

/* The hit primitive's surface, per lane (`hit` is each lane's primitive id,
 * -1 for none: zeros). Lanes may hit different primitives. Testing every
 * sphere, each one is read (a uniform load) and selected per lane: few
 * spheres, no gathers. With the hierarchy that loop would cost as much as
 * testing every sphere, so each distinct id among the lanes is read once
 * (one pass per primitive the lanes hit, at most CLRT_LANES); planes and
 * triangles always take that path. */
CLRT_INLINE hit_surface hit_material(lint hit, const scene_data* scene) {
  __global const clrt_params* params = scene->params;
  hit_surface out;
  out.center = v3(0, 0, 0);
  out.color = v3(0, 0, 0);
  out.specular = 0;
  out.reflective = 0;
#if CLRT_HAS_TRANSPARENT
  out.transparency = 0;
  out.refractive_index = 1;
  out.outside_index = 1;
#endif
#if CLRT_HAS_FLAT
  out.flat = 0;
  out.flat_normal = v3(0, 0, 0);
#endif
#ifdef CLRT_BVH
  lint pending = hit >= 0;
  while (ANY(pending)) {
    const int i = LANE_MIN(pending ? hit : (lint)INT_MAX);
    const lint is_hit = hit == i;
    pending = pending & !is_hit;
#if CLRT_HAS_FLAT
    if (i >= CLRT_SPHERE_COUNT(params)) {
      flat_surface(i, is_hit, scene, &out);
      continue;
    }
#endif
#else
  for (int i = 0; i < CLRT_SPHERE_COUNT(params); ++i) {
    const lint is_hit = hit == i;
#endif
    __global const clrt_sphere* sphere = &scene->spheres[i];
    out.center = vsel(is_hit, VEC3_FROM_HI_LO(sphere->center, sphere->center_lo), out.center);
    out.color = vsel(is_hit, v3(sphere->color[0], sphere->color[1], sphere->color[2]), out.color);
    out.specular = is_hit ? (lreal)sphere->specular : out.specular;
    out.reflective = is_hit ? (lreal)sphere->reflective : out.reflective;
#if CLRT_HAS_TRANSPARENT
    out.transparency = is_hit ? (lreal)sphere->transparency : out.transparency;
    out.refractive_index = is_hit ? (lreal)sphere->refractive_index : out.refractive_index;
    out.outside_index = is_hit ? (lreal)sphere->outside_index : out.outside_index;
#endif
  }
#if CLRT_HAS_FLAT && !defined(CLRT_BVH)
  lint pending = hit >= CLRT_SPHERE_COUNT(params);
  while (ANY(pending)) {
    const int i = LANE_MIN(pending ? hit : (lint)INT_MAX);
    const lint is_hit = hit == i;
    pending = pending & !is_hit;
    flat_surface(i, is_hit, scene, &out);
  }
#endif
  return out;
}

/* The unit normal at hit point Pt: outward for spheres; for planes and
 * triangles (two-sided) turned against the ray D. */
CLRT_INLINE vec3 surface_normal(const hit_surface* surface, const vec3* Pt, const vec3* D) {
  vec3 N = vsub(*Pt, surface->center);
#if CLRT_HAS_FLAT
  const vec3 flat = vsel(vdot(surface->flat_normal, *D) > 0, vneg(surface->flat_normal), surface->flat_normal);
  N = vsel(surface->flat, flat, N);
#endif
  return vscale(1 / vlen(N), N);
}

#if CLRT_HAS_TRANSPARENT
/* Snell's law per lane (the reference's RefractRay, stated there): for the
 * unit direction d = D/|D| and the outward normal N of the hit sphere, the
 * ray leaves the sphere where N.d > 0 (*exiting), passing from the ray's
 * medium n1 into the sphere's index (entering) or the medium around it
 * (leaving), *n2. With cos_i = |N.d|, N' = N turned against d,
 * eta = n1 / n2 and k = 1 - eta^2 (1 - cos_i^2), k < 0 is total internal
 * reflection (*tir), else T = eta d + (eta cos_i - sqrt(k)) N'; equal
 * indices go straight on (T = d). */
CLRT_INLINE vec3 refract_ray(const vec3 D, const vec3 N, const lreal n1, const hit_surface* surface, lreal* n2_out,
                             lint* tir) {
  const vec3 d = vscale(1 / vlen(D), D);
  const lreal n_dot_d = vdot(N, d);
  const lint exiting = n_dot_d > 0;
  const lreal cos_i = exiting ? n_dot_d : -n_dot_d;
  const vec3 facing = vsel(exiting, vneg(N), N);
  const lreal n2 = exiting ? surface->outside_index : surface->refractive_index;
  const lreal eta = n1 / n2;
  const lreal k = 1 - eta * eta * (1 - cos_i * cos_i);
  const lint same = n1 == n2;
  *tir = !same & (k < 0);
  *n2_out = n2;
  const vec3 bent = vadd(vscale(eta, d), vscale(eta * cos_i - REAL_SQRT(max(k, (lreal)0)), facing));
  return vsel(same, d, bent);
}
#endif

/* The book's ComputeLighting, per lane, at the hit point Pt of sphere `hit`
 * with normal N, seen along V (= -D), for the lanes of `alive`: ambient
 * light, plus diffuse and specular terms of every point and directional
 * light that no sphere blocks (a shadow ray from Pt). Where `classify` is
 * set (the primary ray of a pixel's first sample, clrt_ray_tree.h) the lights
 * blocked in a lane set its bits of *shadow_mask (the first 32 lights). */
CLRT_INLINE lreal compute_lighting(const vec3* point, const vec3* normal, const vec3* view, lreal specular, lint hit,
                                   lint alive, real epsilon, int classify, const scene_data* scene, lint* shadow_mask,
                                   lane_ray_counts* counts) {
  __global const clrt_params* params = scene->params;
  __global const clrt_light* lights = scene->lights;
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
    /* A directional light's range starts at epsilon in units of the
     * direction the scene gave (clrt_light.t_min_scale). */
    real tmin = epsilon;
#if CLRT_HAS_POINT && CLRT_HAS_DIRECTIONAL
    if (type == CLRT_LIGHT_POINT) {
      L = vsub(light_vector, Pt);
      tmax = 1;
    } else {
      L = light_vector;
      tmin = epsilon * (real)light->t_min_scale;
      tmax = REAL_INFINITY;
    }
#elif CLRT_HAS_POINT
    L = vsub(light_vector, Pt);
    tmax = 1;
#else
    L = light_vector;
    tmin = epsilon * (real)light->t_min_scale;
    tmax = REAL_INFINITY;
#endif
    /* A light adds its diffuse term where N.L > 0 and its specular term
     * where R.V > 0; where neither holds it adds nothing, blocked or not, so
     * no shadow ray is traced there (the same image as the book's order,
     * which tests the shadow first), unless the lane's blocked lights are
     * stored (classes: subsampling's and --classes' shadow masks). */
    const lreal n_dot_l = vdot(N, L);
#if CLRT_HAS_SPECULAR
    const vec3 R = reflect_ray(L, N);
    const lreal r_dot_v = vdot(R, V);
    const lint toward_eye = (specular != -1) & (r_dot_v > 0);
    const lint adds = (n_dot_l > 0) | toward_eye;
#else
    const lint adds = n_dot_l > 0;
#endif
#if defined(CLRT_OUT_CLASSES) || CLRT_SUBSAMPLE
    const lint traced = classify ? alive : alive & adds;
#else
    const lint traced = alive & adds;
#endif
    COUNT_IN_LANES(counts->shadow, traced, 1);
    lint tests = 0;
    const lint blocked = ANY(traced) ? any_intersection(&Pt, &L, tmin, tmax, hit, traced, scene, &tests) : (lint)0;
    COUNT_IN_LANES(counts->sphere_tests, traced, tests);
    if (classify && light_index < 32) *shadow_mask |= (blocked & alive) ? (lint)(int)(1u << light_index) : (lint)0;
    const lint lit = traced & !blocked;
    intensity =
        (lit & (n_dot_l > 0)) ? intensity + light_intensity * REAL_DIVIDE(n_dot_l, length_n * vlen(L)) : intensity;
#if CLRT_HAS_SPECULAR
    const lint shiny = lit & toward_eye;
    if (ANY(shiny)) {
      intensity = shiny ? intensity + light_intensity * REAL_POW(REAL_DIVIDE(r_dot_v, vlen(R) * length_v), specular)
                        : intensity;
    }
#endif
#endif
  }
  return intensity;
}

#endif /* CLRT_SHADE_H */
