#pragma once
// The pixels a texture key names, for both renderers: an image embedded in
// a mesh file, or a file found through the scene's search roots. Errors
// name the prim (or light) that uses it.
#include <string>

#include "assets/asset_resolver.h"
#include "assets/image.h"
#include "assets/mesh_data.h"

namespace sdg {

// `embedded`: the image the key names when it is one of a mesh file's
// (null for a file).
ImageRgba8 decodeTextureImage(const std::string& key, const EmbeddedImage* embedded, const AssetResolver& assets,
                              TextureData data, const std::string& owner);

// A dome's lat-long map as linear RGBA floats.
ImageRgbaF loadDomeMap(const std::string& file, const AssetResolver& assets, const std::string& owner);

}  // namespace sdg
