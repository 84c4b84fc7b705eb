// The driver of the USD mapping (usd_import.h): walks the composed prims,
// defines each on the stage with its type, transform, schema attributes and
// geometry, corrects units and up axis, and hands materials and per-prim
// labels to their importers.
#include "scene_io/usd_import.h"

#include <algorithm>
#include <filesystem>
#include <set>

#include "core/text.h"
#include "scene_io/overrides.h"
#include "scene_io/scene_validate.h"
#include "scene_io/usd_animation.h"
#include "scene_io/usd_export.h"
#include "scene_io/usd_default_view.h"
#include "scene_io/usd_import_internal.h"
#include "scene_io/usd_lens_schemas.h"
#include "scene_io/usd_mesh_asset.h"
#include "scene_io/usd_mesh_topology.h"
#include "scene_io/usd_point_instancer.h"
#include "scene_io/usd_prim_labels.h"
#include "scene_io/usd_settings.h"
#include "scene_io/usd_skel.h"
#include "scene_io/usd_value_node.h"
#include "stage/path.h"
#include "usd/layer_io.h"

namespace sdg {
namespace {

using usd::ComposedPrim;
using usd::ComposedProperty;

// USD types with a stage type of the same name; typeless prims and the
// types below map to Xform (a group) with a warning naming the type.
std::optional<PrimType> stageTypeFor(const std::string& typeName) {
  if (typeName.empty()) return PrimType::Xform;
  // UsdSkel's transformable prims: groups on the stage (the skinning poses
  // their meshes, usd_skel.h).
  if (typeName == "SkelRoot" || typeName == "Skeleton") return PrimType::Xform;
  return primTypeFromName(typeName);
}

// Types whose prims are handled by their parent (GeomSubset by its Mesh,
// shaders by their Material, a skeleton's animation by the skinning) or
// that carry nothing to draw.
bool handledElsewhere(const std::string& typeName) {
  return typeName == "GeomSubset" || typeName == "Shader" || typeName == "NodeGraph" || typeName == "SkelAnimation" ||
         typeName == "BlendShape";
}

// Schema attributes are authored in USD under the same names; lights of
// USD before 21.02 wrote them without the `inputs:` prefix.
const AttributeSpec* schemaSpecFor(PrimType type, const std::string& name) {
  if (const AttributeSpec* spec = findSchemaAttribute(type, name)) return spec;
  if (primTypeInfo(type).light) return findSchemaAttribute(type, "inputs:" + name);
  return nullptr;
}

// Attributes the mapping consumes by other means or that the stage has no
// use for; the rest of the unmapped are reported once per name.
bool quietlyIgnored(const std::string& name) {
  static const std::vector<std::string> kNames = {
      "xformOpOrder", "extent", "purpose", "proxyPrim", "points", "faceVertexCounts", "faceVertexIndices",
      "normals", "subdivisionScheme", "orientation", "interpolateBoundary", "faceVaryingLinearInterpolation",
      "triangleSubdivisionRule", "cornerIndices", "cornerSharpnesses", "creaseIndices", "creaseLengths",
      "creaseSharpnesses", "holeIndices", "velocities", "accelerations", "material:binding"};
  if (std::find(kNames.begin(), kNames.end(), name) != kNames.end()) return true;
  for (const char* prefix : {"xformOp:", "primvars:", "semantic:", "semantics:", "omni:", "physics:", "physx",
                             "material:binding", "exposedVar:", "sdgbehave:", "inputs:", "outputs:", "info:", "shaping:",
                             "shadow:", "light:", "collection:", "proxy", "ui:", "skel:"})
    if (name.rfind(prefix, 0) == 0) return true;
  return false;
}

class Importer {
 public:
  Importer(const usd::ComposedStage& composed, Stage& stage, const BehaviorCatalog& catalog,
           const UsdImportOptions& options, UsdImportReport& report, Diagnostics& diag)
      : composed_(composed), stage_(stage), catalog_(catalog), options_(options), report_(report), diag_(diag) {}

