/* clrt_lanes.h - the scalar type of a precision variant (`real`) and the SIMD
 * lane types built from it.
 *
 * A work-item shades a block of CLRT_LANES pixels (clrt_block.h), one per lane of
 * `lreal`: float16/float8/float4 in specialized float builds (the host picks
 * 16 on AVX-512 CPUs, 8 on other CPUs, 1 on GPUs: default_lanes() in
 * host/render/build_options.hpp), a plain scalar (1 lane) in generic and fp64
 * builds. Every lane runs exactly the per-pixel algorithm, with branches
 * turned into per-lane masks; loops stop when no lane needs them any more.
 * PoCL does not vectorize the kernel across work-items by itself (see
 * docs/developer/kernel.md), so the lanes are written out; the scalar build runs
 * the same code with 1-lane masks. */
#ifndef CLRT_LANES_H
#define CLRT_LANES_H

#include "clrt_config.h"

/* ---- the scalar of the precision variant ------------------------------ */
#if CLRT_PRECISION == CLRT_PRECISION_FP64
#pragma OPENCL EXTENSION cl_khr_fp64 : enable
typedef double real;
#define REAL_INFINITY ((double)INFINITY)
#else
typedef float real;
#if CLRT_PRECISION == CLRT_PRECISION_FAST
/* -cl-fast-relaxed-math lets the compiler assume no operand is infinite, so
 * a comparison with INFINITY is undefined there: the largest float stands for
 * "no hit" instead (no distance reaches it). (Not what made the fast variant
 * slow on large scenes: that was its boxes' padding, host/render/bvh.hpp.) */
#define REAL_INFINITY FLT_MAX
#else
#define REAL_INFINITY INFINITY
#endif
#endif

/* ---- lane types -------------------------------------------------------- */
/* lreal holds one value per pixel of the work-item, lint the matching
 * integers and masks. Masks are what comparisons return: 0/1 for scalars,
 * 0/-1 for vectors, so they are only ever combined with & | ! and other
 * masks of the same kind, and consumed by ?: or ANY/ALL. */
#if CLRT_LANES == 1
typedef real lreal;
typedef int lint;
#define ANY(mask) (mask)
#define ALL(mask) (mask)
#define TO_LREAL(i) ((real)(i))
#define LANE_IOTA 0
#elif CLRT_LANES == 4
typedef float4 lreal;
typedef int4 lint;
#define TO_LREAL(i) convert_float4(i)
#define LANE_IOTA ((int4)(0, 1, 2, 3))
#elif CLRT_LANES == 8
typedef float8 lreal;
typedef int8 lint;
#define TO_LREAL(i) convert_float8(i)
#define LANE_IOTA ((int8)(0, 1, 2, 3, 4, 5, 6, 7))
#elif CLRT_LANES == 16
typedef float16 lreal;
typedef int16 lint;
#define TO_LREAL(i) convert_float16(i)
#define LANE_IOTA ((int16)(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15))
#else
#error "CLRT_LANES must be 1, 4, 8 or 16"
#endif
#if CLRT_LANES > 1
#if CLRT_PRECISION == CLRT_PRECISION_FP64
#error "fp64 builds use CLRT_LANES=1"
#endif
/* OR / AND of the lanes as a tree of halves (LLVM turns it into one vector
 * test; PoCL's any() and all() test lane after lane, a branch each). */
