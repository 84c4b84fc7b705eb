// importUsdMaterial (scene_io/usd_import.h): a USD Material and the shader
// network below it onto a stage Material (OmniPBR's inputs, prim_types.cpp).
//
//   outputs:mdl:surface -> Shader with info:mdl:sourceAsset @OmniPBR.mdl@:
//       every input whose name the stage Material has, read with the YAML
//       loader's checks (an input connected to the material's interface
//       takes the interface's value);
//   outputs:surface -> UsdPreviewSurface: diffuseColor, roughness, metallic,
//       opacity, opacityThreshold, normal as constants or UsdUVTexture
//       outputs (channel rgb/r/g/b/a; roughness .g + metallic .b of one file
//       is an ORM map), the texture's st through UsdTransform2d
//       (scale/rotation) to a UsdPrimvarReader_float2;
//   anything else (MaterialX, other MDL): grey, with one warning; bindings
//       to it are left out so bound prims keep their displayColor.
//
// What a supported material says that the stage cannot hold (emission,
// clamp wrapping, a texture offset, ...) is listed in one warning per
// material rather than dropped silently.
#include "scene_io/usd_materials.h"

#include <cmath>
#include <optional>

#include "core/text.h"
#include "scene_io/usd_import.h"
#include "scene_io/usd_value_node.h"

namespace sdg {
namespace {

constexpr int kMaxConnectionHops = 32;

// Where an input's value comes from: a shader's output, or a constant.
struct Source {
  const usd::ComposedPrim* shader = nullptr;
  std::string output;  // "outputs:rgb"
  const usd::ComposedProperty* constant = nullptr;
};

std::pair<std::string, std::string> splitPropertyPath(const std::string& path) {
  const size_t dot = path.rfind('.');
  if (dot == std::string::npos) return {path, ""};
  return {path.substr(0, dot), path.substr(dot + 1)};
}

// Follows connections through NodeGraph / Material interface properties to
// a Shader's output or an authored value.
Source resolveSource(const usd::ComposedStage& composed, const usd::ComposedProperty* property) {
  for (int hop = 0; property && hop < kMaxConnectionHops; ++hop) {
    if (property->connections.empty())
      return property->value.empty() || property->value.kind == usd::Kind::ValueBlock ? Source{} : Source{nullptr, "", property};
    auto [primPath, name] = splitPropertyPath(property->connections.front());
    const usd::ComposedPrim* prim = composed.prim(primPath);
    if (!prim) return {};
    if (prim->typeName == "Shader") return {prim, name, nullptr};
    property = prim->property(name);
  }
  return {};
}

std::string textOf(const usd::ComposedPrim& prim, const std::string& name) {
  const usd::ComposedProperty* p = prim.property(name);
  if (!p || !usd::isText(p->value.kind) || p->value.isArray || p->value.strings.empty()) return "";
  return p->value.strings.front();
}

std::string shaderId(const usd::ComposedPrim& shader) { return textOf(shader, "info:id"); }

bool isOmniPbr(const usd::ComposedPrim& shader) {
  std::string asset = textOf(shader, "info:mdl:sourceAsset");
  const size_t slash = asset.find_last_of("/\\");
  if (slash != std::string::npos) asset = asset.substr(slash + 1);
  const std::string sub = textOf(shader, "info:mdl:sourceAsset:subIdentifier");
  return asset == "OmniPBR.mdl" && (sub.empty() || sub == "OmniPBR");
}

enum class SurfaceKind { OmniPbr, PreviewSurface, Unsupported };

struct Surface {
  SurfaceKind kind = SurfaceKind::Unsupported;
  const usd::ComposedPrim* shader = nullptr;
  std::string what;  // for the fallback warning: what the material has instead
};

Surface chooseSurface(const usd::ComposedStage& composed, const usd::ComposedPrim& material) {
  Surface s;
  if (const usd::ComposedProperty* mdl = material.property("outputs:mdl:surface")) {
    Source src = resolveSource(composed, mdl);
    if (src.shader && isOmniPbr(*src.shader)) return {SurfaceKind::OmniPbr, src.shader, ""};
    if (src.shader) {
      const std::string asset = textOf(*src.shader, "info:mdl:sourceAsset");
      s.what = "an MDL surface (" + (asset.empty() ? src.shader->path : asset) + ") other than OmniPBR";
    }
  }
  if (const usd::ComposedProperty* preview = material.property("outputs:surface")) {
    Source src = resolveSource(composed, preview);
    if (src.shader && shaderId(*src.shader) == "UsdPreviewSurface") return {SurfaceKind::PreviewSurface, src.shader, ""};
    if (src.shader && s.what.empty()) s.what = "a surface shader " + text::quote(shaderId(*src.shader));
  }
  if (s.what.empty()) {
    for (const usd::ComposedProperty& p : material.properties)
      if (p.name.starts_with("outputs:") && p.name.ends_with(":surface")) {
        s.what = "only " + p.name + (p.name.find("mtlx") != std::string::npos ? " (MaterialX)" : "");
        break;
      }
  }
  if (s.what.empty()) s.what = "no surface output";
  return s;
}

// The numbers of a numeric constant (empty when it is not one).
std::vector<double> numbersOf(const usd::ComposedProperty* p) {
  if (!p || !usd::isNumeric(p->value.kind) || p->value.isArray) return {};
  return p->value.numbers;
}

struct UvTransform {
  float scale[2] = {1, 1};
  float rotation = 0;
  float translation[2] = {0, 0};
  bool operator==(const UvTransform& o) const {
    return scale[0] == o.scale[0] && scale[1] == o.scale[1] && rotation == o.rotation &&
           translation[0] == o.translation[0] && translation[1] == o.translation[1];
  }
};

struct Texture {
  const usd::ComposedPrim* shader = nullptr;
  const usd::ComposedProperty* file = nullptr;
  std::string channel;  // "rgb", "r", ...
  std::vector<double> scale, bias;
  std::string colorSpace;
  std::optional<UvTransform> transform;
};

class PreviewMapper {
 public:
  PreviewMapper(const usd::ComposedStage& composed, const usd::ComposedPrim& shader, Prim& stagePrim, Diagnostics& diag,
                std::vector<std::string>& notes)
      : composed_(composed), shader_(shader), prim_(stagePrim), diag_(diag), notes_(notes) {}

