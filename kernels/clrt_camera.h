/* clrt_camera.h - camera rays: the book's CanvasToViewport followed by the
 * camera's rotation, per lane. The canvas has its origin at the image's
 * centre, x to the right and y up; a pixel (x, y) is a canvas point, and
 * supersampling's samples are canvas points around it (clrt_samples.h).
 * fp64 builds rebuild every camera value from its hi and lo parts. */
#ifndef CLRT_CAMERA_H
#define CLRT_CAMERA_H

#include "clrt_math.h"

/* The camera of a frame, read once per work-item. */
typedef struct camera_view {
  vec3 origin;
  real rotation[9];        /* row-major: a direction is rotation x (dx, dy, d) */
  real viewport_w, viewport_h;
  real d;                  /* the projection plane's distance */
  int width, height;       /* the image's, in pixels */
} camera_view;

CLRT_INLINE camera_view camera_of(__global const clrt_params* params) {
  camera_view view;
  view.origin = VEC3_FROM_HI_LO(params->origin, params->origin_lo);
  for (int k = 0; k < 9; ++k) view.rotation[k] = REAL_FROM_HI_LO(params->rotation[k], params->rotation_lo[k]);
  view.viewport_w = REAL_FROM_HI_LO(params->viewport[0], params->viewport_lo[0]);
  view.viewport_h = REAL_FROM_HI_LO(params->viewport[1], params->viewport_lo[1]);
  view.d = REAL_FROM_HI_LO(params->proj_d, params->proj_d_lo);
  view.width = params->width;
  view.height = params->height;
  return view;
}

/* The canvas point of each lane's pixel, from its image column and row
 * (rows count down from the top). */
CLRT_INLINE void canvas_point(const camera_view* view, const lint col, const lint row, lint* x, lint* y) {
  *x = col - view->width / 2;
  *y = view->height / 2 - 1 - row;
}

/* The direction of the camera ray through the viewport point (dx, dy, dz),
 * rotated by the camera's m. */
CLRT_INLINE vec3 camera_direction(const lreal dx, const lreal dy, const real* m, const real dz) {
  return v3(m[0] * dx + m[1] * dy + m[2] * dz, m[3] * dx + m[4] * dy + m[5] * dz, m[6] * dx + m[7] * dy + m[8] * dz);
}

/* The direction of the camera ray through canvas point (cx, cy): its
 * viewport point, rotated. Every camera ray takes this one expression (the
 * layers' ray and subsampling's first pass must meet what the colour's ray
 * met, bit for bit). */
CLRT_INLINE vec3 canvas_direction(const camera_view* view, const lreal cx, const lreal cy) {
  const lreal dx = cx * view->viewport_w / (real)view->width;
  const lreal dy = cy * view->viewport_h / (real)view->height;
  return camera_direction(dx, dy, view->rotation, view->d);
}

#endif /* CLRT_CAMERA_H */