  void run(const std::string& sourceRoot, const std::string& mountPath) {
    sourceRoot_ = sourceRoot;
    mountPath_ = mountPath;
    usd::LayerUnits into;
    into.metersPerUnit = stage_.metadata().metersPerUnit;
    into.upAxis = stage_.metadata().upAxis;
    const std::vector<XformOp> rootUnits = usd_map::unitsOps(composed_.units, into);
    const double scale = usd_map::unitsScale(composed_.units, into);
    if (sourceRoot == "/") {
      for (const std::string& path : composed_.rootPrims())
        if (const ComposedPrim* prim = composed_.prim(path)) importPrim(*prim, stage_.pseudoRoot(), rootUnits, scale);
      poseSkinnedMeshes();
      expandInstancers();
      return;
    }
    const ComposedPrim* prim = composed_.prim(sourceRoot);
    if (!prim) {
      diag_.error(SourceLoc{composed_.rootLayer, 0, 0}, "no prim " + sourceRoot + " in " + composed_.rootLayer);
      return;
    }
    // Mounted in a YAML scene: the correction goes after the prim's own ops,
    // as for a USD reference, so that the scene's overrides of them keep it.
    Prim* parent = stage_.find(std::string(path::parent(mountPath)));
    mountUnits_ = rootUnits;
    importPrim(*prim, *parent, {}, scale);
    poseSkinnedMeshes();
    expandInstancers();
  }

  std::string mapPath(const std::string& source) const {
    if (sourceRoot_ == "/") return mountPath_ == "/" ? source : mountPath_ + source;
    if (source == sourceRoot_) return mountPath_;
    if (source.rfind(sourceRoot_ + "/", 0) == 0) return mountPath_ + source.substr(sourceRoot_.size());
    return source;  // outside the mounted scope: left as written (the binding check reports it)
  }

 private:
  void warnOnce(const SourceLoc& loc, const std::string& key, const std::string& message) {
    if (!warned_.insert(key).second) return;
    diag_.warning(loc, message);
    report_.warnings.push_back(message);
  }

  // Prim metadata that changes what is drawn and that nothing here reads:
  // applied schemas that change the look, value clips.
  void noteUnreadMetadata(const ComposedPrim& prim, bool isLight) {
    for (const std::string& schema : prim.apiSchemas)
      if (appliedSchemaChangesAppearance(schema, isLight))
        report_.losses.note(UsdLossKind::AppliedSchema, schema, prim.loc, prim.path);
    for (const char* clips : {"clips", "clipSets"})
      if (prim.metadata.count(clips)) report_.losses.note(UsdLossKind::Composition, "value clips", prim.loc, prim.path);
  }

  // PointInstancers (usd_point_instancer.h) once every prototype is on the stage.
  void expandInstancers() {
    expandPointInstancers(
        instancers_, stage_, [this](const std::string& s) { return mapPath(s); },
        [this](const SourceLoc& loc, const std::string& key, const std::string& m) { warnOnce(loc, key, m); },
        usdAnimationClock(composed_), diag_);
  }

  // Skinned meshes (usd_skel.h) once every skeleton is on the stage, before
  // instancers copy any of them.
  void poseSkinnedMeshes() {
    if (skinned_.empty()) return;
    std::vector<UsdSkinnedMesh> meshes;
    for (const ComposedPrim* mesh : skinned_) {
      UsdSkinnedMesh m{mesh, {mapPath(mesh->path)}};
      for (const std::string& child : mesh->children)
        if (const ComposedPrim* c = composed_.prim(mesh->path + "/" + child); c && c->typeName == "GeomSubset")
          m.stagePaths.push_back(mapPath(c->path));
      meshes.push_back(std::move(m));
    }
    poseUsdSkinnedMeshes(
        composed_, meshes, [this](const std::string& s) { return mapPath(s); }, usdAnimationClock(composed_), stage_,
        report_.losses,
        [this](const SourceLoc& loc, const std::string& key, const std::string& m) { warnOnce(loc, key, m); }, diag_);
  }