  void map() {
    diffuse();
    roughnessAndMetallic();
    opacity();
    normal();
    unsupportedInputs();
    if (transform_) {
      prim_.setAttribute("inputs:texture_scale", Value::makeFloat2(transform_->scale[0], transform_->scale[1]));
      prim_.setAttribute("inputs:texture_rotate", Value::makeFloat(transform_->rotation));
      if (transform_->translation[0] != 0 || transform_->translation[1] != 0)
        notes_.push_back("the UsdTransform2d translation (the stage's materials have no texture offset)");
    }
  }

 private:
  const usd::ComposedStage& composed_;
  const usd::ComposedPrim& shader_;
  Prim& prim_;
  Diagnostics& diag_;
  std::vector<std::string>& notes_;
  std::optional<UvTransform> transform_;

  Source input(const std::string& name) { return resolveSource(composed_, shader_.property("inputs:" + name)); }

  void setFrom(const std::string& stageName, const usd::ComposedProperty& p) {
    const AttributeSpec* spec = findSchemaAttribute(PrimType::Material, stageName);
    std::optional<Value> v = readUsdValue(p, *spec, prim_.path() + "." + stageName + " (from " + p.name + ")", diag_);
    if (!v) return;
    Attribute& a = prim_.setAttribute(stageName, *v);
    a.loc = p.loc;
  }
  void setFlag(const std::string& name, bool on, const SourceLoc& loc) { prim_.setAttribute(name, Value::makeBool(on)).loc = loc; }

