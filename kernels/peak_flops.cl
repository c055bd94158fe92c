// peak_flops.cl - measures a device's single-precision multiply-add rate for
// `clrt bench` (host/peak_flops.cpp). Eight independent float16 chains of
// mad() per work-item: enough independent work to fill two FMA pipes of
// 4-cycle latency on a CPU, and plain scalar chains on a GPU. Each mad is
// counted as 2 FLOP; a = 0.9999, b = 0.001 keep every value near 10 (no
// denormals, no overflow), and the sum is stored so nothing is dead code.
__kernel void peak_flops(__global float* out, const float a, const float b, const int iterations) {
  const float seed = (float)(get_global_id(0) & 1023) * 1e-3f;
  float16 x0 = (float16)(seed), x1 = x0 + 1.0f, x2 = x0 + 2.0f, x3 = x0 + 3.0f;
  float16 x4 = x0 + 4.0f, x5 = x0 + 5.0f, x6 = x0 + 6.0f, x7 = x0 + 7.0f;
  for (int i = 0; i < iterations; ++i) {
    x0 = mad(x0, a, b);
    x1 = mad(x1, a, b);
    x2 = mad(x2, a, b);
    x3 = mad(x3, a, b);
    x4 = mad(x4, a, b);
    x5 = mad(x5, a, b);
    x6 = mad(x6, a, b);
    x7 = mad(x7, a, b);
  }
  const float16 s = ((x0 + x1) + (x2 + x3)) + ((x4 + x5) + (x6 + x7));
  out[get_global_id(0)] = s.s0 + s.s1 + s.s2 + s.s3 + s.s4 + s.s5 + s.s6 + s.s7 + s.s8 + s.s9 + s.sa + s.sb + s.sc +
                          s.sd + s.se + s.sf;
}