  // `outerUnits` go before the prim's own ops (the root layer's units into
  // the stage's); a units change on the prim goes after them, as Omniverse
  // appends its unitsResolve ops.
  void importPrim(const ComposedPrim& prim, Prim& parent, const std::vector<XformOp>& outerUnits, double unitScale) {
    if (!prim.defined || prim.abstract || !prim.active) return;
    if (handledElsewhere(prim.typeName)) return;
    std::optional<PrimType> type = stageTypeFor(prim.typeName);
    const bool knownType = type.has_value();
    if (isPointInstancer(prim)) {
      type = PrimType::Xform;  // its instances are added under it afterwards
      instancers_.push_back(&prim);
    }
    if (!type) {
      report_.losses.note(UsdLossKind::PrimType, prim.typeName, prim.loc, prim.path);
      warnOnce(prim.loc, "type:" + prim.typeName,
               prim.path + ": USD type " + prim.typeName + " has no stage counterpart; imported as an Xform (a group)");
      type = PrimType::Xform;
    }
    noteUnreadMetadata(prim, primTypeInfo(*type).light);
    const std::string stagePath = mapPath(prim.path);
    Prim& p = stage_.definePrim(stagePath, *type);
    p.loc() = prim.loc;
    const double scale = importValues(prim, p, parent, *type, outerUnits, unitScale, knownType);
    if (*type == PrimType::Material) {
      importUsdMaterial(composed_, prim, p, diag_, report_);
      importUsdPrimLabels(composed_, prim, p, [this](const std::string& s) { return mapPath(s); }, catalog_,
                          options_, report_, diag_);
      return;  // its shaders are the material's
    }
    importMetadata(prim, p);
    importUsdPrimLabels(composed_, prim, p, [this](const std::string& s) { return mapPath(s); }, catalog_, options_,
                        report_, diag_);
    if (*type == PrimType::Mesh && prim.property("primvars:skel:jointIndices")) skinned_.push_back(&prim);
    if (usdPrimIsAnimated(prim)) recordAnimation(prim, p, parent, *type, outerUnits, unitScale, knownType);
    for (const std::string& child : prim.children)
      if (const ComposedPrim* c = composed_.prim(prim.path == "/" ? "/" + child : prim.path + "/" + child))
        importPrim(*c, p, {}, scale);
  }

  // The prim's transform ops, schema attributes and geometry: all that its
  // time samples can change. Returns the units scale for its children.
  double importValues(const ComposedPrim& prim, Prim& p, const Prim& parent, PrimType type,
                      const std::vector<XformOp>& outerUnits, double unitScale, bool knownType) {
    const Matrix4d parentWorld = stage_.worldMatrix(parent);
    std::vector<XformOp> ops = outerUnits;
    for (XformOp& op : usd_map::xformOpsOf(prim, parentWorld, diag_)) ops.push_back(std::move(op));
    double scale = unitScale;
    if (prim.path == sourceRoot_ && sourceRoot_ != "/")
      for (const XformOp& op : mountUnits_) ops.push_back(op);
    if (prim.unitsChange) {
      for (XformOp& op : usd_map::unitsOps(prim.unitsChange->asset, prim.unitsChange->into)) ops.push_back(std::move(op));
      scale *= usd_map::unitsScale(prim.unitsChange->asset, prim.unitsChange->into);
    }
    if (primTypeInfo(type).xformable) p.xformOps() = std::move(ops);
    else if (!ops.empty() && !(ops.size() == outerUnits.size())) {
      report_.losses.note(UsdLossKind::Attribute, "xformOps of a " + prim.typeName, prim.loc, prim.path);
      warnOnce(prim.loc, "xform:" + prim.path, prim.path + ": a " + prim.typeName + " has no transform; its xform ops are ignored");
    }
    if (type == PrimType::Material) return scale;
    importAttributes(prim, p, type, scale, knownType);
    if (type == PrimType::Camera) importLensSchema(prim, p);
    if (type == PrimType::Mesh && !importMeshAsset(prim, p)) importMesh(prim, p);
    return scale;
  }