  std::optional<UvTransform> readTransform(const usd::ComposedProperty* st) {
    Source src = resolveSource(composed_, st);
    if (!src.shader || shaderId(*src.shader) != "UsdTransform2d") return std::nullopt;
    UvTransform t;
    std::vector<double> scale = numbersOf(resolveSource(composed_, src.shader->property("inputs:scale")).constant);
    std::vector<double> rotation = numbersOf(resolveSource(composed_, src.shader->property("inputs:rotation")).constant);
    std::vector<double> translation = numbersOf(resolveSource(composed_, src.shader->property("inputs:translation")).constant);
    if (scale.size() == 2) t.scale[0] = float(scale[0]), t.scale[1] = float(scale[1]);
    if (rotation.size() == 1) t.rotation = float(rotation[0]);
    if (translation.size() == 2) t.translation[0] = float(translation[0]), t.translation[1] = float(translation[1]);
    return t;
  }

  // The texture an input is connected to; notes it when it is another shader.
  std::optional<Texture> texture(const std::string& inputName, const Source& src) {
    if (!src.shader) return std::nullopt;
    const std::string id = shaderId(*src.shader);
    if (id != "UsdUVTexture") {
      notes_.push_back("inputs:" + inputName + " (connected to " + (id.empty() ? src.shader->path : id) + ")");
      return std::nullopt;
    }
    Texture t;
    t.shader = src.shader;
    t.file = resolveSource(composed_, src.shader->property("inputs:file")).constant;
    t.channel = src.output.starts_with("outputs:") ? src.output.substr(8) : src.output;
    t.scale = numbersOf(resolveSource(composed_, src.shader->property("inputs:scale")).constant);
    t.bias = numbersOf(resolveSource(composed_, src.shader->property("inputs:bias")).constant);
    t.colorSpace = textOf(*src.shader, "inputs:sourceColorSpace");
    t.transform = readTransform(src.shader->property("inputs:st"));
    for (const char* wrap : {"inputs:wrapS", "inputs:wrapT"}) {
      const std::string w = textOf(*src.shader, wrap);
      if (!w.empty() && w != "repeat" && w != "useMetadata")
        notes_.push_back(src.shader->path + "." + wrap + " = " + w + " (the stage's textures repeat)");
    }
    if (!t.file) {
      notes_.push_back("inputs:" + inputName + " (its UsdUVTexture " + src.shader->path + " has no inputs:file)");
      return std::nullopt;
    }
    if (t.transform) {
      if (!transform_) transform_ = t.transform;
      else if (!(*transform_ == *t.transform))
        notes_.push_back(src.shader->path + "'s UsdTransform2d (the stage's material has one texture transform; the first one is used)");
    }
    return t;
  }

  bool isIdentityScaleBias(const Texture& t) const {
    for (size_t i = 0; i < t.scale.size() && i < 3; ++i)
      if (t.scale[i] != 1) return false;
    for (size_t i = 0; i < t.bias.size() && i < 3; ++i)
      if (t.bias[i] != 0) return false;
    return true;
  }

  void noteScaleBias(const Texture& t, const std::string& inputName) {
    if (!isIdentityScaleBias(t)) notes_.push_back("the scale/bias of " + t.shader->path + " (feeding inputs:" + inputName + ")");
  }

  void diffuse() {
    Source src = input("diffuseColor");
    if (src.constant) return setFrom("inputs:diffuse_color_constant", *src.constant);
    std::optional<Texture> t = texture("diffuseColor", src);
    if (!t) return;
    if (t->channel != "rgb") {
      notes_.push_back("inputs:diffuseColor from channel " + t->channel + " (the stage reads a colour texture's rgb)");
      return;
    }
    if (t->colorSpace == "raw") notes_.push_back(t->shader->path + " sourceColorSpace raw (colour textures are read as sRGB)");
    noteScaleBias(*t, "diffuseColor");
    setFrom("inputs:diffuse_texture", *t->file);
  }

