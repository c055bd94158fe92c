/* clrt_math.h - 3-vectors of lanes, scene values rebuilt from their hi/lo
 * pairs, the arithmetic each precision variant chooses, the specular power,
 * and the error-free transformations of the robust variant. */
#ifndef CLRT_MATH_H
#define CLRT_MATH_H

#include "clrt_lanes.h"

/* ---- 3-vectors ---------------------------------------------------------- */
/* A 3-vector as three lane values, not float3: a 3-component vector per
 * pixel would need one more lane dimension. Macros, not functions, because
 * structs passed or returned by value are coerced to <2 x float> pairs by the
 * target ABI. Plain component formulas (dot = x*x' + y*y' + z*z'). */
typedef struct {
  lreal x, y, z;
} vec3;
#define v3(x, y, z) ((vec3){(x), (y), (z)})
#define vadd(a, b) v3((a).x + (b).x, (a).y + (b).y, (a).z + (b).z)
#define vsub(a, b) v3((a).x - (b).x, (a).y - (b).y, (a).z - (b).z)
#define vscale(s, a) v3((s) * (a).x, (s) * (a).y, (s) * (a).z)
#define vneg(a) v3(-(a).x, -(a).y, -(a).z)
#define vdot(a, b) ((a).x * (b).x + (a).y * (b).y + (a).z * (b).z)
#define vlen(a) sqrt(vdot((a), (a)))
/* per lane: mask ? a : b */
#define vsel(mask, a, b) v3((mask) ? (a).x : (b).x, (mask) ? (a).y : (b).y, (mask) ? (a).z : (b).z)

/* ---- scene values from hi/lo pairs (clrt_layout.h) ---------------------- */
/* fp64 builds rebuild the host's double to ~48 bits from hi + lo; float
 * builds use the hi part (robust mode reads the lo parts where it needs
 * them). */
#if CLRT_PRECISION == CLRT_PRECISION_FP64
#define REAL_FROM_HI_LO(hi, lo) ((double)(hi) + (double)(lo))
#else
#define REAL_FROM_HI_LO(hi, lo) (hi)
#endif
/* the same for 3-element arrays of hi and lo parts */
#define VEC3_FROM_HI_LO(hi, lo) \
  v3(REAL_FROM_HI_LO((hi)[0], (lo)[0]), REAL_FROM_HI_LO((hi)[1], (lo)[1]), REAL_FROM_HI_LO((hi)[2], (lo)[2]))

/* ---- arithmetic per precision variant ---------------------------------- */
/* Fast mode uses the native (hardware, lower accuracy) square root and
 * division. */
#if CLRT_PRECISION == CLRT_PRECISION_FAST
#define REAL_SQRT(x) native_sqrt(x)
#define REAL_DIVIDE(a, b) native_divide((a), (b))
#else
#define REAL_SQRT(x) sqrt(x)
#define REAL_DIVIDE(a, b) ((a) / (b))
#endif
#if CLRT_PRECISION == CLRT_PRECISION_FP64 || defined(CLRT_LIB_POW)
#define REAL_POW(a, b) pow((a), (b))
#else
#define REAL_POW(a, b) spec_pow((a), (b))
#endif

#if CLRT_PRECISION != CLRT_PRECISION_FP64
/* x^s for the specular term (0 < x <~ 1, s >= 0) as exp2(s * log2(x)) in
 * plain arithmetic: the library pow is an out-of-line call, and one call in
 * the work-item body stops PoCL from vectorizing across work-items. Error:
 * log2 has a few ulp relative error (the sqrt(2) range split avoids the
 * cancellation near x = 1), so x^s = 2^(s log2 x) carries an absolute error
 * below u * ln2 * max(y * |log2 y|) ~ 0.4 ulp of 1 on top of exp2's own few
 * ulp - far below one 8-bit level of the 0..255 colour. */
CLRT_INLINE lreal spec_log2(lreal x) {
  lint ix = AS_LINT(x);
  lint e = ((ix >> 23) & 0xff) - 127;
  lreal m = AS_LREAL((ix & 0x007fffff) | 0x3f800000); /* [1, 2) */
  lint big = m > 1.41421356f;
  m = big ? 0.5f * m : m;
  e = big ? e + 1 : e;
  /* ln(m) = 2 atanh(t) = 2 t (1 + t^2/3 + t^4/5 + ...), |t| <= 0.172 */
  lreal t = (m - 1.0f) / (m + 1.0f);
  lreal t2 = t * t;
  lreal p = fma(t2, fma(t2, fma(t2, fma(t2, 1.0f / 9, 1.0f / 7), 1.0f / 5), 1.0f / 3), 1.0f);
  return TO_LREAL(e) + (2.0f * t * p) * 1.44269504088896341f;
}
CLRT_INLINE lreal spec_exp2(lreal y) {
  y = fmax(y, -150.0f);
  lreal fi = TO_LREAL(TO_LINT(y)); /* truncation, then to the nearest integer */
  fi = (y - fi > 0.5f) ? fi + 1.0f : fi;
  fi = (fi - y > 0.5f) ? fi - 1.0f : fi;
  lreal g = (y - fi) * 0.693147180559945309f; /* |g| <= 0.5 ln 2 */
  /* e^g, Taylor to degree 7: truncation error < 6e-9 relative */
  lreal p = fma(g, 1.0f / 5040, 1.0f / 720);
  p = fma(g, p, 1.0f / 120);
  p = fma(g, p, 1.0f / 24);
  p = fma(g, p, 1.0f / 6);
  p = fma(g, p, 0.5f);
  p = fma(g, p, 1.0f);
  p = fma(g, p, 1.0f);
  lint i = TO_LINT(fi);
  lreal scale = AS_LREAL((clamp(i, -126, 127) + 127) << 23);
  return i < -126 ? (lreal)0.0f : p * scale;
}
CLRT_INLINE lreal spec_pow(lreal x, lreal s) { return spec_exp2(s * spec_log2(x)); }
#endif

/* ---- error-free transformations (robust mode) -------------------------- */
#if CLRT_PRECISION == CLRT_PRECISION_ROBUST
/* s + e == a + b exactly (Knuth's TwoSum; no reassociation is allowed by
 * OpenCL C unless -cl-unsafe-math-optimizations, which robust never uses).
 * Results through pointers: a returned pair would become a <2 x float>. */
CLRT_INLINE void two_sum(lreal a, lreal b, lreal* s_out, lreal* e_out) {
  lreal s = a + b;
  lreal bb = s - a;
  *e_out = (a - (s - bb)) + (b - bb);
  *s_out = s;
}
/* (hi, lo) sum of squares of a float-float 3-vector, as float-float. */
CLRT_INLINE void ff_norm2(const vec3* h, const vec3* l, lreal* hi, lreal* lo) {
  lreal p0 = h->x * h->x, p1 = h->y * h->y, p2 = h->z * h->z;
  lreal e0 = fma(h->x, h->x, -p0) + 2.0f * h->x * l->x;
  lreal e1 = fma(h->y, h->y, -p1) + 2.0f * h->y * l->y;
  lreal e2 = fma(h->z, h->z, -p2) + 2.0f * h->z * l->z;
  lreal s, se, t, te;
  two_sum(p0, p1, &s, &se);
  two_sum(s, p2, &t, &te);
  *hi = t;
  *lo = se + te + e0 + e1 + e2;
}
#endif

#endif /* CLRT_MATH_H */