  // The prim's time samples as stage animation (usd_animation.h): a second
  // importer, defining no prim and reporting into its own diagnostics, maps
  // the prim at each sampled time; errors of a sample are reported once.
  void recordAnimation(const ComposedPrim& prim, const Prim& p, const Prim& parent, PrimType type,
                       const std::vector<XformOp>& outerUnits, double unitScale, bool knownType) {
    Diagnostics sampleDiag;
    UsdImportReport sampleReport;
    Importer sampler(composed_, stage_, catalog_, options_, sampleReport, sampleDiag);
    sampler.sampling_ = true;
    sampler.sourceRoot_ = sourceRoot_;
    sampler.mountPath_ = mountPath_;
    sampler.mountUnits_ = mountUnits_;
    recordUsdPrimAnimation(prim, p, usdAnimationClock(composed_),
                           [&](const ComposedPrim& at, Prim& into) {
                             sampler.importValues(at, into, parent, type, outerUnits, unitScale, knownType);
                           },
                           stage_.animation());
    std::set<std::string> said;
    for (const Diagnostic& d : sampleDiag.all())
      if (d.severity == Severity::Error && said.insert(d.format()).second) diag_.error(d.loc, "at a time sample: " + d.message);
  }

  // A camera that applies one of the omni_lens_distortion schemas without
  // authoring the model token gets the schema's model, as in Isaac Sim.
  void importLensSchema(const ComposedPrim& prim, Prim& p) {
    static const std::string kModel = "omni:lensdistortion:model";
    if (p.findAttribute(kModel)) return;
    for (const std::string& schema : prim.apiSchemas)
      for (const UsdLensSchema& lens : kUsdLensSchemas)
        if (schema == lens.schema) {
          p.setAttribute(kModel, Value::makeToken(std::string(lens.model))).loc = prim.loc;
          return;
        }
  }

  // `knownType` false: the prim's type is already reported as dropped, and
  // with it every attribute of that type.
  void importAttributes(const ComposedPrim& prim, Prim& p, PrimType type, double unitScale, bool knownType) {
    std::vector<std::string> fallbacks;  // written by export-usd for other tools only
    if (auto custom = prim.metadata.find("customData"); custom != prim.metadata.end() && custom->second.dictionary)
      if (auto list = custom->second.dictionary->find(kFallbacksKey); list != custom->second.dictionary->end())
        fallbacks = list->second.strings;
    for (const ComposedProperty& prop : prim.properties) {
      if (prop.isRelationship || prop.value.empty()) continue;
      if (std::find(fallbacks.begin(), fallbacks.end(), prop.name) != fallbacks.end()) continue;
      if (usd_map::importDisplayPrimvar(prim, prop, type, p, diag_)) continue;
      const AttributeSpec* spec = schemaSpecFor(type, prop.name);
      if (isPointInstancer(prim) && isPointInstancerAttribute(prop.name)) continue;
      if (prim.typeName == "Skeleton" && isSkeletonAttribute(prop.name)) continue;
      if (!spec && prop.custom && !quietlyIgnored(prop.name) && importCustom(prim, prop, p)) continue;
      // Array attributes are geometry, read with the mesh, except a Lidar's elevations.
      const bool geometryArray = spec && arrayWidth(spec->type) != 0 && type != PrimType::Lidar;
      if (!spec || geometryArray || spec->name == "asset") {
        if (!spec && !quietlyIgnored(prop.name)) {
          if (knownType) report_.losses.note(UsdLossKind::Attribute, prop.name, prop.loc, prim.path);
          warnOnce(prop.loc, "attr:" + prim.typeName + ":" + prop.name,
                   prim.path + "." + prop.name + ": not a " + std::string(primTypeInfo(type).name) +
                       " attribute of the stage; ignored (and on every other prim)");
        }
        continue;
      }
      std::optional<Value> v = usd_map::toStageValue(prop.value, spec->type);
      if (!v) {
        diag_.error(prop.loc, prim.path + "." + prop.name + ": expected " + std::string(valueTypeShape(spec->type)) +
                                  " (" + std::string(valueTypeName(spec->type)) + "), found " + prop.typeName);
        continue;
      }
      if (type == PrimType::Camera && spec->name == "omni:lensdistortion:model" &&
          v->get<std::string>() == kUnreadLensModel) {
        report_.losses.note(UsdLossKind::Attribute, prop.name + " = " + std::string(kUnreadLensModel), prop.loc,
                            prim.path);
        continue;
      }
      if (type == PrimType::Camera && spec->name == "clippingRange") {
        // Distances in the layer's units, into the stage's.
        const Vec2f r = v->get<Vec2f>();
        v = Value::makeFloat2(float(r.x() * unitScale), float(r.y() * unitScale));
      }
      if (!spec->allowedTokens.empty() &&
          std::find(spec->allowedTokens.begin(), spec->allowedTokens.end(), v->get<std::string>()) ==
              spec->allowedTokens.end()) {
        diag_.error(prop.loc, prim.path + "." + prop.name + ": expected one of " + text::join(spec->allowedTokens, ", ") +
                                  ", found " + text::quote(v->get<std::string>()));
        continue;
      }
      p.setAttribute(spec->name, *v).loc = prop.loc;
    }
  }

