// layers.cpp - AOV layer names and channel names.
#include "image/layers.hpp"

#include <limits>

#include "util/error.hpp"

namespace clrt {

FrameLayers::FrameLayers(int w, int h, unsigned asked) : width(w), height(h), layers(asked) {
  const size_t n = pixels();
  if (layers & kLayerDepth) depth.assign(n, std::numeric_limits<float>::infinity());
  if (layers & kLayerNormal) normal.assign(n * 3, 0.0f);
  if (layers & kLayerAlbedo) albedo.assign(n * 3, 0.0f);
  if (layers & kLayerId) id.assign(n, -1);
}

bool FrameLayers::holds(int w, int h, unsigned asked) const {
  const size_t n = size_t(w) * h;
  return width == w && height == h && layers == asked && depth.size() == (asked & kLayerDepth ? n : 0) &&
         normal.size() == (asked & kLayerNormal ? n * 3 : 0) && albedo.size() == (asked & kLayerAlbedo ? n * 3 : 0) &&
         id.size() == (asked & kLayerId ? n : 0);
}

const std::vector<std::string>& layer_names() {
  static const std::vector<std::string> names{"depth", "normal", "albedo", "id"};
  return names;
}

unsigned layer_bit(const std::string& name) {
  const auto& names = layer_names();
  for (size_t i = 0; i < names.size(); ++i)
    if (names[i] == name) return 1u << i;
  return 0;
}

unsigned parse_layers(const std::string& list) {
  unsigned layers = 0;
  size_t begin = 0;
  for (;;) {
    const size_t comma = list.find(',', begin);
    const std::string name = list.substr(begin, comma == std::string::npos ? std::string::npos : comma - begin);
    const unsigned bit = layer_bit(name);
    if (bit == 0 && list.empty()) throw UserError("no layer named (the layers: depth, normal, albedo, id)");
    if (bit == 0)
      throw UserError("unknown layer \"" + name + "\" (the layers: depth, normal, albedo, id, comma-separated)");
    if (layers & bit) throw UserError("layer \"" + name + "\" is listed twice");
    layers |= bit;
    if (comma == std::string::npos) return layers;
    begin = comma + 1;
  }
}

std::string layer_list(unsigned layers) {
  std::string out;
  for (const std::string& name : layer_names())
    if (layers & layer_bit(name)) out += (out.empty() ? "" : ",") + name;
  return out;
}

std::vector<std::string> layer_channels(unsigned layers) {
  std::vector<std::string> channels;
  if (layers & kLayerDepth) channels.push_back("Z");
  if (layers & kLayerNormal) channels.insert(channels.end(), {"N.X", "N.Y", "N.Z"});
  if (layers & kLayerAlbedo) channels.insert(channels.end(), {"albedo.R", "albedo.G", "albedo.B"});
  if (layers & kLayerId) channels.push_back("id");
  return channels;
}

}  // namespace clrt