#if CLRT_LANES == 4
#define LANE_OR(m) lane_or4(m)
#define LANE_AND(m) lane_and4(m)
#elif CLRT_LANES == 8
#define LANE_OR(m) lane_or4((m).lo | (m).hi)
#define LANE_AND(m) lane_and4((m).lo&(m).hi)
#else
#define LANE_OR(m) lane_or4(((m).lo.lo | (m).lo.hi) | ((m).hi.lo | (m).hi.hi))
#define LANE_AND(m) lane_and4(((m).lo.lo & (m).lo.hi) & ((m).hi.lo & (m).hi.hi))
#endif
inline int lane_or4(int4 m) {
  const int2 h = m.lo | m.hi;
  return h.x | h.y;
}
inline int lane_and4(int4 m) {
  const int2 h = m.lo & m.hi;
  return h.x & h.y;
}
#define ANY(mask) (LANE_OR(mask) != 0)
#define ALL(mask) (LANE_AND(mask) != 0)
#define FIRST_LANE(x) ((x).s0)
#else
#define FIRST_LANE(x) (x)
#endif
/* The smallest of the lanes of a lint. */
#if CLRT_LANES == 1
#define LANE_MIN(x) (x)
#elif CLRT_LANES == 4
#define LANE_MIN(x) lane_min4(x)
#elif CLRT_LANES == 8
#define LANE_MIN(x) lane_min4(min((x).lo, (x).hi))
#else
#define LANE_MIN(x) lane_min4(min(min((x).lo.lo, (x).lo.hi), min((x).hi.lo, (x).hi.hi)))
#endif
#if CLRT_LANES > 1
inline int lane_min4(int4 x) {
  const int2 m = min(x.lo, x.hi);
  return min(m.x, m.y);
}
/* The smallest of four floats, by selects (no NaN where it is used). */
inline float lane_min4_real(float4 x) {
  const float2 m = x.lo < x.hi ? x.lo : x.hi;
  return m.x < m.y ? m.x : m.y;
}
#endif
#define MASK_TRUE ((lint)(CLRT_LANES == 1 ? 1 : -1))

/* Bit casts and the truncating conversion, per lane. */
#if CLRT_LANES == 1
#define AS_LINT(x) as_int(x)
#define AS_LREAL(i) as_float(i)
#define TO_LINT(x) ((int)(x))
#define LOAD_LANES(lanes) ((lanes)[0])
#else
#define CONCAT_TOKENS(a, b) a##b
#define CONCAT_EXPANDED(a, b) CONCAT_TOKENS(a, b) /* expands CLRT_LANES first */
#define AS_LINT(x) CONCAT_EXPANDED(as_int, CLRT_LANES)(x)
#define AS_LREAL(i) CONCAT_EXPANDED(as_float, CLRT_LANES)(i)
#define TO_LINT(x) CONCAT_EXPANDED(convert_int, CLRT_LANES)(x) /* truncates, like (int) */
/* Stores the lanes of `value` to the array `lanes` (one element per lane). */
#define STORE_LANES(lanes, value) CONCAT_EXPANDED(vstore, CLRT_LANES)((value), 0, (lanes))
/* The lanes' values from the array `lanes` (one int per lane). */
#define LOAD_LANES(lanes) CONCAT_EXPANDED(vload, CLRT_LANES)(0, (lanes))
#endif

/* ---- the stored colour (CLRT_OUT_RGBA8) --------------------------------- */
/* A pixel's colour as stored: float (unclamped), or the book's canvas rule
 * for 8-bit outputs - clamp to [0, 255], round half to even, NaN to 0 (what
 * a saturating conversion does) - exactly the host's to_u8() of the float
 * the host would have received (fp64 results are rounded to float first). */
#ifdef CLRT_OUT_RGBA8
typedef uchar CANVAS_T;
#if CLRT_LANES == 1
#define TO_CANVAS(v) convert_uchar_sat_rte((float)(v))
#else
#define TO_CANVAS(v) CONCAT_EXPANDED(CONCAT_EXPANDED(convert_uchar, CLRT_LANES), _sat_rte)(v)
#endif
#else
typedef float CANVAS_T;
#define TO_CANVAS(v) CONVERT_TO_FLOAT(v)
#if CLRT_LANES == 1
#define CONVERT_TO_FLOAT(v) ((float)(v))
#else
#define CONVERT_TO_FLOAT(v) (v)
#endif
#endif

/* ---- per-lane ray counters (CLRT_COUNT_RAYS) --------------------------- */
/* One clrt_ray_counts per lane's pixel. Without CLRT_COUNT_RAYS nothing is
 * ever added, and the unused counters are compiled away. */
typedef struct {
  lint primary, shadow, reflection, sphere_tests, refraction;
} lane_ray_counts;
#ifdef CLRT_COUNT_RAYS
/* adds n to `counter` in the lanes of `mask` */
#define COUNT_IN_LANES(counter, mask, n) ((counter) += (mask) ? (lint)(n) : (lint)0)
#else
#define COUNT_IN_LANES(counter, mask, n) ((void)0)
#endif

#endif /* CLRT_LANES_H */