  // A `custom` attribute of a type the stage has (`custom double user:weight`,
  // as export-usd writes a scene's custom attributes) becomes a custom
  // attribute of the prim; false for other types (reported by the caller).
  bool importCustom(const ComposedPrim& prim, const ComposedProperty& prop, Prim& p) {
    const std::optional<ValueType> type = valueTypeFromName(prop.typeName);
    if (!type) return false;
    if (std::optional<Value> v = readUsdValue(prop, *type, prim.path + "." + prop.name, diag_))
      p.setAttribute(prop.name, *v, true).loc = prop.loc;
    return true;
  }

  // Prim metadata the stage keeps: `kind`, `documentation`, and the string
  // entries of `customData` (how export-usd writes a prim's metadata:).
  void importMetadata(const ComposedPrim& prim, Prim& p) {
    if (!prim.kind.empty()) p.metadata()["kind"] = prim.kind;
    auto doc = prim.metadata.find("documentation");
    if (doc != prim.metadata.end() && usd::isText(doc->second.kind) && !doc->second.strings.empty())
      p.metadata()["documentation"] = doc->second.strings[0];
    auto custom = prim.metadata.find("customData");
    if (custom != prim.metadata.end() && custom->second.dictionary)
      for (const auto& [key, value] : *custom->second.dictionary)
        if (value.kind == usd::Kind::String && !value.isArray && !value.strings.empty())
          p.metadata()[key] = value.strings[0];
  }

  // A Mesh that export-usd wrote from a mesh file keeps the file in
  // `sdgbehave:asset` (and `sdgbehave:submesh`): the file is the mesh again,
  // with its own materials, rather than the triangles written for other
  // tools. False when the prim has no such attribute.
  bool importMeshAsset(const ComposedPrim& prim, Prim& p) {
    const ComposedProperty* asset = prim.property("sdgbehave:asset");
    if (!asset || asset->value.empty()) return false;
    for (const char* name : {"asset", "submesh"}) {
      const ComposedProperty* prop = prim.property(std::string("sdgbehave:") + name);
      if (!prop || prop->value.empty()) continue;
      if (std::optional<Value> v = readUsdValue(*prop, *findSchemaAttribute(PrimType::Mesh, name),
                                                prim.path + ".sdgbehave:" + name, diag_))
        p.setAttribute(name, *v).loc = prop->loc;
    }
    return true;
  }

