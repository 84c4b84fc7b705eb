// textureRandomizer — a random texture, projection, scale and rotation per
// geometry prim.
//
// Exposed variables (exposedVar:textureRandomizer:*):
//   textures:assets        asset[]  []       texture files
//   textures:csv           string   (Isaac's two pattern textures)  comma-separated texture files
//   projectUvwProbability  float    0.9      probability that project_uvw (world-space projection) is on
//   textureScaleRange      float2   (0.1, 1) (min, max) of the uniform texture scale
//   textureRotateRange     float2   (0, 45)  (min, max) of the texture rotation (degrees)
//   includeChildren        bool     true     every geometry prim below too
//   interval               uint     0
//   seed                   int      -1
//
// On the first play each geometry prim (Mesh, Cube, Sphere, ...) gets its own
// Material under /Behaviors/textureRandomizer/Looks/OmniPBR_<4 random chars>,
// bound strongerThanDescendants. Texture files: textures:assets first, then
// the CSV entries, resolved against the scene's asset roots (a missing file
// is an error naming it and every place searched). Per material and apply:
// diffuse_texture = choice(files), project_uvw = (u < probability),
// s = U(scale) into texture_scale (s, s), texture_rotate = U(rotate). An
// empty file list warns and skips every apply. On stop each prim gets back
// exactly the binding it had (Isaac Sim re-binds the computed material
// directly on the prim, even when it was inherited), and the created
// materials and empty scopes are removed.
//
// Example:
//   behaviors:
//     textureRandomizer: {interval: 5, textures:csv: "textures/wood.png,textures/bamboo.png"}
//
// Events: none (timeline driven).
#include <optional>

#include "assets/asset_resolver.h"
#include "assets/file_check.h"
#include "behavior/behavior_prims.h"
#include "behavior/interval_behavior.h"
#include "builtin_behaviors/builtin_behaviors.h"
#include "builtin_behaviors/spec_helpers.h"
#include "core/diagnostics.h"
#include "core/log.h"
#include "core/text.h"

namespace sdg {
namespace {

constexpr const char* kLooksPath = "/Behaviors/textureRandomizer/Looks";
constexpr std::string_view kNameCharacters = "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789";

class TextureRandomizer final : public IntervalBehavior {
  struct Entry {
    std::string prim;
    std::optional<MaterialBinding> originalBinding;
    std::string material;
  };

  void setup() override {
    probability_ = var<float>("projectUvwProbability");
    scaleRange_ = var<Vec2f>("textureScaleRange");
    rotateRange_ = var<Vec2f>("textureRotateRange");
    textures_ = resolveTextures();
    if (textures_.empty()) log::warn(primPath() + ": textureRandomizer: no textures given; nothing will change");
    if (isSetUp()) return;
    rng_ = makeRng(var<int32_t>("seed"));
    entries_.clear();
    std::vector<Prim*> prims = selectPrims(var<bool>("includeChildren"), [](const Prim& p) { return p.typeInfo().gprim; });
    if (prims.empty()) return;
    looks_ = nextFreePath(stage(), kLooksPath);
    ensureScope(stage(), looks_);
    for (Prim* p : prims) {
      std::string suffix;
      for (int i = 0; i < 4; ++i) suffix += kNameCharacters[rng_.index(kNameCharacters.size())];
      std::string materialPath = nextFreePath(stage(), looks_ + "/OmniPBR_" + suffix);
      Prim& material = stage().definePrim(materialPath, PrimType::Material);
      material.setAttribute("inputs:diffuse_texture", Value::makeAsset(""));
      material.setAttribute("inputs:project_uvw", Value::makeBool(false));
      material.setAttribute("inputs:texture_scale", Value::makeFloat2(1.0f, 1.0f));
      material.setAttribute("inputs:texture_rotate", Value::makeFloat(0.0f));
      entries_.push_back({p->path(), p->material(), materialPath});
      p->material() = MaterialBinding{materialPath, "strongerThanDescendants"};
    }
  }

