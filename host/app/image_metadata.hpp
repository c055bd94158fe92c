// image_metadata.hpp - what an image clrt writes says about itself
// (docs/guide/images.md): renders and compare's --diff images alike.
#pragma once
#include <string>

#include "app/options.hpp"
#include "image/image_file.hpp"

namespace clrt {

// How the pixels were sampled, in words: "spp 1", "spp 4, adaptive 8",
// "spp 1, subsample shade".
std::string sampling_words(const Sampling& s);

// The attributes of an image made from `o`'s scene and settings at `depth`:
// `what` opens ImageDescription ("clrt render", "clrt compare --diff ..."),
// `engine` and `device` say what rendered it.
ImageMetadata image_metadata(const std::string& what, const RenderOptions& o, int depth, const std::string& engine,
                             const std::string& device);

}  // namespace clrt