  void roughnessAndMetallic() {
    Source rough = input("roughness"), metal = input("metallic");
    if (rough.constant) setFrom("inputs:reflection_roughness_constant", *rough.constant);
    if (metal.constant) setFrom("inputs:metallic_constant", *metal.constant);
    std::optional<Texture> r = texture("roughness", rough), m = texture("metallic", metal);
    auto same = [](const Texture& a, const Texture& b) { return a.file->resolvedAssets == b.file->resolvedAssets; };
    if (r && m && r->channel == "g" && m->channel == "b" && same(*r, *m)) {  // glTF's packing: occlusion, roughness, metallic
      noteScaleBias(*r, "roughness");
      setFrom("inputs:ORM_texture", *r->file);
      setFlag("inputs:enable_ORM_texture", true, r->file->loc);
      return;
    }
    auto single = [&](const std::optional<Texture>& t, const std::string& input, const std::string& file,
                      const std::string& influence) {
      if (!t) return;
      if (t->channel != "r") {
        notes_.push_back("inputs:" + input + " from channel " + t->channel +
                         " (the stage reads red, or green and blue of one ORM file for roughness and metallic)");
        return;
      }
      noteScaleBias(*t, input);
      setFrom(file, *t->file);
      prim_.setAttribute(influence, Value::makeFloat(1.0f)).loc = t->file->loc;
    };
    single(r, "roughness", "inputs:reflectionroughness_texture", "inputs:reflection_roughness_texture_influence");
    single(m, "metallic", "inputs:metallic_texture", "inputs:metallic_texture_influence");
  }

  void opacity() {
    Source op = input("opacity");
    Source threshold = input("opacityThreshold");
    if (threshold.constant) setFrom("inputs:opacity_threshold", *threshold.constant);
    if (op.constant) {
      std::vector<double> v = numbersOf(op.constant);
      setFrom("inputs:opacity_constant", *op.constant);
      if (v.size() == 1 && v[0] < 1) {
        setFlag("inputs:enable_opacity", true, op.constant->loc);
        std::vector<double> cut = numbersOf(threshold.constant);
        if ((cut.empty() || cut[0] == 0) && v[0] > 0)
          notes_.push_back("partial opacity " + text::formatNumber(v[0]) + " (drawn as a cut-out at 0.5)");
      }
      return;
    }
    std::optional<Texture> t = texture("opacity", op);
    if (!t) return;
    if (t->channel != "r") {
      notes_.push_back("inputs:opacity from channel " + t->channel + " (the stage reads an opacity map's red channel)");
      return;
    }
    noteScaleBias(*t, "opacity");
    setFrom("inputs:opacity_texture", *t->file);
    setFlag("inputs:enable_opacity_texture", true, t->file->loc);
    setFlag("inputs:enable_opacity", true, t->file->loc);
  }

  void normal() {
    Source src = input("normal");
    if (src.constant) {
      std::vector<double> n = numbersOf(src.constant);
      if (!(n.size() == 3 && n[0] == 0 && n[1] == 0 && n[2] == 1)) notes_.push_back("a constant inputs:normal");
      return;
    }
    std::optional<Texture> t = texture("normal", src);
    if (!t) return;
    if (t->channel != "rgb") {
      notes_.push_back("inputs:normal from channel " + t->channel);
      return;
    }
    // USD's normal maps decode with scale 2 and bias -1 (the stage does so
    // itself); anything else (a flipped green axis, say) is not a map the
    // stage can read.
    auto all = [](const std::vector<double>& v, double x) {
      for (size_t i = 0; i < v.size() && i < 3; ++i)
        if (v[i] != x) return false;
      return true;
    };
    const bool standard = (t->scale.empty() || all(t->scale, 2)) && (t->bias.empty() || all(t->bias, -1));
    if (!standard && !isIdentityScaleBias(*t)) {
      notes_.push_back("the normal map " + t->shader->path +
                       " with a scale/bias other than 2/-1 (the stage reads +Y-up tangent-space maps)");
      return;
    }
    setFrom("inputs:normalmap_texture", *t->file);
  }

