#include "scene_io/references.h"

#include <algorithm>
#include <filesystem>
#include <functional>

#include "assets/asset_resolver.h"
#include "core/log.h"
#include "core/text.h"
#include "scene_io/map_reader.h"
#include "scene_io/usd_import.h"
#include "scene_io/usd_prim_labels.h"
#include "scene_io/value_reader.h"
#include "stage/path.h"
#include "usd/layer_io.h"

namespace sdg {
namespace fs = std::filesystem;

struct AssetLibrary::Asset {
  std::string path;  // absolute, normalized
  SceneDocument doc;
  std::unique_ptr<Scene> scene;  // built on first mount
  bool failed = false;           // built, with problems (reported once)
};

AssetLibrary::AssetLibrary(AssetSceneBuilder build, std::map<std::string, std::string> texts)
    : texts_(std::move(texts)), build_(build) {}
AssetLibrary::~AssetLibrary() = default;

namespace {

std::string absoluteNormal(const fs::path& p) { return fs::absolute(p).lexically_normal().string(); }

// How messages name an asset file: relative to the working folder when it
// lies below it (as users type paths), else absolute.
std::string displayPath(const std::string& absolute) {
  std::error_code ec;
  fs::path relative = fs::path(absolute).lexically_relative(fs::current_path(ec));
  if (ec || relative.empty() || *relative.begin() == "..") return absolute;
  return relative.string();
}

std::string chainText(const std::vector<std::string>& chain, const std::string& last) {
  std::string out;
  for (const std::string& file : chain) out += displayPath(absoluteNormal(file)) + " -> ";
  return out + displayPath(absoluteNormal(last));
}

// The `reference:` of each prim entry of a document, with the entry's path.
std::vector<std::pair<std::string, const RawNode*>> referencesIn(const SceneDocument& doc) {
  std::vector<std::pair<std::string, const RawNode*>> out;
  const RawNode* prims = doc.root.isMap() ? doc.root.find("prims") : nullptr;
  if (!prims || !prims->isMap()) return out;
  for (const RawEntry& e : prims->entries)
    if (e.value.isMap())
      if (const RawNode* ref = e.value.find("reference")) out.emplace_back(e.key.scalar, ref);
  return out;
}

// Rewrites the files an asset's attribute names so that they resolve from
// the referencing file's folder to what they named from the asset's.
class PathRebaser {
 public:
  PathRebaser(const Scene& asset, const std::string& fromDir)
      : resolver_(makeSceneResolver(asset.sourceDir, asset.assetRoots, {})),
        assetDir_(absoluteNormal(asset.sourceDir)),
        fromDir_(absoluteNormal(fromDir.empty() ? "." : fromDir)) {}

  std::string entry(const std::string& e, bool labelled) const {
    std::string file = e, suffix;
    if (labelled)
      if (size_t hash = e.rfind('#'); hash != std::string::npos) {
        file = e.substr(0, hash);
        suffix = e.substr(hash);
      }
    if (file.empty() || fs::path(file).is_absolute() || file.find("://") != std::string::npos) return e;
    std::optional<std::string> found = resolver_.resolve(file);
    fs::path target = found ? fs::path(absoluteNormal(*found)) : fs::path(assetDir_) / file;
    fs::path relative = target.lexically_normal().lexically_relative(fromDir_);
    return (relative.empty() ? target.lexically_normal() : relative).string() + suffix;
  }

  Value value(const Value& v, FileKind kind) const {
    const bool labelled = kind == FileKind::Mesh;
    switch (v.type()) {
      case ValueType::Asset: return Value::makeAsset(entry(v.get<std::string>(), labelled));
      case ValueType::AssetArray: {
        std::vector<std::string> list;
        for (const std::string& e : v.get<std::vector<std::string>>()) list.push_back(entry(e, labelled));
        return Value::makeAssetArray(std::move(list));
      }
      case ValueType::String: {
        if (kind == FileKind::None) return v;
        std::vector<std::string> parts;
        for (const std::string& e : text::splitCsv(v.get<std::string>())) parts.push_back(entry(e, labelled));
        return Value::makeString(text::join(parts, ","));
      }
      default: return v;
    }
  }