  // The mesh's faces, less those a GeomSubset with a material binding
  // takes: each such subset becomes a child Mesh of its faces, bound to its
  // material (the stage binds materials per prim).
  void importMesh(const ComposedPrim& prim, Prim& p) {
    std::vector<int32_t> rest;
    std::vector<std::pair<const ComposedPrim*, std::vector<int32_t>>> subsets;
    const ComposedProperty* counts = prim.property("faceVertexCounts");
    const size_t faceCount = counts ? counts->value.numbers.size() : 0;
    for (const std::string& child : prim.children) {
      const ComposedPrim* c = composed_.prim(prim.path + "/" + child);
      if (!c || c->typeName != "GeomSubset" || !c->active) continue;
      const ComposedProperty* binding = c->property("material:binding");
      if (!binding || binding->targets.empty()) continue;
      const ComposedProperty* elementType = c->property("elementType");
      if (elementType && !elementType->value.empty() &&
          (elementType->value.strings.empty() || elementType->value.strings[0] != "face")) {  // not text: not "face"
        const std::string what = elementType->value.strings.empty() ? "a GeomSubset whose elementType is not text"
                                                                     : "a GeomSubset of " + elementType->value.strings[0] + "s";
        report_.losses.note(UsdLossKind::Binding, "a material bound to " + what, c->loc, c->path);
        warnOnce(c->loc, "subset:" + c->path, c->path + ": only face subsets bind materials; ignored");
        continue;
      }
      std::optional<std::vector<int32_t>> faces = usd_map::subsetFaces(*c, prim.path, faceCount, diag_);
      if (!faces) return;
      subsets.emplace_back(c, std::move(*faces));
    }
    if (subsets.empty()) {
      usd_map::importMeshGeometry(prim, p, nullptr, diag_);
      return;
    }
    std::vector<bool> taken(faceCount, false);
    for (const auto& [subset, faces] : subsets)
      for (int32_t f : faces) taken[size_t(f)] = true;
    for (size_t f = 0; f < faceCount; ++f)
      if (!taken[f]) rest.push_back(int32_t(f));
    const size_t errorsBefore = diag_.errorCount();
    usd_map::importMeshGeometry(prim, p, &rest, diag_);
    if (diag_.errorCount() > errorsBefore) return;  // the mesh's problems said once, not again for each subset
    if (sampling_) return;  // subsets are prims of their own, not animated (docs/usd.md)
    for (const auto& [subset, faces] : subsets) {
      Prim& s = stage_.definePrim(mapPath(subset->path), PrimType::Mesh);
      s.loc() = subset->loc;
      for (const auto& [name, attr] : p.attributes())
        if (name == "doubleSided" || name == "primvars:displayColor" || name == "subdivisionScheme" ||
            name == "orientation" || name == "interpolateBoundary" || name == "faceVaryingLinearInterpolation" ||
            name == "triangleSubdivisionRule")
          s.setAttribute(name, attr.value).loc = attr.loc;
      usd_map::importMeshGeometry(prim, s, &faces, diag_);
      importUsdPrimLabels(composed_, *subset, s, [this](const std::string& x) { return mapPath(x); }, catalog_,
                          options_, report_, diag_);
    }
  }

