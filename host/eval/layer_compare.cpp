// layer_compare.cpp - AOV layers against the reference's.
#include "eval/layer_compare.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "image/image.hpp"

namespace clrt {
namespace {

// Whether the reference's id at (x, y) differs from a 4-neighbour's.
bool on_silhouette(const FrameLayers& ref, int x, int y) {
  const int32_t id = ref.id[size_t(y) * ref.width + x];
  const auto differs = [&](int nx, int ny) {
    return nx >= 0 && ny >= 0 && nx < ref.width && ny < ref.height && ref.id[size_t(ny) * ref.width + nx] != id;
  };
  return differs(x - 1, y) || differs(x + 1, y) || differs(x, y - 1) || differs(x, y + 1);
}

// A tolerance as text ("1e-04").
std::string number(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", v);
  return text;
}

}  // namespace

LayerComparison compare_layers(const FrameLayers& test, const FrameLayers& ref, const std::vector<float>* incidence) {
  if (test.width != ref.width || test.height != ref.height)
    throw std::invalid_argument("compare_layers: size mismatch");
  if (!(ref.layers & kLayerId) || (ref.layers & test.layers) != test.layers)
    throw std::invalid_argument("compare_layers: the reference needs the test's layers and the id");
  if (incidence && incidence->size() != ref.pixels()) throw std::invalid_argument("compare_layers: incidence size");
  LayerComparison c;
  c.layers = test.layers;
  c.pixels = ref.pixels();
  const bool test_ids = (test.layers & kLayerId) != 0;
  c.ids_compared = test_ids;
  for (int y = 0; y < ref.height; ++y)
    for (int x = 0; x < ref.width; ++x) {
      const size_t p = size_t(y) * ref.width + x;
      const bool silhouette = on_silhouette(ref, x, y);
      c.silhouette_pixels += silhouette;
      if (test_ids && test.id[p] != ref.id[p]) {
        ++c.id_differ;
        ++(silhouette ? c.id_differ_silhouette : c.id_differ_inside);
        continue;
      }
      if (ref.id[p] < 0) {
        // a miss: +inf, zeros
        if (test.layers & kLayerDepth) c.non_finite += !std::isinf(test.depth[p]) || test.depth[p] < 0;
        continue;
      }
      ++c.same_hit;
      const double cosine = incidence ? double((*incidence)[p]) : 1.0;
      bool bad = false;
      if (test.layers & kLayerDepth) {
        const double z = test.depth[p], z_ref = ref.depth[p];
        bad |= !std::isfinite(z);
        const double relative = std::isfinite(z) ? std::fabs(z - z_ref) * cosine / z_ref : HUGE_VAL;
        c.depth_max_relative = std::max(c.depth_max_relative, relative);
        c.depth_over += relative > kDepthRelative;
      }
      if (test.layers & kLayerNormal) {
        double worst = 0;
        for (int k = 0; k < 3; ++k) {
          const double n = test.normal[p * 3 + k];
          bad |= !std::isfinite(n);
          worst = std::max(worst, std::isfinite(n) ? std::fabs(n - ref.normal[p * 3 + k]) : HUGE_VAL);
        }
        c.normal_max_error = std::max(c.normal_max_error, worst * cosine);
        c.normal_over += worst * cosine > kNormalAbsolute;
      }
      if (test.layers & kLayerAlbedo) {
        bool differ = false;
        for (int k = 0; k < 3; ++k) {
          const double a = test.albedo[p * 3 + k];
          bad |= !std::isfinite(a);
          differ |= to_u8(255 * a) != to_u8(255 * double(ref.albedo[p * 3 + k]));
        }
        c.albedo_differ += differ;
      }
      c.non_finite += bad;
    }
  return c;
}

bool LayerComparison::pass() const {
  return failures().empty();
}

std::string LayerComparison::failures() const {
  std::string out;
  const auto add = [&out](const std::string& clause) { out += (out.empty() ? "" : "; ") + clause; };
  if (id_differ_inside > 0) add("id: " + std::to_string(id_differ_inside) + " pixels differ off the silhouettes");
  if ((layers & kLayerDepth) && depth_over > 0)
    add("depth: " + std::to_string(depth_over) + " pixels over the relative error (times cos) " + number(kDepthRelative));
  if ((layers & kLayerNormal) && normal_over > 0)
    add("normal: " + std::to_string(normal_over) + " pixels with a component off (times cos) by more than " +
        number(kNormalAbsolute));
  if ((layers & kLayerAlbedo) && albedo_differ > 0)
    add("albedo: " + std::to_string(albedo_differ) + " pixels differ at the 8-bit level");
  if (non_finite > 0) add(std::to_string(non_finite) + " pixels with a NaN, or a finite depth on a miss");
  return out;
}

}  // namespace clrt
