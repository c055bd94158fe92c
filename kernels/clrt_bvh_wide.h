/* clrt_bvh_wide.h - the vector types of one ray's walk (clrt_bvh.h:
 * ray_boxes(), ray_push()), which tests a node's CLRT_BVH_WIDTH children
 * in one SIMD step: wide_real (a row of a node's boxes, in the precision's
 * scalar), wide_mask and wide_int, their loads and stores, the sum of a
 * mask's lanes, and the sorting network that orders a node's keys. */
#ifndef CLRT_BVH_WIDE_H
#define CLRT_BVH_WIDE_H

#if CLRT_BVH_WIDTH == 4
#define WIDE_LOAD(p) vload4(0, p)
#define WIDE_STORE(v, p) vstore4(v, 0, p)
#if CLRT_PRECISION == CLRT_PRECISION_FP64
typedef double4 wide_real;
typedef long4 wide_mask;
#define TO_WIDE_REAL(v) convert_double4(v)
#define TO_WIDE_MASK(v) convert_long4(v)
#define WIDE_MASK_TO_INT(v) convert_int4(v)
#define AS_WIDE_KEY(v) as_long4(v)
#define AS_WIDE_REAL(v) as_double4(v)
#else
typedef float4 wide_real;
typedef int4 wide_mask;
#define TO_WIDE_REAL(v) (v)
#define TO_WIDE_MASK(v) (v)
#define WIDE_MASK_TO_INT(v) (v)
#define AS_WIDE_KEY(v) as_int4(v)
#define AS_WIDE_REAL(v) as_float4(v)
#endif
#define WIDE_KEY_IOTA ((wide_mask)(0, 1, 2, 3))
typedef int4 wide_int;
CLRT_INLINE int wide_sum(int4 v) {
  const int2 h = v.lo + v.hi;
  return h.x + h.y;
}
/* Sorts keys largest first: a bitonic network of swizzles, min and max. */
CLRT_INLINE wide_mask sort_descending(wide_mask v) {
  wide_mask p = v.s1032;
  v = select(min(v, p), max(v, p), (wide_mask)(-1, 0, 0, -1));
  p = v.s2301;
  v = select(min(v, p), max(v, p), (wide_mask)(-1, -1, 0, 0));
  p = v.s1032;
  return select(min(v, p), max(v, p), (wide_mask)(-1, 0, -1, 0));
}
#elif CLRT_BVH_WIDTH == 8
#define WIDE_LOAD(p) vload8(0, p)
#define WIDE_STORE(v, p) vstore8(v, 0, p)
#if CLRT_PRECISION == CLRT_PRECISION_FP64
typedef double8 wide_real;
typedef long8 wide_mask;
#define TO_WIDE_REAL(v) convert_double8(v)
#define TO_WIDE_MASK(v) convert_long8(v)
#define WIDE_MASK_TO_INT(v) convert_int8(v)
#define AS_WIDE_KEY(v) as_long8(v)
#define AS_WIDE_REAL(v) as_double8(v)
#else
typedef float8 wide_real;
typedef int8 wide_mask;
#define TO_WIDE_REAL(v) (v)
#define TO_WIDE_MASK(v) (v)
#define WIDE_MASK_TO_INT(v) (v)
#define AS_WIDE_KEY(v) as_int8(v)
#define AS_WIDE_REAL(v) as_float8(v)
#endif
#define WIDE_KEY_IOTA ((wide_mask)(0, 1, 2, 3, 4, 5, 6, 7))
typedef int8 wide_int;
CLRT_INLINE int wide_sum(int8 v) {
  const int4 h4 = v.lo + v.hi;
  const int2 h = h4.lo + h4.hi;
  return h.x + h.y;
}
/* Sorts keys largest first: a bitonic network of swizzles, min and max. */
CLRT_INLINE wide_mask sort_descending(wide_mask v) {
  wide_mask p = v.s10325476;
  v = select(min(v, p), max(v, p), (wide_mask)(-1, 0, 0, -1, -1, 0, 0, -1));
  p = v.s23016745;
  v = select(min(v, p), max(v, p), (wide_mask)(-1, -1, 0, 0, 0, 0, -1, -1));
  p = v.s10325476;
  v = select(min(v, p), max(v, p), (wide_mask)(-1, 0, -1, 0, 0, -1, 0, -1));
  p = v.s45670123;
  v = select(min(v, p), max(v, p), (wide_mask)(-1, -1, -1, -1, 0, 0, 0, 0));
  p = v.s23016745;
  v = select(min(v, p), max(v, p), (wide_mask)(-1, -1, 0, 0, -1, -1, 0, 0));
  p = v.s10325476;
  return select(min(v, p), max(v, p), (wide_mask)(-1, 0, -1, 0, -1, 0, -1, 0));
}
#else
#error "CLRT_BVH_WIDTH must be 4 or 8"
#endif

#endif /* CLRT_BVH_WIDE_H */
