#pragma once
// The stage: a tree of prims addressed by absolute paths, plus stage-wide
// metadata. Prims are owned here; pointers to them stay valid until the prim
// is removed.
#include <functional>
#include <memory>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "stage/prim.h"
#include "stage/stage_animation.h"

namespace sdg {

struct StageMetadata {
  double timeCodesPerSecond = 60.0;
  double metersPerUnit = 1.0;
  std::string upAxis = "Z";
  // render.subdivision_level (0 for none), copied here once the settings are
  // final (applyRenderSettingsToStage): every reader of a prim's geometry
  // (renderers, colliders, BOP models) refines subdivision surfaces alike.
  int subdivisionLevel = 2;
  bool operator==(const StageMetadata&) const = default;
};

class Stage {
 public:
  Stage();
  Stage(const Stage& other);
  Stage& operator=(const Stage& other);
  Stage(Stage&&) noexcept = default;
  Stage& operator=(Stage&&) noexcept = default;

  StageMetadata& metadata() { return metadata_; }
  const StageMetadata& metadata() const { return metadata_; }
  // The stage's own animation (a USD stage's time samples), played by the
  // timeline; copied with the stage, not part of its state (operator==).
  StageAnimation& animation() { return animation_; }
  const StageAnimation& animation() const { return animation_; }

  // Defines a prim. The path must be valid, free, and its parent must exist
  // (the loader reports user mistakes before calling this; here they are
  // programming errors and throw std::logic_error).
  Prim& definePrim(const std::string& path, PrimType type);
  // Removes the prim and everything below it. False when it does not exist.
  bool removePrim(std::string_view path);

  Prim* find(std::string_view path);
  const Prim* find(std::string_view path) const;
  Prim& pseudoRoot() { return *root_; }
  const Prim& pseudoRoot() const { return *root_; }
  size_t primCount() const { return byPath_.size() - 1; }

  // Pre-order depth-first visit of every prim below (and including) `start`;
  // children in their authored order. Without `start`: the whole stage.
  void traverse(const std::function<void(const Prim&)>& visit) const;
  void traverse(const std::function<void(Prim&)>& visit);
  std::vector<Prim*> subtree(Prim& start);

  // local-to-world (column-vector convention).
  Matrix4d worldMatrix(const Prim& prim) const;

  // Deep comparison of structure, values and metadata.
  bool operator==(const Stage& other) const;

 private:
  StageMetadata metadata_;
  StageAnimation animation_;
  std::unique_ptr<Prim> root_;
  std::unordered_map<std::string, std::unique_ptr<Prim>> owned_;
  std::unordered_map<std::string_view, Prim*> byPath_;
};

}  // namespace sdg