  // Inputs the stage has no place for, when authored with a value that
  // changes the look.
  void unsupportedInputs() {
    struct Default {
      const char* name;
      std::vector<double> value;
    };
    static const Default kDefaults[] = {{"emissiveColor", {0, 0, 0}}, {"useSpecularWorkflow", {0}},
                                        {"clearcoat", {0}}, {"ior", {1.5}}, {"displacement", {0}},
                                        {"occlusion", {1}}};
    for (const Default& d : kDefaults) {
      const usd::ComposedProperty* p = shader_.property(std::string("inputs:") + d.name);
      if (!p) continue;
      Source src = resolveSource(composed_, p);
      if (src.constant && numbersOf(src.constant) == d.value) continue;
      if (!src.constant && !src.shader) continue;
      notes_.push_back(std::string("inputs:") + d.name);
    }
  }
};

void mapOmniPbr(const usd::ComposedStage& composed, const usd::ComposedPrim& shader, Prim& stagePrim,
                Diagnostics& diag, std::vector<std::string>& notes) {
  for (const usd::ComposedProperty& p : shader.properties) {
    if (!p.name.starts_with("inputs:")) continue;
    Source src = resolveSource(composed, &p);
    if (!src.constant) {
      if (src.shader) notes.push_back(p.name + " (connected to a shader)");
      continue;
    }
    const AttributeSpec* spec = findSchemaAttribute(PrimType::Material, p.name);
    if (!spec) {
      notes.push_back(p.name);
      continue;
    }
    std::optional<Value> v = readUsdValue(*src.constant, *spec, stagePrim.path() + "." + p.name, diag);
    if (!v) continue;
    stagePrim.setAttribute(p.name, *v).loc = src.constant->loc;
  }
}

std::string where(const usd::ComposedPrim& prim) {
  const std::string loc = prim.loc.str();
  return loc.empty() ? "" : " (" + loc + ")";
}

}  // namespace

bool usdMaterialIsSupported(const usd::ComposedStage& composed, const usd::ComposedPrim& material) {
  return chooseSurface(composed, material).kind != SurfaceKind::Unsupported;
}

void importUsdMaterial(const usd::ComposedStage& composed, const usd::ComposedPrim& material, Prim& stagePrim,
                       Diagnostics& diag, UsdImportReport& report) {
  Surface surface = chooseSurface(composed, material);
  std::vector<std::string> notes;
  switch (surface.kind) {
    case SurfaceKind::OmniPbr:
      mapOmniPbr(composed, *surface.shader, stagePrim, diag, notes);
      break;
    case SurfaceKind::PreviewSurface:
      PreviewMapper(composed, *surface.shader, stagePrim, diag, notes).map();
      break;
    case SurfaceKind::Unsupported:
      stagePrim.setAttribute("inputs:diffuse_color_constant", Value::makeColor3f(Vec3f(0.5f, 0.5f, 0.5f)));
      report.losses.note(UsdLossKind::MaterialNetwork, surface.what, material.loc, material.path);
      report.warnings.push_back("material " + material.path + where(material) + " has " + surface.what +
                                "; only UsdPreviewSurface and MDL OmniPBR are read, so prims bound to it keep "
                                "their primvars:displayColor (grey when none)");
      return;
  }
  for (const std::string& note : notes)
    report.losses.note(UsdLossKind::MaterialInput, note.substr(0, note.find(" (")), material.loc, material.path);
  if (!notes.empty())
    report.warnings.push_back("material " + material.path + where(material) + ": not carried over: " +
                              text::join(notes, "; "));
}

}  // namespace sdg
