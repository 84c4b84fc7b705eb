#pragma once
// YAML scene -> Scene, in passes: parse to located raw nodes; read settings;
// declare prims (paths, types, parents); fill each prim (attributes, xform
// ops, labels, material, behaviors with their exposed variables); apply the
// --set overrides; check cross references. Every problem of the file is
// collected and reported together as one SceneError.
#include <span>
#include <string>
#include <vector>

#include "core/diagnostics.h"
#include "scene_io/scene.h"
#include "scene_io/scene_document.h"
#include "stage/behavior_spec.h"

namespace sdg {

class AssetLibrary;
class MapReader;

// The run's sections of a scene mapping (render, physics, capture, run,
// writer, events), read into `scene` with the YAML loader's checks; also
// how a USD layer's customLayerData["sdgbehave"] comes back (usd_settings.cpp).
void readSettingSections(MapReader& top, Scene& scene, Diagnostics& diag);

// Builds the scene; throws SceneError listing every problem. Prims with
// `reference:` are mounted from `assets` (a library of this load; one is
// made for the call when null).
Scene buildScene(const SceneDocument& doc, const BehaviorCatalog& catalog,
                 std::span<const std::string> overrides = {}, AssetLibrary* assets = nullptr);

// What an AssetLibrary builds a referenced asset's scene with: buildScene,
// with the library itself for the asset's own references.
Scene buildAssetScene(const SceneDocument& doc, const BehaviorCatalog& catalog, AssetLibrary& assets);

Scene loadScene(const std::string& path, const BehaviorCatalog& catalog,
                std::span<const std::string> overrides = {});

}  // namespace sdg