  const usd::ComposedStage& composed_;
  Stage& stage_;
  const BehaviorCatalog& catalog_;
  const UsdImportOptions& options_;
  UsdImportReport& report_;
  Diagnostics& diag_;
  std::string sourceRoot_, mountPath_;
  std::vector<XformOp> mountUnits_;  // the file's units into the stage's, on a mounted root
  std::vector<const ComposedPrim*> instancers_;  // PointInstancers, in import order
  std::vector<const ComposedPrim*> skinned_;     // Meshes with skel:jointIndices, in import order
  std::set<std::string> warned_;
  bool sampling_ = false;  // a sampler of time samples (recordAnimation): defines no prims
};

// What a USD stage does not say: one BasicWriter writing rgb, tight boxes
// and semantic segmentation, a framing camera and lights where it has none
// (usd_default_view.h), and the first camera (docs/usd.md).
void addDefaultRunSettings(Scene& scene) {
  addDefaultCameraAndLights(scene);
  WriterConfig writer;
  writer.type = "BasicWriter";
  writer.options = OptionSet(findWriterType("BasicWriter")->options);
  for (const char* flag : {"rgb", "bounding_box_2d_tight", "semantic_segmentation"})
    writer.options.set(flag, Value::makeBool(true));
  scene.writers.push_back(std::move(writer));
  std::string firstCamera;
  scene.stage.traverse([&](const Prim& p) {
    if (firstCamera.empty() && p.type() == PrimType::Camera) firstCamera = p.path();
  });
  if (!firstCamera.empty()) scene.capture.set("cameras", Value::makeStringArray({firstCamera}));
}

}  // namespace

void importUsdPrims(const usd::ComposedStage& composed, const std::string& sourceRoot, Stage& stage,
                    const std::string& mountPath, const BehaviorCatalog& catalog, const UsdImportOptions& options,
                    UsdImportReport& report, Diagnostics& diag) {
  for (const std::string& layer : composed.layers)
    if (std::find(report.layers.begin(), report.layers.end(), layer) == report.layers.end())
      report.layers.push_back(layer);
  for (const usd::ComposeWarning& w : composed.warnings) {
    report.losses.note(UsdLossKind::Composition, w.feature, w.loc, w.loc.known() ? "" : w.message);
    report.warnings.push_back(w.message);
  }
  Importer importer(composed, stage, catalog, options, report, diag);
  importer.run(sourceRoot, mountPath);
}

bool isUsdFile(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
  return ext == ".usd" || ext == ".usda" || ext == ".usdc" || ext == ".usdz";
}

UsdImportOptions usdImportOptionsFor(std::span<const std::string> overrides) {
  Diagnostics diag;
  UsdImportOptions options;
  for (const VariantSelection& v : variantSelections(overrides, diag)) {
    options.variants[v.prim][v.set] = v.variant;
    options.variantLocs[v.prim + " " + v.set] = v.loc;
  }
  diag.throwIfErrors();
  return options;
}

Scene importUsdScene(const std::string& path, const BehaviorCatalog& catalog, const UsdImportOptions& options,
                     UsdImportReport& report) {
  usd::ComposeOptions composeOptions;
  composeOptions.variantOverrides = options.variants;
  usd::ComposedStage composed;
  try {
    composed = usd::composeStage(path, [](const std::string& id) { return usd::readLayerFile(id); }, composeOptions);
  } catch (const usd::VariantOverrideError& e) {
    // A chosen set or variant the stage lacks: reported at the choice.
    auto at = options.variantLocs.find(e.prim() + " " + e.set());
    throw SceneError(at != options.variantLocs.end() ? at->second : e.loc(), e.what());
  } catch (const usd::UsdError& e) {
    // what() starts with the location SceneError adds again.
    std::string message = e.what();
    const std::string where = e.loc().str() + ": ";
    if (e.loc().known() && message.rfind(where, 0) == 0) message = message.substr(where.size());
    throw SceneError(e.loc(), message);
  }
  Scene scene;
  scene.sourcePath = path;
  scene.sourceDir = std::filesystem::path(path).parent_path().string();
  if (scene.sourceDir.empty()) scene.sourceDir = ".";
  // The stage is Z-up metres; the root layer's units become a transform.
  if (auto it = composed.layerMetadata.find("timeCodesPerSecond");
      it != composed.layerMetadata.end() && usd::isNumeric(it->second.kind) && !it->second.numbers.empty() &&
      it->second.numbers[0] >= 1)
    scene.stage.metadata().timeCodesPerSecond = it->second.numbers[0];
  Diagnostics diag;
  importUsdPrims(composed, "/", scene.stage, "/", catalog, options, report, diag);
  // A stage that plays its own animation runs at its rate (USD's 24 when unsaid).
  if (!scene.stage.animation().empty() && !composed.layerMetadata.count("timeCodesPerSecond"))
    scene.stage.metadata().timeCodesPerSecond = usdAnimationClock(composed).timeCodesPerSecond;
  // A stage export-usd wrote says its own run settings; others get defaults.
  const bool exported = importUsdSceneSettings(composed, scene, diag);
  diag.throwIfErrors();
  if (!exported && options.runDefaults) addDefaultRunSettings(scene);
  return scene;
}

}  // namespace sdg
