/* clrt_device_status.h - checks a work-item makes on its own run, reported
 * in the status word (CLRT_STATUS_*, clrt_layout.h).
 *
 * Mesa's llvmpipe (the device of rusticl's swrast) ends a work-item's loops
 * after 65 535 iterations in all: one counter per invocation, shared by
 * every loop it runs (gallivm's LP_MAX_TGSI_LOOP_ITERATIONS), guards against
 * shaders that never end. Past it every loop stops after one pass and the
 * work-item goes on with what it has: a pixel whose ray tree, hierarchy
 * walks and light loops take more iterations than that comes out wrong, and
 * nothing says so (measured: the ray-cut test's shells between mirrors at
 * depth 14 and more, 18 to 55 levels off). The host builds the check into
 * programs for llvmpipe (-DCLRT_LOOP_LIMIT_PROBE, host/render/build_options.cpp).
 *
 * The check: a last loop of two passes. Its bound comes from memory (the
 * compiler cannot unroll it away) and it counts in a volatile (nor fold the
 * count); where the driver's counter has run out it makes one pass, and the
 * work-item sets CLRT_STATUS_LOOP_LIMIT. A work-item that used exactly the
 * whole allowance is reported too (its last loop could not have ended
 * otherwise). */
#ifndef CLRT_DEVICE_STATUS_H
#define CLRT_DEVICE_STATUS_H

#include "clrt_config.h"
#include "clrt_layout.h"

#ifdef CLRT_LOOP_LIMIT_PROBE
CLRT_INLINE void check_loop_limit(const int frame_width, __global int* status) {
  const int passes = 2 + (frame_width < 0); /* 2: the width is never negative, but only memory says so */
  volatile int made = 0;
  for (int i = 0; i < passes; ++i) made = made + 1;
  if (made != passes) atomic_or(status, CLRT_STATUS_LOOP_LIMIT);
}
#define CHECK_LOOP_LIMIT(params, status) check_loop_limit((params)->width, (status))
#else
#define CHECK_LOOP_LIMIT(params, status) ((void)0)
#endif

#endif
