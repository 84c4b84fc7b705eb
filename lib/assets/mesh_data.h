#pragma once
// Triangle meshes on the CPU: what the asset loaders and the primitive
// generators produce and the renderer uploads once.
#include <compare>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "stage/math_types.h"

namespace sdg {

// The textures a material samples, each a texture key: a file path, or
// for an image embedded in a mesh file "embedded:" and a hash of its bytes
// (MeshData::embeddedImages). "" for none.
struct MaterialMaps {
  std::string baseColor;  // sRGB colour; its alpha is glTF's opacity
  std::string roughness;  // linear, red channel
  std::string metallic;   // linear, red channel
  std::string orm;        // linear: occlusion, roughness (green), metallic (blue); also glTF's metallicRoughness
  std::string normal;     // linear tangent-space normal map, +Y up (OpenGL and glTF convention)
  std::string opacity;    // linear, red channel
  auto operator<=>(const MaterialMaps&) const = default;
  bool any() const {
    return !baseColor.empty() || !roughness.empty() || !metallic.empty() || !orm.empty() || !normal.empty() ||
           !opacity.empty();
  }
};

// Where a cut-out's opacity comes from (none: opaque).
enum class OpacitySource : uint8_t { None, Constant, OpacityMap, BaseColorAlpha };

// A range of indices drawn with one material of the file (or the prim's).
struct MeshPart {
  uint32_t firstIndex = 0;
  uint32_t indexCount = 0;
  bool hasMaterial = false;  // the file gave a material for this part
  Vec3f baseColor{0.5f, 0.5f, 0.5f};
  MaterialMaps maps;     // files resolved against the mesh file's folder
  float roughness = 0.5f;  // glTF's factors: they multiply the maps' values
  float metallic = 0.0f;
  float normalScale = 1.0f;
  OpacitySource opacity = OpacitySource::None;  // glTF alphaMode MASK and BLEND
  float opacityConstant = 1.0f;  // multiplies the source's value (glTF: the base colour factor's alpha)
  float opacityCutoff = 0.5f;    // drawn where opacity >= the cut-off
  bool vertexColors = false;     // baseColor and opacity times MeshData::colors (a USD mesh's displayColor)
};

// An image stored inside a mesh file (glTF, FBX): its encoded bytes (PNG,
// JPEG, ...), or for assimp's uncompressed form raw BGRA texels.
struct EmbeddedImage {
  std::string key;   // "embedded:<hash of the bytes>"
  std::string name;  // "file.glb[*0]", for messages
  std::shared_ptr<const std::vector<uint8_t>> bytes;
  uint32_t rawWidth = 0, rawHeight = 0;  // non-zero: `bytes` are raw BGRA texels, rows top first
};

struct MeshData {
  std::vector<Vec3f> positions;
  std::vector<Vec3f> normals;
  std::vector<Eigen::Vector2f> uvs;
  // A colour and opacity per vertex (USD's non-constant displayColor and
  // displayOpacity; white and 1 where only the other is given); empty for
  // the meshes that have none, so they upload and trace no colour at all.
  std::vector<Eigen::Vector4f> colors;
  std::vector<uint32_t> indices;  // triangles
  std::vector<MeshPart> parts;
  std::vector<EmbeddedImage> embeddedImages;  // those the parts name
  Eigen::AlignedBox3f bounds;

  size_t triangleCount() const { return indices.size() / 3; }
  // Recomputes `bounds` from the positions.
  void updateBounds();
};

}  // namespace sdg