 private:
  AssetResolver resolver_;
  std::string assetDir_;
  fs::path fromDir_;
};

}  // namespace

std::string assetKey(const std::string& path) { return absoluteNormal(path); }

SourceLoc referencedFrom(const SourceLoc& loc, const SourceLoc& from) {
  SourceLoc out = loc;
  out.via = std::make_shared<const SourceLoc>(loc.via ? referencedFrom(*loc.via, from) : from);
  return out;
}

std::optional<ReferenceSpec> readReferenceSpec(const RawNode& node, const std::string& what, Diagnostics& diag) {
  ReferenceSpec ref;
  ref.loc = node.loc;
  if (node.isScalar()) {
    ref.file = node.scalar;
  } else {
    MapReader map(node, what, diag);
    if (!map.ok()) return std::nullopt;
    if (const RawNode* f = map.require("file"))
      if (auto s = readString(*f, joinWhat(what, "file"), diag)) ref.file = *s;
    if (const RawNode* p = map.get("prim"))
      if (auto s = readString(*p, joinWhat(what, "prim"), diag)) ref.prim = *s;
    if (const RawNode* v = map.get("variants")) {
      MapReader sets(*v, joinWhat(what, "variants"), diag);
      if (sets.ok())
        for (const RawEntry& e : v->entries) {
          sets.allow(e.key.scalar);
          if (auto variant = readString(e.value, joinWhat(joinWhat(what, "variants"), e.key.scalar), diag))
            ref.variants[e.key.scalar] = *variant;
        }
    }
    map.finish();
  }
  if (ref.file.empty()) {
    diag.error(node.loc, what + ": expected an asset file (a scene file), e.g. `reference: assets/drill.yaml`");
    return std::nullopt;
  }
  if (!ref.variants.empty() && !isUsdFile(ref.file)) {
    diag.error(node.loc, what + ".variants: variant selections are for USD files (.usd, .usda, .usdc, .usdz); " +
                             text::quote(ref.file) + " is not one");
    return std::nullopt;
  }
  if (!ref.prim.empty())
    if (std::string why = path::whyInvalid(ref.prim); !why.empty()) {
      diag.error(node.loc, what + ".prim: " + text::quote(ref.prim) + " is not a prim path: " + why);
      return std::nullopt;
    }
  return ref;
}

AssetLibrary::Asset& AssetLibrary::document(const std::string& absolutePath, const SourceLoc& from) {
  auto it = assets_.find(absolutePath);
  if (it != assets_.end()) return *it->second;
  std::error_code ec;
  if (!fs::is_regular_file(absolutePath, ec))
    throw SceneError(from, "reference: asset file not found; searched: " + absolutePath);
  auto asset = std::make_unique<Asset>();
  asset->path = absolutePath;
  try {
    auto edited = texts_.find(absolutePath);
    asset->doc = edited == texts_.end() ? readSceneDocument(displayPath(absolutePath))
                                        : sceneDocumentFromText(edited->second, displayPath(absolutePath));
    log::debug("reference: read " + asset->doc.path);
  } catch (const SceneError& e) {
    std::vector<Diagnostic> problems = e.problems();
    for (Diagnostic& d : problems) d.loc = referencedFrom(d.loc, from);
    throw SceneError(std::move(problems));
  }
  return *assets_.emplace(absolutePath, std::move(asset)).first->second;
}

std::vector<DeclaredFile> AssetLibrary::preload(const SceneDocument& doc) {
  std::vector<std::string> chain = {doc.path};
  std::vector<DeclaredFile> scripts;
  preloadFrom(doc, chain, SourceLoc{}, scripts);
  return scripts;
}

void AssetLibrary::preloadFrom(const SceneDocument& doc, std::vector<std::string>& chain, const SourceLoc& via,
                               std::vector<DeclaredFile>& scripts) {
  const fs::path dir = fs::path(doc.path).parent_path();
  for (const auto& [primPath, node] : referencesIn(doc)) {
    Diagnostics diag;
    std::optional<ReferenceSpec> ref = readReferenceSpec(*node, primPath + ".reference", diag);
    if (!ref) continue;  // buildScene reports it, in line order with the rest
    SourceLoc from = via.known() ? referencedFrom(ref->loc, via) : ref->loc;
    const std::string file = absoluteNormal(fs::path(ref->file).is_absolute() ? fs::path(ref->file) : dir / ref->file);
    if (isUsdFile(file)) {
      // The script files its prims list are attached by the program's
      // loader before any prim is read, as a YAML scene's own listed
      // scripts are; each is reported where the file is mounted. A broken
      // file is reported where it is mounted, when it is built.
      try {
        for (const ListedScript& script : usdListedScripts(usdStage(file, {})))
          if (std::none_of(usdScripts_.begin(), usdScripts_.end(),
                           [&](const ListedScript& l) { return l.path == script.path; }))
            usdScripts_.push_back(ListedScript{script.path, from});
      } catch (const usd::UsdError&) {
      }
      continue;
    }
    for (const std::string& seen : chain)
      if (absoluteNormal(seen) == file)
        throw SceneError(from, primPath + ".reference: a reference cycle: " + chainText(chain, file));
    if (chain.size() > kMaxReferenceDepth)
      throw SceneError(from, primPath + ".reference: references nest deeper than " +
                                 std::to_string(kMaxReferenceDepth) + " files: " + chainText(chain, file));
    const bool firstTime = !assets_.count(file);
    Asset& asset = document(file, from);
    if (!firstTime) continue;  // read once; its scripts and references are known
    for (const DeclaredFile& script : declaredFiles(asset.doc, "scripts")) {
      fs::path p(script.path);
      std::string absolute = absoluteNormal(p.is_absolute() ? p : fs::path(asset.path).parent_path() / p);
      scripts.push_back(DeclaredFile{absolute, referencedFrom(script.loc, from)});
      scripts_.push_back(absolute);
    }
    chain.push_back(file);
    preloadFrom(asset.doc, chain, from, scripts);
    chain.pop_back();
  }
}

const Scene* AssetLibrary::built(Asset& asset, const BehaviorCatalog& catalog, const SourceLoc& from,
                                 Diagnostics& diag) {
  if (asset.scene) return asset.scene.get();
  if (asset.failed) return nullptr;
  for (const std::string& file : building_)
    if (file == asset.path) {
      diag.error(from, "reference: a reference cycle: " + chainText(building_, asset.path));
      return nullptr;
    }
  if (building_.size() >= kMaxReferenceDepth) {
    diag.error(from, "reference: references nest deeper than " + std::to_string(kMaxReferenceDepth) + " files");
    return nullptr;
  }
  building_.push_back(asset.path);
  try {
    asset.scene = std::make_unique<Scene>(build_(asset.doc, catalog, *this));
  } catch (const SceneError& e) {
    asset.failed = true;
    for (const Diagnostic& d : e.problems()) diag.error(referencedFrom(d.loc, from), d.message);
  }
  building_.pop_back();
  return asset.scene.get();
}

void AssetLibrary::mount(const ReferenceSpec& ref, const std::string& fromDir, const std::string& mountPath,
                         Stage& stage, const BehaviorCatalog& catalog, Diagnostics& diag) {
  const std::string what = mountPath + ".reference";
  const std::string file =
      absoluteNormal(fs::path(ref.file).is_absolute() ? fs::path(ref.file) : fs::path(fromDir) / ref.file);
  if (isUsdFile(file)) {
    mountUsd(ref, file, mountPath, stage, catalog, diag);
    return;
  }
  Asset* asset = nullptr;
  try {
    asset = &document(file, ref.loc);
  } catch (const SceneError& e) {
    for (const Diagnostic& d : e.problems()) diag.error(d.loc, what + ": " + d.message);
    return;
  }
  const Scene* scene = built(*asset, catalog, ref.loc, diag);
  if (!scene) return;
  // The prim to mount: as named, else the asset's first top-level prim.
  const Prim* root = nullptr;
  if (!ref.prim.empty()) {
    root = scene->stage.find(ref.prim);
    if (!root) {
      std::vector<std::string> tops;
      for (const Prim* p : scene->stage.pseudoRoot().children()) tops.push_back(p->path());
      diag.error(ref.loc, what + ": " + ref.file + " has no prim " + ref.prim + "; its top-level prims: " +
                              text::join(tops, ", ") + text::didYouMean(ref.prim, tops));
      return;
    }
  } else if (!scene->stage.pseudoRoot().children().empty()) {
    root = scene->stage.pseudoRoot().children().front();
  } else {
    diag.error(ref.loc, what + ": " + ref.file + " has no prims to reference");
    return;
  }

  const std::string& rootPath = root->path();
  auto remap = [&](const std::string& p) {
    if (p == rootPath) return mountPath;
    if (p.size() > rootPath.size() && p.starts_with(rootPath) && p[rootPath.size()] == '/')
      return mountPath + p.substr(rootPath.size());
    return p;
  };
  PathRebaser rebase(*scene, fromDir);
  // Pre-order: parents are defined before their children.
  bool ok = true;
  std::function<void(const Prim&)> copy = [&](const Prim& source) {
    const std::string target = remap(source.path());
    if (std::string why = path::whyInvalid(target); !why.empty()) {
      diag.error(ref.loc, what + ": mounting " + source.path() + " at " + target + ": " + why);
      ok = false;
      return;
    }
    Prim& prim = stage.definePrim(target, source.type());
    prim.loc() = referencedFrom(source.loc(), ref.loc);
    for (const auto& [name, attribute] : source.attributes()) {
      Attribute& a = prim.setAttribute(name, attribute.value, attribute.custom);
      a.doc = attribute.doc;
      a.loc = attribute.loc.known() ? referencedFrom(attribute.loc, ref.loc) : SourceLoc{};
      // Files resolve from the asset's folder; prim paths inside the asset
      // follow it to the mount point.
      const AttributeSpec* spec = findSchemaAttribute(source.type(), name);
      if (name.starts_with("exposedVar:")) {
        const size_t colon = name.find(':', 11);
        if (const BehaviorSpec* b = colon == std::string::npos ? nullptr : catalog.find(name.substr(11, colon - 11)))
          spec = b->findVariable(name.substr(colon + 1));
      }
      const FileKind kind = spec ? spec->files : FileKind::None;
      if (a.value.type() == ValueType::Asset || a.value.type() == ValueType::AssetArray ||
          (a.value.type() == ValueType::String && kind != FileKind::None))
        a.value = rebase.value(a.value, kind);
      if (spec && spec->primPath && a.value.type() == ValueType::String && !a.value.get<std::string>().empty())
        a.value = Value::makeString(remap(a.value.get<std::string>()));
    }
    prim.xformOps() = source.xformOps();
    prim.semantics() = source.semantics();
    prim.material() = source.material();
    if (prim.material()) prim.material()->path = remap(prim.material()->path);
    prim.behaviors() = source.behaviors();
    prim.metadata() = source.metadata();
    for (const Prim* child : source.children())
      if (ok) copy(*child);
  };
  copy(*root);
}

void AssetLibrary::mountUsd(const ReferenceSpec& ref, const std::string& file, const std::string& mountPath,
                            Stage& stage, const BehaviorCatalog& catalog, Diagnostics& diag) {
  const std::string what = mountPath + ".reference";
  std::error_code ec;
  if (!fs::is_regular_file(usd::splitPackagePath(file).first, ec)) {
    diag.error(ref.loc, what + ": USD file not found; searched: " + file);
    return;
  }
  UsdImportOptions options;
  options.runDefaults = false;
  usd::ComposeOptions composeOptions;
  const usd::ComposedStage* stageRead = nullptr;
  std::string root = ref.prim;
  try {
    if (root.empty()) {  // the defaultPrim, else the first root prim: known once composed
      stageRead = &usdStage(file, composeOptions);
      const std::vector<std::string> tops = stageRead->rootPrims();
      root = !stageRead->defaultPrim.empty() ? "/" + stageRead->defaultPrim : tops.empty() ? "" : tops.front();
      if (root.empty()) {
        diag.error(ref.loc, what + ": " + ref.file + " has no prims to reference");
        return;
      }
    }
    // The reference's own selections, then --set's at or under the mount point.
    for (const auto& [set, variant] : ref.variants) composeOptions.variantOverrides[root][set] = variant;
    if (building_.empty())
      for (size_t i = 0; i < selections_.size(); ++i) {
        const VariantSelection& v = selections_[i];
        if (v.prim != mountPath && !v.prim.starts_with(mountPath + "/")) continue;
        composeOptions.variantOverrides[root + v.prim.substr(mountPath.size())][v.set] = v.variant;
        selectionUsed_[i] = true;
      }
    if (!stageRead || !composeOptions.variantOverrides.empty()) stageRead = &usdStage(file, composeOptions);
  } catch (const usd::UsdError& e) {
    diag.error(ref.loc, what + ": " + e.what());
    return;
  }
  const usd::ComposedStage& composed = *stageRead;
  if (!composed.prim(root)) {
    const std::vector<std::string> tops = composed.rootPrims();
    diag.error(ref.loc, what + ": " + ref.file + " has no prim " + root + "; its root prims: " + text::join(tops, ", ") +
                            text::didYouMean(root, tops));
    return;
  }
  UsdImportReport report;
  importUsdPrims(composed, root, stage, mountPath, catalog, options, report, diag);
  usdLosses_.append(report.losses);
  for (const std::string& layer : report.layers) {
    const std::string f = absoluteNormal(usd::splitPackagePath(layer).first);
    if (std::find(usdFiles_.begin(), usdFiles_.end(), f) == usdFiles_.end()) usdFiles_.push_back(f);
  }
}

const usd::ComposedStage& AssetLibrary::usdStage(const std::string& file, const usd::ComposeOptions& options) {
  std::string key = file;
  for (const auto& [prim, sets] : options.variantOverrides)
    for (const auto& [set, variant] : sets) key += "\n" + prim + "{" + set + "=" + variant + "}";
  std::shared_ptr<const usd::ComposedStage>& slot = usdStages_[key];
  if (!slot)
    slot = std::make_shared<const usd::ComposedStage>(
        usd::composeStage(file, [](const std::string& id) { return usd::readLayerFile(id); }, options));
  return *slot;
}

std::vector<VariantSelection> AssetLibrary::unusedVariantSelections() const {
  std::vector<VariantSelection> out;
  for (size_t i = 0; i < selections_.size(); ++i)
    if (i >= selectionUsed_.size() || !selectionUsed_[i]) out.push_back(selections_[i]);
  return out;
}

std::vector<std::string> AssetLibrary::files() const {
  std::vector<std::string> out;
  for (const auto& entry : assets_) out.push_back(entry.first);
  for (const std::string& f : usdFiles_)
    if (std::find(out.begin(), out.end(), f) == out.end()) out.push_back(f);
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace sdg
