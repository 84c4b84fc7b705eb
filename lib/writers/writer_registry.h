#pragma once
// The registry of writers: every `writer.type` a scene may name and the
// factory that makes it. The run makes its writers here, in one place, and
// derives what to render from their needs; an unknown type is a located
// scene error, never a fallback to another writer.
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "assets/asset_resolver.h"
#include "assets/labelled_mesh.h"
#include "scene_io/scene.h"
#include "writers/writer.h"

namespace sdg {

// What every writer may use when it is made.
struct WriterSetup {
  std::vector<std::string> productNames;
  int64_t seed = 0;
  int width = 0, height = 0;
  const Stage* stage = nullptr;            // as loaded (BOP's object models)
  const AssetResolver* assets = nullptr;   // meshes of the models
  std::vector<LabelledMesh> spawnedMeshes; // what behaviors add during the run (BOP's models of those objects)
};

// What finishing the dataset needs from its writers (recorded in run.json,
// so `merge` finishes a sharded run without the scene).
struct DatasetParts {
  std::string cocoFile;  // "" without a COCO writer
  std::string cocoTaxonomy;
  std::string bopSplit;  // "" without a BOP writer
};

struct WriterSet {
  std::vector<std::unique_ptr<Writer>> writers;  // registry order: a frame's files are listed in it
  std::vector<std::string> semanticTypes;        // the taxonomies entities are made from
  AnnotatorNeeds needs;                          // the union of the writers'
  DatasetParts parts;
};

// Makes the scene's writers. A COCO writer alone gets a BasicWriter that
// writes only rgb (its images). SceneError for an unknown type or bad options.
WriterSet makeWriters(const std::vector<WriterConfig>& configs, const WriterSetup& setup, const SourceLoc& sceneLoc);

// The writer types the registry can make, in its order.
std::vector<std::string_view> registeredWriterTypes();

}  // namespace sdg
