// layers.hpp - the AOV layers a frame can carry besides its colour (render
// --aov, the Python module's aovs=): what each holds at a pixel, their names
// on the command line and as EXR channels (docs/guide/images.md, "Layers").
//
// Every layer describes the first hit of one camera ray per pixel, the ray
// through the pixel's centre (the canvas point (x, y): the ray of spp 1),
// whatever the supersampling or subsampling: a layer does not average
// samples (a mean depth or normal across a silhouette is no surface's).
//   depth   Z: distance from the camera to the first hit along that ray
//           (t |D|, in scene units); +inf where it hits nothing
//   normal  N.X, N.Y, N.Z: the unit shading normal there, in world space
//           (outward for spheres; planes and triangles turned against the
//           ray, as shading sees them); 0, 0, 0 where it hits nothing
//   albedo  albedo.R, .G, .B: the hit primitive's colour / 255; 0 on a miss
//   id      the primitive hit: spheres 0..S-1, then planes, then triangles
//           (compare's numbering); -1 on a miss. Stored as float in the file,
//           exact up to kMaxLayerIds primitives.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

namespace clrt {

// Bits of FrameContents::layers.
enum LayerBit : unsigned {
  kLayerDepth = 1u << 0,
  kLayerNormal = 1u << 1,
  kLayerAlbedo = 1u << 2,
  kLayerId = 1u << 3,
};
constexpr unsigned kAllLayers = kLayerDepth | kLayerNormal | kLayerAlbedo | kLayerId;

// Integers a float holds exactly: the id layer refuses scenes with more
// primitives (2^24).
constexpr long long kMaxLayerIds = 1LL << 24;

// A frame's layers, row 0 at the top; each buffer empty unless asked for.
struct FrameLayers {
  int width = 0, height = 0;
  unsigned layers = 0;         // kLayer* bits
  std::vector<float> depth;    // kLayerDepth: width*height
  std::vector<float> normal;   // kLayerNormal: width*height*3
  std::vector<float> albedo;   // kLayerAlbedo: width*height*3
  std::vector<int32_t> id;     // kLayerId: width*height

  FrameLayers() = default;
  // Sized for `layers`, every pixel a miss.
  FrameLayers(int w, int h, unsigned layers);
  size_t pixels() const { return size_t(width) * height; }
  bool holds(int w, int h, unsigned layers) const;
};

// "depth", "normal", "albedo", "id", in that order.
const std::vector<std::string>& layer_names();
// The bit of a layer name; 0 for none.
unsigned layer_bit(const std::string& name);
// "depth,normal,albedo,id" (any subset, any order, each once) into bits;
// UserError naming an unknown name (with the known ones), a repeated one or
// an empty list (the message without the option's name: callers add
// "--aov: " or "aovs: ").
unsigned parse_layers(const std::string& list);
// The names of `layers`' bits, comma-separated, in layer_names() order.
std::string layer_list(unsigned layers);
// The file's channel names for `layers`, after R, G, B, A: Z, N.X, N.Y, N.Z,
// albedo.R, albedo.G, albedo.B, id (the ones asked for).
std::vector<std::string> layer_channels(unsigned layers);

}  // namespace clrt
