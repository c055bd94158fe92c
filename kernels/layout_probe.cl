/* layout_probe.cl - reports the kernel compiler's view of the shared layouts,
 * compared with the host's in tests/render/test_opencl.cpp. For every entry
 * of CLRT_LAYOUT_FIELDS, in order, three ints: the member's offset, the
 * member's size and the size of its struct. */
#include "clrt_layout.h"

/* Offsets as differences of two addresses inside one real object: the
 * null-pointer form ((T*)0)->m is undefined, and Mesa rusticl's compiler
 * folds it to values one less than the true offsets. */
#define PROBE_FIELD(type, member)                                               \
  {                                                                             \
    type probe;                                                                 \
    out[i++] = (int)((__private char*)&probe.member - (__private char*)&probe); \
    out[i++] = (int)sizeof(probe.member);                                       \
    out[i++] = (int)sizeof(type);                                               \
  }

__kernel void layout_probe(__global int* out) {
  int i = 0;
  CLRT_LAYOUT_FIELDS(PROBE_FIELD)
}
