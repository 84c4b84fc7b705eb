#pragma once
// BOP's object models: for every object of the writer's `objects` list, the
// geometry of the first entity with that label in the stage as loaded, in
// the entity root's frame with its scale applied, in millimetres
// (models/obj_XXXXXX.ply), and models_info.json (diameter, extents and the
// symmetries the scene declares), as the BOP toolkit reads them.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "assets/asset_resolver.h"
#include "assets/labelled_mesh.h"
#include "render/render_list.h"
#include "stage/stage.h"
#include "writers/output_files.h"
#include "writers/semantics.h"

namespace sdg {

// A rigid pose and the scale it was split from (world = R * diag(scale) * local + t).
struct ScaledPose {
  Matrix3d rotation = Matrix3d::Identity();
  Vec3d translation = Vec3d::Zero();
  Vec3d scale = Vec3d::Ones();
};
ScaledPose splitScale(const Matrix4d& m);

// One declared symmetry, in BOP's terms (the model frame, millimetres).
struct BopSymmetry {
  bool continuous = false;
  Vec3d axis = Vec3d::UnitZ();
  double angleDegrees = 0;  // discrete: the rotation about `axis` that maps the object onto itself
};

struct BopObject {
  uint32_t id = 0;          // obj_id: position in `objects` + 1
  std::string label;
  std::string modelPrim;    // the entity its model was taken from ("" when none was in the stage)
  Vec3d scale = Vec3d::Ones();  // the model entity's scale, which every instance must share
  std::vector<Vec3f> positions, normals;  // millimetres, model frame
  std::vector<uint32_t> indices;
  std::vector<BopSymmetry> symmetries;
};

// Collects the models from the stage as loaded; RunError for an unreadable mesh.
std::vector<BopObject> collectBopObjects(const Stage& stage, const std::vector<std::string>& labels,
                                         const std::string& taxonomy, const std::vector<std::string>& semanticTypes,
                                         const AssetResolver& assets);

// The model of an object no prim of the stage as loaded carries, from the
// mesh files behaviors spawn with its label (`spawned`), each placed alone
// as the behavior places it (unscaled, in the stage's units). Returns the
// problem when none spawns it or when its files differ in shape (a BOP
// object has one model); RunError for an unreadable mesh.
std::optional<std::string> addSpawnedModel(BopObject& object, const std::string& taxonomy,
                                           const std::vector<LabelledMesh>& spawned, const Stage& loaded,
                                           const std::vector<std::string>& semanticTypes, const AssetResolver& assets);

// models/obj_XXXXXX.ply (binary little-endian: x y z nx ny nz, triangles)
// and models/models_info.json.
std::vector<OutputFile> bopModelFiles(const std::vector<BopObject>& objects);

// The largest distance between two of the points (exact up to 4000 points;
// beyond, between the points extreme along 2000 directions).
double pointsDiameter(const std::vector<Vec3f>& points);

}  // namespace sdg
