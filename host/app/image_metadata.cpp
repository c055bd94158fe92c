// image_metadata.cpp - the attributes of every image clrt writes.
#include "app/image_metadata.hpp"

#include <cstdio>

#include "app/report_header.hpp"

#ifndef CLRT_VERSION
#define CLRT_VERSION "unknown"
#endif

namespace clrt {

std::string sampling_words(const Sampling& s) {
  std::string w = "spp " + std::to_string(s.spp);
  if (s.adaptive()) {
    char t[32];
    std::snprintf(t, sizeof t, "%g", s.adaptive_threshold);
    w += std::string(", adaptive ") + t;
  }
  if (s.subsample != Subsample::Off) w += ", subsample " + subsample_name(s.subsample);
  if (!s.ray_cut) w += ", no ray cut";
  return w;
}

ImageMetadata image_metadata(const std::string& what, const RenderOptions& o, int depth, const std::string& engine,
                             const std::string& device) {
  // (an image file's precision is not known)
  const std::string precision = engine == "opencl"      ? o.kernel.precision
                                : engine == "reference" ? "reference (scalar double)"
                                                        : "-";
  const std::string size = std::to_string(o.image.width) + "x" + std::to_string(o.image.height);
  const std::string sampling = sampling_words(o.image.sampling());
  std::string overridden;  // ", with -D a=1 -D b=2"
  for (const std::string& text : o.image.overrides) overridden += (overridden.empty() ? ", with -D " : " -D ") + text;
  ImageMetadata m = {
      {"Software", std::string("clrt ") + CLRT_VERSION},
      {"ImageDescription", what + " of " + o.scene_path + ": " + size + ", depth " + std::to_string(depth) +
                               ", precision " + precision + ", " + sampling + ", on " + device + overridden},
      {"clrt:version", CLRT_VERSION},
      {"clrt:scene", o.scene_path},
      {"clrt:width", std::to_string(o.image.width)},
      {"clrt:height", std::to_string(o.image.height)},
      {"clrt:depth", std::to_string(depth)},
      {"clrt:precision", precision},
      {"clrt:sampling", sampling},
      {"clrt:engine", engine},
      {"clrt:device", device},
  };
  // Only where -D was given: the scene is then not the file's alone.
  if (!o.image.overrides.empty()) m.push_back({"clrt:overrides", overrides_json(o.image.overrides).dump(-1, ' ', false, nlohmann::ordered_json::error_handler_t::replace)});
  return m;
}

}  // namespace clrt
