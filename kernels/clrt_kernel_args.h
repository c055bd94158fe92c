/* clrt_kernel_args.h - the render kernels' arguments, declared once, for
 * both sides: every entry point (trace.cl) expands the list into its
 * parameter list (CLRT_RENDER_PARAMS), the host into the enum it sets them
 * by (host/render/kernel_args.hpp: RenderArg, set_arg()). An argument added
 * here reaches both; the host checks each built kernel's count against the
 * list (DeviceRenderer::use_program) and a test their names
 * (tests/render/test_kernel_args.cpp).
 *
 * Each entry is X(name, kernel type, host kind): the name is the kernel's
 * parameter and the host's enumerator, the kind says what the host passes
 * (buffer: a cl::Buffer; integer: a cl_int). The layers buffer exists only
 * in layer builds (-DCLRT_OUT_LAYERS), so it is the last entry (through
 * LAYERS_X), and every other argument has the same index in every build.
 *
 * Like clrt_layout.h this file is compiled by both sides: the host sees
 * the list only (the types are tokens it never expands). */
#ifndef CLRT_KERNEL_ARGS_H
#define CLRT_KERNEL_ARGS_H

#define CLRT_RENDER_ARGS(X, LAYERS_X)                                                                                 \
  X(params, __global const clrt_params*, buffer)                                                                      \
  X(spheres, __global const clrt_sphere*, buffer)                                                                     \
  X(lights, __global const clrt_light*, buffer)                                                                       \
  X(colors, __global CANVAS_T*, buffer)               /* 3 floats or 4 bytes per pixel (clrt_film.h) */               \
  X(classes, __global int*, buffer)                   /* hit id and shadow mask per pixel */                          \
  X(counters, __global clrt_ray_counts*, buffer)      /* per pixel (CLRT_COUNT_RAYS) */                               \
  X(x0, const int, integer)                           /* the tile's first column, */                                  \
  X(y0, const int, integer)                           /* its first row, */                                            \
  X(tile_w, const int, integer)                       /* its width */                                                 \
  X(tile_h, const int, integer)                       /* and height */                                                \
  X(first_column, const int, integer)                 /* the launch's tile columns: first_column, */                  \
  X(column_step, const int, integer)                  /* then every column_step-th (clrt_block.h) */                  \
  X(nodes, __global const clrt_wide_node*, buffer)    /* the hierarchy (-DCLRT_BVH) */                                \
  X(primitives, __global const int*, buffer)          /* its leaves' entries */                                       \
  X(leaf_spheres, __global const clrt_leaf_sphere*, buffer) /* their spheres, in the entries' order */               \
  X(planes, __global const clrt_plane*, buffer)                                                                       \
  X(triangles, __global const clrt_triangle*, buffer)                                                                 \
  X(triangles_lo, __global const clrt_triangle_lo*, buffer) /* their lo parts (fp64 builds) */                     \
  X(triangle_slots, __global const int*, buffer)      /* a triangle's place in them (-DCLRT_BVH: clrt_layout.h) */    \
  X(materials, __global const clrt_material*, buffer) /* of planes and triangles */                                   \
  X(status, __global int*, buffer)                    /* the device status word (clrt_device_status.h) */             \
  LAYERS_X(layers, __global float*, buffer)           /* CLRT_LAYER_FLOATS per pixel (clrt_layers.h) */

#ifdef __OPENCL_VERSION__
/* The entry points' parameter list: every entry as ", type name", the
 * first comma dropped (CLRT_DROP_FIRST, through CLRT_APPLY so that the list
 * is expanded into arguments first); the layers only in layer builds. */
#define CLRT_PARAM(name, type, kind) , type name
#define CLRT_NO_PARAM(name, type, kind)
#ifdef CLRT_OUT_LAYERS
#define CLRT_LAYERS_PARAM CLRT_PARAM
#else
#define CLRT_LAYERS_PARAM CLRT_NO_PARAM
#endif
#define CLRT_DROP_FIRST(first, ...) __VA_ARGS__
#define CLRT_APPLY(macro, ...) macro(__VA_ARGS__)
#define CLRT_RENDER_PARAMS CLRT_APPLY(CLRT_DROP_FIRST, CLRT_RENDER_ARGS(CLRT_PARAM, CLRT_LAYERS_PARAM))
#endif

#endif /* CLRT_KERNEL_ARGS_H */
