// eval_wire.cpp - images and evaluation rows as bytes, field by field.
#include "dist/eval_wire.hpp"

#include "util/error.hpp"

namespace clrt::dist {

// A tripwire for "every field": these structs' sizes on the platform CI
// builds (x86-64, libstdc++). A new field changes its struct's size and
// stops the build here: write it below (put_* and get_*) and in
// tests/dist/test_grid.cpp's round trip, then update the size.
#if defined(__x86_64__) && defined(__GLIBCXX__)
static_assert(sizeof(Stats) == 48, "Stats changed: update put_stats/get_stats");
static_assert(sizeof(Comparison) == 120, "Comparison changed: update put_comparison/get_comparison");
static_assert(sizeof(Image) == 136, "Image changed: update put_image/get_image");
static_assert(sizeof(RayCounts) == 40, "RayCounts changed: update put_bench/get_bench");
static_assert(sizeof(PeakFlops) == 104, "PeakFlops changed: update put_bench/get_bench");
static_assert(sizeof(BenchResult) == 1328, "BenchResult changed: update put_bench/get_bench");
static_assert(sizeof(SweepRow) == 1672, "SweepRow changed: update encode_sweep_row/decode_sweep_row");
static_assert(sizeof(AccuracyRow) == 264, "AccuracyRow changed: update encode_accuracy_row/decode_accuracy_row");
#endif

namespace {

// A vector of plain values: its length, then its bytes (none when empty:
// an empty vector's data() may be null, which memcpy must not get).
template <class T>
void put_vector(Writer& w, const std::vector<T>& v) {
  w.put<uint64_t>(v.size());
  if (!v.empty()) w.put_raw(v.data(), v.size() * sizeof(T));
}
template <class T>
std::vector<T> get_vector(Reader& r) {
  std::vector<T> v(size_t(r.get_count(sizeof(T))));
  if (!v.empty()) r.get_raw(v.data(), v.size() * sizeof(T));
  return v;
}

void put_rays(Writer& w, const RayCounts& c) {
  w.put(c.primary), w.put(c.shadow), w.put(c.reflection), w.put(c.sphere_tests), w.put(c.refraction);
}
RayCounts get_rays(Reader& r) {
  RayCounts c;
  c.primary = r.get<uint64_t>(), c.shadow = r.get<uint64_t>(), c.reflection = r.get<uint64_t>();
  c.sphere_tests = r.get<uint64_t>(), c.refraction = r.get<uint64_t>();
  return c;
}

// DeviceShare: every field as of render/band_scheduler.hpp (no size
// tripwire: that header is another layer's and changes on its own).
void put_share(Writer& w, const DeviceShare& s) {
  w.put_text(s.device);
  w.put<int32_t>(s.tiles), w.put<int64_t>(s.rows), w.put(s.kernel_ms), w.put<int32_t>(s.host_timed_launches);
  w.put(s.busy_ms), w.put(s.max_launch_ms);
}
DeviceShare get_share(Reader& r) {
  DeviceShare s;
  s.device = r.get_text();
  s.tiles = r.get<int32_t>(), s.rows = r.get<int64_t>(), s.kernel_ms = r.get<double>();
  s.host_timed_launches = r.get<int32_t>();
  s.busy_ms = r.get<double>(), s.max_launch_ms = r.get<double>();
  return s;
}

void put_peak(Writer& w, const PeakFlops& p) {
  w.put<uint8_t>(p.measured), w.put(p.gflops), put_stats(w, p.launch_ms), w.put<uint8_t>(p.from_events);
  w.put_text(p.note);
}
PeakFlops get_peak(Reader& r) {
  PeakFlops p;
  p.measured = r.get<uint8_t>() != 0, p.gflops = r.get<double>(), p.launch_ms = get_stats(r);
  p.from_events = r.get<uint8_t>() != 0;
  p.note = r.get_text();
  return p;
}

Subsample get_subsample(Reader& r) {
  const int32_t v = r.get<int32_t>();
  if (v < int32_t(Subsample::Off) || v > int32_t(Subsample::Interpolate))
    throw DeviceError("MPI: a result with a bad subsampling mode");
  return Subsample(v);
}

}  // namespace

void expect_done(const Reader& r, const char* what) {
  if (!r.done()) throw DeviceError(std::string("MPI: ") + what + " message with bytes left over");
}

namespace {

// A value as a message of its own: written by `put`; read by `get`, and then
// nothing may be left (`what` names it in the error).
template <class T>
Bytes encode_whole(void (*put)(Writer&, const T&), const T& value) {
  Writer w;
  put(w, value);
  return std::move(w.bytes);
}

template <class T>
T decode_whole(T (*get)(Reader&), const Bytes& b, const char* what) {
  Reader r(b);
  T value = get(r);
  expect_done(r, what);
  return value;
}

}  // namespace

void put_image(Writer& w, const Image& img) {
  w.put<int32_t>(img.width), w.put<int32_t>(img.height);
  w.put<int32_t>(int32_t(img.contents.pixels)), w.put<uint8_t>(img.contents.classes);
  // Each buffer with its length: an image's buffers are empty or sized for
  // its contents, and a default Image() holds none.
  put_vector(w, img.rgb), put_vector(w, img.rgba8), put_vector(w, img.unit);
  put_vector(w, img.hit), put_vector(w, img.shadowed);
}

Image get_image(Reader& r) {
  Image img;
  img.width = r.get<int32_t>(), img.height = r.get<int32_t>();
  const int32_t pixels = r.get<int32_t>();
  if (img.width < 0 || img.height < 0 ||
      (pixels != int32_t(PixelFormat::Float) && pixels != int32_t(PixelFormat::Rgba8) &&
       pixels != int32_t(PixelFormat::Unit)))
    throw DeviceError("MPI: an image message with a bad size or format");
  img.contents.pixels = PixelFormat(pixels);
  img.contents.classes = r.get<uint8_t>() != 0;
  img.rgb = get_vector<double>(r), img.rgba8 = get_vector<uint8_t>(r), img.unit = get_vector<float>(r);
  img.hit = get_vector<int32_t>(r), img.shadowed = get_vector<int32_t>(r);
  // Every buffer empty or sized for the image (compare_images reads them
  // by the size).
  const size_t n = size_t(img.width) * size_t(img.height);
  const auto sized = [n](size_t got, size_t per_pixel) { return got == 0 || got == n * per_pixel; };
  if (!sized(img.rgb.size(), 3) || !sized(img.rgba8.size(), 4) || !sized(img.unit.size(), 3) ||
      !sized(img.hit.size(), 1) || !sized(img.shadowed.size(), 1))
    throw DeviceError("MPI: an image message whose buffers do not fit its size");
  return img;
}

void put_stats(Writer& w, const Stats& s) {
  w.put<int32_t>(s.n), w.put(s.median), w.put(s.mean), w.put(s.sd), w.put(s.min), w.put(s.max);
}

Stats get_stats(Reader& r) {
  Stats s;
  s.n = r.get<int32_t>();
  s.median = r.get<double>(), s.mean = r.get<double>(), s.sd = r.get<double>();
  s.min = r.get<double>(), s.max = r.get<double>();
  return s;
}

void put_comparison(Writer& w, const Comparison& c) {
  w.put<uint64_t>(c.pixels), w.put<uint64_t>(c.differ), w.put<uint64_t>(c.off_by_gt1);
  w.put<int32_t>(c.max_abs_8bit), w.put(c.rmse_8bit), w.put(c.psnr_8bit);
  w.put(c.max_abs_float), w.put(c.rmse_float), w.put(c.psnr_float);
  w.put<uint64_t>(c.nan_inf), w.put<uint64_t>(c.nan_inf_reference);
  w.put<uint64_t>(c.hit_flips), w.put<uint64_t>(c.shadow_flips);
  w.put<int32_t>(c.worst_x), w.put<int32_t>(c.worst_y);
  w.put_raw(c.worst_test, sizeof c.worst_test), w.put_raw(c.worst_reference, sizeof c.worst_reference);
}

Comparison get_comparison(Reader& r) {
  Comparison c;
  c.pixels = size_t(r.get<uint64_t>()), c.differ = size_t(r.get<uint64_t>());
  c.off_by_gt1 = size_t(r.get<uint64_t>());
  c.max_abs_8bit = r.get<int32_t>(), c.rmse_8bit = r.get<double>(), c.psnr_8bit = r.get<double>();
  c.max_abs_float = r.get<double>(), c.rmse_float = r.get<double>(), c.psnr_float = r.get<double>();
  c.nan_inf = size_t(r.get<uint64_t>()), c.nan_inf_reference = size_t(r.get<uint64_t>());
  c.hit_flips = size_t(r.get<uint64_t>()), c.shadow_flips = size_t(r.get<uint64_t>());
  c.worst_x = r.get<int32_t>(), c.worst_y = r.get<int32_t>();
  r.get_raw(c.worst_test, sizeof c.worst_test), r.get_raw(c.worst_reference, sizeof c.worst_reference);
  return c;
}

void put_bench(Writer& w, const BenchResult& b) {
  w.put_text(b.device), w.put_text(b.options);
  w.put<int32_t>(b.width), w.put<int32_t>(b.height), w.put<int32_t>(b.depth), w.put<int32_t>(b.spp);
  w.put<int32_t>(b.repeat), w.put<int32_t>(int32_t(b.subsample)), w.put<uint8_t>(b.rgba8);
  w.put_text(b.tracers_not_run), w.put_text(b.omp_not_run);
  put_stats(w, b.build_cold), put_stats(w, b.build_warm), w.put<uint8_t>(b.build_warm_cached);
  put_stats(w, b.upload);
  w.put(b.end_to_end_ms), w.put(b.first_launch_ms);
  w.put<uint8_t>(b.bvh), w.put(b.bvh_build_ms), w.put<uint64_t>(b.bvh_bytes), w.put<int32_t>(b.bvh_depth);
  put_vector(w, b.kernel_ms);
  put_stats(w, b.kernel);
  w.put<int32_t>(b.launches), w.put<int32_t>(b.host_timed_launches);
  put_stats(w, b.frame), put_stats(w, b.download);
  w.put<uint64_t>(b.shares.size());
  for (const DeviceShare& s : b.shares) put_share(w, s);
  put_rays(w, b.rays);
  w.put(b.mrays_per_s), w.put(b.ns_per_sphere_test), w.put(b.gflops);
  w.put<uint64_t>(b.peaks.size());
  for (const PeakFlops& p : b.peaks) put_peak(w, p);
  w.put(b.peak_gflops);
  put_stats(w, b.reference), w.put(b.speedup_vs_reference);
  put_stats(w, b.omp), w.put<int32_t>(b.omp_threads);
  put_stats(w, b.speedup_vs_omp), put_stats(w, b.kernel_speedup_vs_omp);
  put_stats(w, b.embree), put_stats(w, b.embree_build), w.put(b.embree_build_ms), w.put<int32_t>(b.embree_threads);
  put_stats(w, b.speedup_vs_embree);
  w.put(b.embree_vs_omp_differ), w.put<int32_t>(b.embree_vs_omp_max_levels);
  w.put(b.embree_vs_clrt_differ), w.put<int32_t>(b.embree_vs_clrt_max_levels);
  put_image(w, b.image), put_image(w, b.reference_image);
}

BenchResult get_bench(Reader& r) {
  BenchResult b;
  b.device = r.get_text(), b.options = r.get_text();
  b.width = r.get<int32_t>(), b.height = r.get<int32_t>(), b.depth = r.get<int32_t>(), b.spp = r.get<int32_t>();
  b.repeat = r.get<int32_t>(), b.subsample = get_subsample(r), b.rgba8 = r.get<uint8_t>() != 0;
  b.tracers_not_run = r.get_text(), b.omp_not_run = r.get_text();
  b.build_cold = get_stats(r), b.build_warm = get_stats(r), b.build_warm_cached = r.get<uint8_t>() != 0;
  b.upload = get_stats(r);
  b.end_to_end_ms = r.get<double>(), b.first_launch_ms = r.get<double>();
  b.bvh = r.get<uint8_t>() != 0, b.bvh_build_ms = r.get<double>(), b.bvh_bytes = size_t(r.get<uint64_t>());
  b.bvh_depth = r.get<int32_t>();
  b.kernel_ms = get_vector<double>(r);
  b.kernel = get_stats(r);
  b.launches = r.get<int32_t>(), b.host_timed_launches = r.get<int32_t>();
  b.frame = get_stats(r), b.download = get_stats(r);
  b.shares.resize(size_t(r.get_count(1)));
  for (DeviceShare& s : b.shares) s = get_share(r);
  b.rays = get_rays(r);
  b.mrays_per_s = r.get<double>(), b.ns_per_sphere_test = r.get<double>(), b.gflops = r.get<double>();
  b.peaks.resize(size_t(r.get_count(1)));
  for (PeakFlops& p : b.peaks) p = get_peak(r);
  b.peak_gflops = r.get<double>();
  b.reference = get_stats(r), b.speedup_vs_reference = r.get<double>();
  b.omp = get_stats(r), b.omp_threads = r.get<int32_t>();
  b.speedup_vs_omp = get_stats(r), b.kernel_speedup_vs_omp = get_stats(r);
  b.embree = get_stats(r), b.embree_build = get_stats(r), b.embree_build_ms = r.get<double>();
  b.embree_threads = r.get<int32_t>();
  b.speedup_vs_embree = get_stats(r);
  b.embree_vs_omp_differ = r.get<double>(), b.embree_vs_omp_max_levels = r.get<int32_t>();
  b.embree_vs_clrt_differ = r.get<double>(), b.embree_vs_clrt_max_levels = r.get<int32_t>();
  b.image = get_image(r), b.reference_image = get_image(r);
  return b;
}

void put_sweep_row(Writer& w, const SweepRow& row) {
  w.put_text(row.device), w.put<int32_t>(row.device_index), w.put_text(row.device_pd), w.put<int32_t>(row.depth);
  put_bench(w, row.bench);
  put_comparison(w, row.error), put_comparison(w, row.change);
  w.put(row.kernel_ms_delta), w.put(row.reference_ms), w.put(row.speedup_vs_reference);
}

SweepRow get_sweep_row(Reader& r) {
  SweepRow row;
  row.device = r.get_text(), row.device_index = r.get<int32_t>(), row.device_pd = r.get_text();
  row.depth = r.get<int32_t>();
  row.bench = get_bench(r);
  row.error = get_comparison(r), row.change = get_comparison(r);
  row.kernel_ms_delta = r.get<double>(), row.reference_ms = r.get<double>();
  row.speedup_vs_reference = r.get<double>();
  return row;
}

void put_accuracy_row(Writer& w, const AccuracyRow& row) {
  w.put_text(row.scene), w.put_text(row.variant), w.put<int32_t>(row.depth), w.put<uint8_t>(row.supported);
  w.put_text(row.note);
  put_vector(w, row.kernel_ms);
  w.put(row.median_ms), w.put<int32_t>(row.launches), w.put<int32_t>(row.host_timed_launches);
  put_comparison(w, row.error);
}

AccuracyRow get_accuracy_row(Reader& r) {
  AccuracyRow row;
  row.scene = r.get_text(), row.variant = r.get_text(), row.depth = r.get<int32_t>();
  row.supported = r.get<uint8_t>() != 0;
  row.note = r.get_text();
  row.kernel_ms = get_vector<double>(r);
  row.median_ms = r.get<double>(), row.launches = r.get<int32_t>(), row.host_timed_launches = r.get<int32_t>();
  row.error = get_comparison(r);
  return row;
}

// The messages of a value each (eval_wire.hpp): a type's encode_ and
// decode_ are its put_ and get_ through encode_whole() and decode_whole().
#define CLRT_WHOLE_MESSAGE(Type, name, what)  \
  Bytes encode_##name(const Type& value) {    \
    return encode_whole(put_##name, value);   \
  }                                           \
  Type decode_##name(const Bytes& b) {        \
    return decode_whole(get_##name, b, what); \
  }
CLRT_WHOLE_MESSAGE(Image, image, "an image")
CLRT_WHOLE_MESSAGE(SweepRow, sweep_row, "a sweep row")
CLRT_WHOLE_MESSAGE(AccuracyRow, accuracy_row, "an accuracy row")
#undef CLRT_WHOLE_MESSAGE

}  // namespace clrt::dist
