/* layout_probe.cl - reports the kernel compiler's view of the shared layouts
 * (sizes and member offsets), compared with the host's in tests/. */
#include "clrt_layout.h"

/* Offsets as differences of two addresses inside one real object: the
 * null-pointer form ((T*)0)->m is undefined, and Mesa rusticl's compiler
 * folds it to values one less than the true offsets. */
#define OFF(T, m) ((int)((__private char*)&probe_##T.m - (__private char*)&probe_##T))

__kernel void layout_probe(__global int* out) {
  clrt_sphere probe_clrt_sphere;
  clrt_light probe_clrt_light;
  clrt_params probe_clrt_params;
  clrt_ray_counts probe_clrt_ray_counts;
  int i = 0;
  out[i++] = (int)sizeof(clrt_sphere);
  out[i++] = OFF(clrt_sphere, radius);
  out[i++] = OFF(clrt_sphere, center_lo);
  out[i++] = OFF(clrt_sphere, radius_lo);
  out[i++] = OFF(clrt_sphere, color);
  out[i++] = OFF(clrt_sphere, specular);
  out[i++] = OFF(clrt_sphere, reflective);
  out[i++] = (int)sizeof(clrt_light);
  out[i++] = OFF(clrt_light, intensity);
  out[i++] = OFF(clrt_light, vec);
  out[i++] = OFF(clrt_light, vec_lo);
  out[i++] = (int)sizeof(clrt_params);
  out[i++] = OFF(clrt_params, n_lights);
  out[i++] = OFF(clrt_params, viewport);
  out[i++] = OFF(clrt_params, proj_d);
  out[i++] = OFF(clrt_params, epsilon);
  out[i++] = OFF(clrt_params, origin);
  out[i++] = OFF(clrt_params, origin_lo);
  out[i++] = OFF(clrt_params, rotation);
  out[i++] = OFF(clrt_params, rotation_lo);
  out[i++] = OFF(clrt_params, background);
  out[i++] = OFF(clrt_params, proj_d_lo);
  out[i++] = OFF(clrt_params, viewport_lo);
  out[i++] = OFF(clrt_params, epsilon_lo);
  out[i++] = (int)sizeof(clrt_ray_counts);
  out[i++] = OFF(clrt_ray_counts, sphere_tests);
}
