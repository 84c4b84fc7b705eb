#pragma once
// Triangle meshes on the CPU: what the asset loaders and the primitive
// generators produce and the renderer uploads once.
#include <cstdint>
#include <string>
#include <vector>

#include "stage/math_types.h"

namespace sdg {

// A range of indices drawn with one material of the file (or the prim's).
struct MeshPart {
  uint32_t firstIndex = 0;
  uint32_t indexCount = 0;
  bool hasMaterial = false;  // the file gave a material for this part
  Vec3f baseColor{0.5f, 0.5f, 0.5f};
  std::string texture;  // resolved path, "" for none
  float roughness = 0.5f;
  float metallic = 0.0f;
};

struct MeshData {
  std::vector<Vec3f> positions;
  std::vector<Vec3f> normals;
  std::vector<Eigen::Vector2f> uvs;
  std::vector<uint32_t> indices;  // triangles
  std::vector<MeshPart> parts;
  Eigen::AlignedBox3f bounds;

  size_t triangleCount() const { return indices.size() / 3; }
  // Recomputes `bounds` from the positions.
  void updateBounds();
};

}  // namespace sdg