  void apply() override {
    if (textures_.empty()) return;
    for (const Entry& e : entries_) {
      Prim& m = *stage().find(e.material);
      m.setAttribute("inputs:diffuse_texture", Value::makeAsset(textures_[rng_.index(textures_.size())]));
      m.setAttribute("inputs:project_uvw", Value::makeBool(rng_.bernoulli(probability_)));
      auto s = static_cast<float>(rng_.uniform(scaleRange_.x(), scaleRange_.y()));
      m.setAttribute("inputs:texture_scale", Value::makeFloat2(s, s));
      m.setAttribute("inputs:texture_rotate",
                     Value::makeFloat(static_cast<float>(rng_.uniform(rotateRange_.x(), rotateRange_.y()))));
    }
  }

  void restore() override {
    for (const Entry& e : entries_) {
      if (Prim* p = stage().find(e.prim)) p->material() = e.originalBinding;
      stage().removePrim(e.material);
    }
    if (!entries_.empty()) removeEmptyScopes(stage(), kBehaviorsScope);
    entries_.clear();
  }

  // textures:assets, then the CSV entries; each must resolve to a readable
  // file (validate checked them already; a --set or a behavior may not
  // have), but the material keeps the path as written so outputs do not
  // depend on the working directory (the renderer resolves it again).
  std::vector<std::string> resolveTextures() const {
    static const AssetResolver kNoRoots;
    const AssetResolver& resolver = context().assets ? *context().assets : kNoRoots;
    std::vector<std::string> files;
    for (std::string_view name : {"textures:assets", "textures:csv"}) {
      const Attribute* attr = prim().findAttribute(attributeName(name));
      if (!attr) continue;
      for (std::string& file : fileEntriesOf(*attr, *spec().findVariable(name), resolver, primPath()))
        if (std::optional<std::string> problem = fileProblem(file, FileKind::Image, resolver))
          throw SceneError(locOf(name), primPath() + ": textureRandomizer: " + *problem);
        else
          files.push_back(std::move(file));
    }
    return files;
  }

  SourceLoc locOf(std::string_view variable) const {
    const Attribute* a = prim().findAttribute(attributeName(variable));
    return a && a->loc.known() ? a->loc : prim().loc();
  }

  Rng rng_;
  std::vector<Entry> entries_;
  std::vector<std::string> textures_;
  std::string looks_;
  float probability_ = 0.9f;
  Vec2f scaleRange_, rotateRange_;
};

}  // namespace

BehaviorSpec textureRandomizerSpec() {
  using namespace behaviors;
  BehaviorSpec spec;
  spec.name = "textureRandomizer";
  spec.summary = "Gives each geometry prim its own material with a random texture, projection, scale and rotation.";
  AttributeSpec probability = variable("projectUvwProbability", Value::makeFloat(0.9f),
                                       "Probability that the texture is projected in world space (project_uvw).");
  probability.minimum = 0.0;
  spec.variables = {
      includeChildrenVariable(),
      intervalVariable(),
      fileVariable("textures:assets", Value::makeAssetArray({}), FileKind::Image, "Texture files."),
      fileVariable("textures:csv",
               Value::makeString("/Isaac/Materials/Textures/Patterns/nv_bamboo_desktop.jpg,"
                                 "/Isaac/Materials/Textures/Patterns/nv_brick_grey.jpg"),
               FileKind::Image,
               "Comma-separated texture files, used after textures:assets."),
      probability,
      variable("textureScaleRange", Value::makeFloat2(0.1f, 1.0f), "(min, max) of the uniform texture scale."),
      variable("textureRotateRange", Value::makeFloat2(0.0f, 45.0f), "(min, max) of the texture rotation (degrees)."),
      seedVariable(),
  };
  spec.example = "textureRandomizer: {interval: 5, textures:csv: \"textures/wood.png,textures/bamboo.png\"}";
  spec.validate = [](const Prim& prim, Diagnostics& diag) {
    behaviors::checkRange(prim, "textureRandomizer", "textureScaleRange", "", diag);
    behaviors::checkRange(prim, "textureRandomizer", "textureRotateRange", "", diag);
    const Attribute* p = prim.findAttribute("exposedVar:textureRandomizer:projectUvwProbability");
    if (p && p->value.get<float>() > 1.0f)
      diag.error(p->loc.known() ? p->loc : prim.loc(),
                 prim.path() + ".exposedVar:textureRandomizer:projectUvwProbability: a probability is at most 1, found " +
                     text::formatFloat(p->value.get<float>()));
  };
  return spec;
}

std::unique_ptr<Behavior> makeTextureRandomizer() { return std::make_unique<TextureRandomizer>(); }

}  // namespace sdg
