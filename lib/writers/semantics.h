#pragma once
// Semantic entities of a frame, as Replicator's annotators define them: a
// labelled prim and its unlabelled descendants form one entity (one
// instance); labels are inherited from ancestors (ancestor first, labels of
// one taxonomy joined with ","); geometry with no labelled ancestor is
// UNLABELLED and empty pixels are BACKGROUND. Only taxonomies in
// `semanticTypes` count.
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "render/render_list.h"
#include "stage/stage.h"

namespace sdg {

inline constexpr uint32_t kBackgroundId = 0;
inline constexpr uint32_t kUnlabelledId = 1;

using LabelSet = std::map<std::string, std::string>;  // taxonomy -> "a,b"

struct SemanticEntity {
  std::string primPath;    // the labelled prim (the entity's root)
  LabelSet labels;
  uint32_t semanticId = 0; // >= 2; entities with equal labels share it
  uint32_t instanceId = 0; // >= 2, one per entity
  std::vector<size_t> items;  // indices into RenderList::items
  Matrix4d worldFromRoot = Matrix4d::Identity();  // the labelled prim's, for 3D boxes
};

struct FrameSemantics {
  std::vector<SemanticEntity> entities;          // stage order
  std::vector<LabelSet> semanticLabels;          // by semantic id (0 BACKGROUND, 1 UNLABELLED)
  // Render-pass instance id (RenderItem::instanceId) -> entity index + 1; 0 = unlabelled.
  std::vector<uint32_t> entityOfRenderId;
};

FrameSemantics computeSemantics(const Stage& stage, const RenderList& list,
                                const std::vector<std::string>& semanticTypes);

}  // namespace sdg
