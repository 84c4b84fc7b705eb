#include "scene_io/usd_export.h"

#include <filesystem>
#include <map>
#include <set>

#include "assets/mesh_source.h"
#include "scene_io/usd_lens_schemas.h"
#include "scene_io/usd_prim_labels.h"
#include "stage/behavior_spec.h"
#include "stage/value_json.h"

namespace sdg {
namespace {

using usd::Kind;
using usd::Spec;
using usd::SpecType;
namespace field = usd::field;

const char* kPrototypes = "/Prototypes";

// A stage value as a USD value and its type name. Matrices go from the
// stage's column-vector convention to USD's row vectors (the transpose,
// written row by row); quaternions are (real, i, j, k) as USD stores them.
struct UsdTyped {
  usd::Value value;
  std::string typeName;
};

// A file the scene names, absolute (as found by the resolver) so that the
// layer works from any folder; unchanged when it is not found.
std::string absoluteAsset(const AssetResolver& assets, const std::string& path) {
  std::optional<std::string> found = path.empty() ? std::nullopt : assets.resolve(path);
  return found ? std::filesystem::absolute(*found).lexically_normal().string() : path;
}

UsdTyped toUsd(const Value& v, const AssetResolver& assets) {
  auto num = [](Kind k, std::vector<double> c) { return usd::Value::scalar(k, std::move(c)); };
  auto asset = [&](const std::string& path) { return absoluteAsset(assets, path); };
  std::string name(valueTypeName(v.type()));
  switch (v.type()) {
    case ValueType::Bool: return {num(Kind::Bool, {v.get<bool>() ? 1.0 : 0.0}), name};
    case ValueType::Int: return {num(Kind::Int, {double(v.get<int32_t>())}), name};
    case ValueType::UInt: return {num(Kind::UInt, {double(v.get<uint32_t>())}), name};
    case ValueType::Float: return {num(Kind::Float, {double(v.get<float>())}), name};
    case ValueType::Double: return {num(Kind::Double, {v.get<double>()}), name};
    case ValueType::Int2: {
      const Vec2i& a = v.get<Vec2i>();
      return {num(Kind::Vec2i, {double(a.x()), double(a.y())}), name};
    }
    case ValueType::Float2: {
      const Vec2f& a = v.get<Vec2f>();
      return {num(Kind::Vec2f, {double(a.x()), double(a.y())}), name};
    }
    case ValueType::Float3:
    case ValueType::Color3f: {
      const Vec3f& a = v.get<Vec3f>();
      return {num(Kind::Vec3f, {double(a.x()), double(a.y()), double(a.z())}), name};
    }
    case ValueType::Double3:
    case ValueType::Vector3d: {
      const Vec3d& a = v.get<Vec3d>();
      return {num(Kind::Vec3d, {a.x(), a.y(), a.z()}), name};
    }
    case ValueType::Quatf: {
      const Quatf& q = v.get<Quatf>();
      return {num(Kind::Quatf, {double(q.w()), double(q.x()), double(q.y()), double(q.z())}), name};
    }
    case ValueType::Quatd: {
      const Quatd& q = v.get<Quatd>();
      return {num(Kind::Quatd, {q.w(), q.x(), q.y(), q.z()}), name};
    }
    case ValueType::Matrix4d: {
      const Matrix4d& m = v.get<Matrix4d>();
      std::vector<double> rows;
      for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c) rows.push_back(m(c, r));
      return {num(Kind::Matrix4d, std::move(rows)), name};
    }
    case ValueType::String: return {usd::Value::text(Kind::String, v.get<std::string>()), name};
    case ValueType::Token: return {usd::Value::text(Kind::Token, v.get<std::string>()), name};
    case ValueType::Asset: return {usd::Value::text(Kind::AssetPath, asset(v.get<std::string>())), name};
    case ValueType::AssetArray: {
      std::vector<std::string> items;
      for (const std::string& p : v.get<std::vector<std::string>>()) items.push_back(asset(p));
      return {usd::Value::textArray(Kind::AssetPath, std::move(items)), name};
    }
    case ValueType::StringArray:
      return {usd::Value::textArray(Kind::String, v.get<std::vector<std::string>>()), name};
    // Inline geometry (meshes imported from USD): the same arrays back.
    case ValueType::IntArray: {
      std::vector<double> xs;
      for (int32_t i : v.get<IntArray>().items()) xs.push_back(double(i));
      return {usd::Value::array(Kind::Int, std::move(xs)), name};
    }
    case ValueType::FloatArray:
    case ValueType::Point3fArray:
    case ValueType::Normal3fArray:
    case ValueType::Color3fArray:
    case ValueType::TexCoord2fArray: {
      const Kind kind = v.type() == ValueType::FloatArray        ? Kind::Float
                        : v.type() == ValueType::TexCoord2fArray ? Kind::Vec2f
                                                                 : Kind::Vec3f;
      std::vector<double> xs;
      for (float f : v.get<FloatArray>().items()) xs.push_back(double(f));
      return {usd::Value::array(kind, std::move(xs)), name};
    }
  }
  return {};
}

// JSON (settings, events) as a customLayerData value: objects become
// dictionaries, numbers doubles, lists of numbers or strings arrays.
usd::Value jsonToUsd(const nlohmann::ordered_json& j) {
  if (j.is_object()) {
    usd::Dictionary d;
    for (const auto& [k, v] : j.items()) d[k] = jsonToUsd(v);
    return usd::Value::dict(std::move(d));
  }
  if (j.is_boolean()) return usd::Value::scalar(Kind::Bool, {j.get<bool>() ? 1.0 : 0.0});
  if (j.is_number_integer()) return usd::Value::scalar(Kind::Int64, {j.get<double>()});
  if (j.is_number()) return usd::Value::scalar(Kind::Double, {j.get<double>()});
  if (j.is_string()) return usd::Value::text(Kind::String, j.get<std::string>());
  if (j.is_array()) {
    bool numbers = !j.empty(), strings = !j.empty();
    for (const auto& e : j) {
      numbers = numbers && e.is_number();
      strings = strings && e.is_string();
    }
    if (numbers) {
      std::vector<double> xs;
      for (const auto& e : j) xs.push_back(e.get<double>());
      return usd::Value::array(Kind::Double, std::move(xs));
    }
    if (strings) {
      std::vector<std::string> xs;
      for (const auto& e : j) xs.push_back(e.get<std::string>());
      return usd::Value::textArray(Kind::String, std::move(xs));
    }
  }
  if (j.is_array() && j.empty()) return usd::Value::textArray(Kind::String, {});
  return usd::Value::text(Kind::String, j.dump());  // nested lists, null
}

nlohmann::ordered_json optionsJson(const OptionSet& options) {
  nlohmann::ordered_json j = nlohmann::ordered_json::object();
  for (const auto& [name, value] : options.values()) j[name] = valueToJson(value);
  return j;
}

// A payload's keys in their order: a USD dictionary keeps its keys sorted.
std::vector<std::string> payloadKeys(const Payload& payload) {
  std::vector<std::string> keys;
  for (const auto& entry : payload.entries()) keys.push_back(entry.first);
  return keys;
}

nlohmann::ordered_json payloadJson(const Payload& payload) {
  nlohmann::ordered_json j = nlohmann::ordered_json::object();
  // Not a structured binding: clang 14 (the fuzz build) cannot capture one in a lambda.
  for (const auto& entry : payload.entries()) {
    const std::string& key = entry.first;
    std::visit([&](const auto& x) { j[key] = x; }, entry.second);
  }
  return j;
}

// A name USD accepts as a prim name: letters, digits and '_', not starting with a digit.
std::string identifierFrom(const std::string& text) {
  std::string out;
  for (char c : text) out += (std::isalnum(static_cast<unsigned char>(c)) || c == '_') ? c : '_';
  if (out.empty() || std::isdigit(static_cast<unsigned char>(out[0]))) out = "_" + out;
  return out;
}

class Exporter {
 public:
  Exporter(const Scene& scene, const AssetResolver& assets, const UsdExportOptions& options)
      : scene_(scene), assets_(assets), options_(options) {}

  usd::Layer build() {
    layer_.format = "usda";
    Spec& root = layer_.specs["/"];
    root.type = SpecType::PseudoRoot;
    const StageMetadata& meta = scene_.stage.metadata();
    root.fields[field::kUpAxis] = usd::Value::text(Kind::Token, meta.upAxis);
    root.fields[field::kMetersPerUnit] = usd::Value::scalar(Kind::Double, {meta.metersPerUnit});
    root.fields[field::kTimeCodesPerSecond] = usd::Value::scalar(Kind::Double, {meta.timeCodesPerSecond});
    std::vector<std::string> rootNames;
    for (const Prim* child : scene_.stage.pseudoRoot().children()) {
      rootNames.emplace_back(child->name());
      writePrim(*child);
    }
    if (!rootNames.empty()) root.fields[field::kDefaultPrim] = usd::Value::text(Kind::Token, rootNames.front());
    if (!prototypes_.empty()) {
      rootNames.push_back(std::string(kPrototypes).substr(1));
      Spec& scope = primSpec(kPrototypes, usd::Specifier::Class, "Scope");
      std::vector<std::string> names;
      for (const auto& [key, name] : prototypeOrder_) names.push_back(name);
      scope.fields[field::kPrimChildren] = usd::Value::textArray(Kind::TokenVector, names);
    }
    root.fields[field::kPrimChildren] = usd::Value::textArray(Kind::TokenVector, rootNames);
    root.fields[field::kCustomLayerData] = usd::Value::dict({{"sdgbehave", sceneSettings()}});
    return std::move(layer_);
  }

 private:
  Spec& primSpec(const std::string& path, usd::Specifier specifier, const std::string& typeName) {
    Spec& s = layer_.specs[path];
    s.type = SpecType::Prim;
    s.fields[field::kSpecifier] = usd::Value::specifier(specifier);
    if (!typeName.empty()) s.fields[field::kTypeName] = usd::Value::text(Kind::Token, typeName);
    return s;
  }

  // An attribute spec; its name is added to the prim's property order.
  Spec& attribute(const std::string& prim, const std::string& name, usd::Value value, const std::string& typeName,
                  bool custom = false, usd::Variability variability = usd::Variability::Varying) {
    properties_[prim].push_back(name);
    Spec& s = layer_.specs[prim + "." + name];
    s.type = SpecType::Attribute;
    s.fields[field::kTypeName] = usd::Value::text(Kind::Token, typeName);
    s.fields[field::kCustom] = usd::Value::scalar(Kind::Bool, {custom ? 1.0 : 0.0});
    s.fields[field::kVariability] = usd::Value::variability(variability);
    if (!value.empty()) s.fields[field::kDefault] = std::move(value);
    return s;
  }
  void stageAttribute(const std::string& prim, const std::string& name, const Value& v, bool custom) {
    UsdTyped t = toUsd(v, assets_);
    bool uniform = name == "doubleSided" || name == "axis" || name == "purpose" || name == "subdivisionScheme" ||
                   name == "interpolateBoundary" || name == "faceVaryingLinearInterpolation" ||
                   name == "triangleSubdivisionRule" || name == "orientation";
    attribute(prim, name, std::move(t.value), t.typeName, custom,
              uniform ? usd::Variability::Uniform : usd::Variability::Varying);
  }
  void relationship(const std::string& prim, const std::string& name, const std::string& target) {
    properties_[prim].push_back(name);
    Spec& s = layer_.specs[prim + "." + name];
    s.type = SpecType::Relationship;
    s.fields[field::kCustom] = usd::Value::scalar(Kind::Bool, {0.0});
    s.fields[field::kVariability] = usd::Value::variability(usd::Variability::Uniform);
    usd::Value targets;
    targets.kind = Kind::PathListOp;
    targets.textListOp = std::make_shared<usd::ListOp<std::string>>();
    targets.textListOp->isExplicit = true;
    targets.textListOp->explicitItems = {target};
    s.fields[field::kTargetPaths] = std::move(targets);
  }
  void connect(const std::string& prim, const std::string& name, const std::string& source, const std::string& typeName) {
    Spec& s = attribute(prim, name, {}, typeName);
    usd::Value c;
    c.kind = Kind::PathListOp;
    c.textListOp = std::make_shared<usd::ListOp<std::string>>();
    c.textListOp->isExplicit = true;
    c.textListOp->explicitItems = {source};
    s.fields[field::kConnectionPaths] = std::move(c);
  }
  static void prependApiSchemas(Spec& prim, const std::vector<std::string>& schemas) {
    if (schemas.empty()) return;
    usd::Value v;
    v.kind = Kind::TokenListOp;
    v.textListOp = std::make_shared<usd::ListOp<std::string>>();
    v.textListOp->prependedItems = schemas;
    prim.fields[field::kApiSchemas] = std::move(v);
  }
  void finishProperties(const std::string& prim) {
    auto it = properties_.find(prim);
    if (it != properties_.end())
      layer_.specs[prim].fields[field::kProperties] = usd::Value::textArray(Kind::TokenVector, it->second);
  }

  void writePrim(const Prim& prim) {
    const std::string& path = prim.path();
    Spec& spec = primSpec(path, usd::Specifier::Def, std::string(prim.typeInfo().name));
    std::vector<std::string> apiSchemas;
    usd::Dictionary customData;
    fallbacks_.clear();
    if (prim.type() == PrimType::Mesh) writeMeshReference(prim, spec);
    if (prim.type() == PrimType::Material) writeMaterial(prim);
    else writeAttributes(prim);
    writeXformOps(prim);
    if (prim.material()) {
      apiSchemas.push_back("MaterialBindingAPI");
      relationship(path, "material:binding", prim.material()->path);
      layer_.specs[path + ".material:binding"].fields["bindMaterialAs"] =
          usd::Value::text(Kind::Token, prim.material()->strength);
    }
    for (const auto& [key, value] : prim.metadata()) {
      if (key == "kind") spec.fields[field::kKind] = usd::Value::text(Kind::Token, value);
      else if (key == "documentation") spec.fields[field::kDocumentation] = usd::Value::text(Kind::String, value);
      else customData[key] = usd::Value::text(Kind::String, value);
    }
    // What the layer states only for other tools (the stage's fallbacks,
    // a prototype's subdivisionScheme): the import leaves it unauthored.
    if (prim.type() == PrimType::Mesh && !prim.getString("asset").empty() && !prim.findAttribute("subdivisionScheme"))
      fallbacks_.push_back("subdivisionScheme");
    if (!fallbacks_.empty()) customData[kFallbacksKey] = usd::Value::textArray(Kind::Token, fallbacks_);
    if (!customData.empty()) spec.fields[field::kCustomData] = usd::Value::dict(std::move(customData));
    if (prim.type() == PrimType::Camera) writeLensSchema(prim, apiSchemas);
    writeSemantics(prim, apiSchemas);
    writeBehaviors(prim);
    prependApiSchemas(spec, apiSchemas);
    std::vector<std::string> children;
    for (const Prim* child : prim.children()) {
      children.emplace_back(child->name());
      writePrim(*child);
    }
    if (!children.empty()) spec.fields[field::kPrimChildren] = usd::Value::textArray(Kind::TokenVector, children);
    finishProperties(path);
  }

  // Schema attributes (authored, plus the displayColor every gprim is drawn
  // with and the stage fallbacks USD's schemas do not share) and custom ones.
  // A Mesh's `asset`/`submesh` become `sdgbehave:asset`/`sdgbehave:submesh`:
  // its geometry comes from the prototype it references.
  void writeAttributes(const Prim& prim) {
    const std::string& path = prim.path();
    for (const AttributeSpec& schema : prim.typeInfo().attributes) {
      const Attribute* a = prim.findAttribute(schema.name);
      // A Mesh's per-corner displayColor / displayOpacity is USD's primvar
      // itself (faceVarying): it takes the constant one's name, and place.
      if (prim.findAttribute(schema.name + ":faceVarying")) continue;
      if (a && schema.name.ends_with(":faceVarying") && schema.name.starts_with("primvars:display")) {
        const std::string usdName = schema.name.substr(0, schema.name.size() - std::string(":faceVarying").size());
        const bool color = a->value.type() == ValueType::Color3fArray;
        std::vector<double> xs;
        for (float f : a->value.get<FloatArray>().items()) xs.push_back(double(f));
        attribute(path, usdName, usd::Value::array(color ? Kind::Vec3f : Kind::Float, std::move(xs)), color ? "color3f[]" : "float[]")
            .fields[field::kInterpolation] = usd::Value::text(Kind::Token, "faceVarying");
        continue;
      }
      bool always = (schema.name == "primvars:displayColor") || (prim.type() == PrimType::Plane && schema.name == "doubleSided");
      if (!a && !always) continue;
      if (!a) fallbacks_.push_back(schema.name);
      const Value& v = a ? a->value : schema.defaultValue;
      if (prim.type() == PrimType::Mesh && (schema.name == "asset" || schema.name == "submesh")) {
        stageAttribute(path, "sdgbehave:" + schema.name, v, true);
      } else if (schema.name == "primvars:displayColor") {
        const Vec3f& c = v.get<Vec3f>();
        Spec& s = attribute(path, schema.name, usd::Value::array(Kind::Vec3f, {c.x(), c.y(), c.z()}), "color3f[]");
        s.fields[field::kInterpolation] = usd::Value::text(Kind::Token, "constant");
      } else if (schema.name == "primvars:displayOpacity") {
        Spec& s = attribute(path, schema.name, usd::Value::array(Kind::Float, {double(v.get<float>())}), "float[]");
        s.fields[field::kInterpolation] = usd::Value::text(Kind::Token, "constant");
      } else {
        stageAttribute(path, schema.name, v, false);
      }
    }
    for (const auto& [name, a] : prim.attributes()) {
      if (findSchemaAttribute(prim.type(), name) || name.starts_with("xformOp:")) continue;
      const AttributeSpec* variable = exposedVariable(name);
      if (variable && variable->files != FileKind::None && a.value.type() == ValueType::String)
        stageAttribute(path, name, Value::makeString(resolveFileList(a.value.get<std::string>())), true);
      else
        stageAttribute(path, name, a.value, true);
    }
  }

  // The behavior variable an `exposedVar:<ns>:<name>` attribute holds, or nullptr.
  const AttributeSpec* exposedVariable(const std::string& attribute) const {
    const std::string prefix = std::string(kExposedAttrNamespace) + ":";
    if (!options_.catalog || !attribute.starts_with(prefix)) return nullptr;
    size_t colon = attribute.find(':', prefix.size());
    if (colon == std::string::npos) return nullptr;
    const BehaviorSpec* spec = options_.catalog->find(attribute.substr(prefix.size(), colon - prefix.size()));
    return spec ? spec->findVariable(attribute.substr(colon + 1)) : nullptr;
  }

  // A comma-separated list of files ("props/a.glb#mesh,b.png") with each
  // file resolved, so that the layer works from any folder.
  std::string resolveFileList(const std::string& list) const {
    std::string out;
    size_t start = 0;
    while (start <= list.size()) {
      size_t comma = list.find(',', start);
      if (comma == std::string::npos) comma = list.size();
      std::string item = list.substr(start, comma - start);
      size_t hash = item.find('#');
      std::string file = item.substr(0, hash);
      item = absoluteAsset(assets_, file) + (hash == std::string::npos ? "" : item.substr(hash));
      out += (out.empty() && start == 0 ? "" : ",") + item;
      start = comma + 1;
    }
    return out;
  }

  void writeXformOps(const Prim& prim) {
    if (!prim.typeInfo().xformable || prim.xformOps().empty()) return;
    std::vector<std::string> order;
    for (const XformOp& op : prim.xformOps()) {
      order.push_back(op.attributeName());
      stageAttribute(prim.path(), op.attributeName(), op.value, false);
    }
    attribute(prim.path(), "xformOpOrder", usd::Value::textArray(Kind::Token, order), "token[]", false,
              usd::Variability::Uniform);
  }

  // The triangulated geometry of each distinct file, once, under /Prototypes.
  void writeMeshReference(const Prim& prim, Spec& spec) {
    MeshKey key = meshKeyOf(prim, scene_.stage.metadata().subdivisionLevel);
    std::string id = key.id();
    auto found = prototypes_.find(id);
    if (found == prototypes_.end()) {
      std::string stem = std::filesystem::path(key.asset).stem().string();
      if (!key.submesh.empty()) stem += "_" + key.submesh;
      std::string name = identifierFrom(stem) + "_" + std::to_string(prototypes_.size());
      found = prototypes_.emplace(id, std::string(kPrototypes) + "/" + name).first;
      prototypeOrder_.emplace_back(id, name);
      writePrototype(found->second, meshDataFor(key, assets_, prim.path()));
    }
    usd::Value refs;
    refs.kind = Kind::ReferenceListOp;
    refs.referenceListOp = std::make_shared<usd::ListOp<usd::Reference>>();
    usd::Reference r;
    r.primPath = found->second;
    refs.referenceListOp->prependedItems.push_back(r);
    spec.fields[field::kReferences] = std::move(refs);
  }

  void writePrototype(const std::string& path, const MeshData& mesh) {
    primSpec(path, usd::Specifier::Def, "Mesh");
    std::vector<double> points, normals, st, counts, indices;
    for (const Vec3f& p : mesh.positions) points.insert(points.end(), {p.x(), p.y(), p.z()});
    for (const Vec3f& n : mesh.normals) normals.insert(normals.end(), {n.x(), n.y(), n.z()});
    for (const auto& uv : mesh.uvs) st.insert(st.end(), {uv.x(), uv.y()});
    for (uint32_t i : mesh.indices) indices.push_back(i);
    counts.assign(mesh.indices.size() / 3, 3.0);
    attribute(path, "faceVertexCounts", usd::Value::array(Kind::Int, counts), "int[]");
    attribute(path, "faceVertexIndices", usd::Value::array(Kind::Int, indices), "int[]");
    attribute(path, "points", usd::Value::array(Kind::Vec3f, points), "point3f[]");
    if (mesh.normals.size() == mesh.positions.size() && !mesh.normals.empty())
      attribute(path, "normals", usd::Value::array(Kind::Vec3f, normals), "normal3f[]")
          .fields[field::kInterpolation] = usd::Value::text(Kind::Token, "vertex");
    if (mesh.uvs.size() == mesh.positions.size() && !mesh.uvs.empty())
      attribute(path, "primvars:st", usd::Value::array(Kind::Vec2f, st), "texCoord2f[]")
          .fields[field::kInterpolation] = usd::Value::text(Kind::Token, "vertex");
    attribute(path, "subdivisionScheme", usd::Value::text(Kind::Token, "none"), "token", false,
              usd::Variability::Uniform);
    if (!mesh.positions.empty()) {
      const auto& b = mesh.bounds;
      attribute(path, "extent",
                usd::Value::array(Kind::Vec3f, {b.min().x(), b.min().y(), b.min().z(), b.max().x(), b.max().y(), b.max().z()}),
                "float3[]");
    }
    finishProperties(path);
  }

  // A Material with Isaac's OmniPBR (MDL) and a UsdPreviewSurface for every
  // other tool; the stage's inputs go onto OmniPBR under their own names.
  void writeMaterial(const Prim& prim) {
    const std::string& path = prim.path();
    const std::string omni = path + "/OmniPBR", preview = path + "/PreviewSurface";
    connect(path, "outputs:mdl:surface", omni + ".outputs:out", "token");
    connect(path, "outputs:surface", preview + ".outputs:surface", "token");
    std::vector<std::string> shaders = {"OmniPBR", "PreviewSurface"};

    primSpec(omni, usd::Specifier::Def, "Shader");
    attribute(omni, "info:implementationSource", usd::Value::text(Kind::Token, "sourceAsset"), "token", false,
              usd::Variability::Uniform);
    attribute(omni, "info:mdl:sourceAsset", usd::Value::text(Kind::AssetPath, "OmniPBR.mdl"), "asset", false,
              usd::Variability::Uniform);
    attribute(omni, "info:mdl:sourceAsset:subIdentifier", usd::Value::text(Kind::Token, "OmniPBR"), "token", false,
              usd::Variability::Uniform);
    for (const auto& [name, a] : prim.attributes()) {
      if (!name.starts_with("inputs:")) continue;
      Spec& s = attribute(omni, name, toUsd(a.value, assets_).value, std::string(valueTypeName(a.value.type())));
      if (a.value.type() == ValueType::Asset)
        s.fields[field::kColorSpace] = usd::Value::text(Kind::Token, name == "inputs:diffuse_texture" ? "auto" : "raw");
    }
    attribute(omni, "outputs:out", {}, "token");
    finishProperties(omni);

    primSpec(preview, usd::Specifier::Def, "Shader");
    attribute(preview, "info:id", usd::Value::text(Kind::Token, "UsdPreviewSurface"), "token", false,
              usd::Variability::Uniform);
    const Value& diffuse = *prim.value("inputs:diffuse_color_constant");
    const std::string& texture = prim.getString("inputs:diffuse_texture");
    if (texture.empty()) {
      UsdTyped t = toUsd(diffuse, assets_);
      attribute(preview, "inputs:diffuseColor", std::move(t.value), "color3f");
    } else {
      const std::string tex = path + "/DiffuseTexture", reader = path + "/STReader";
      shaders.insert(shaders.end(), {"DiffuseTexture", "STReader"});
      connect(preview, "inputs:diffuseColor", tex + ".outputs:rgb", "color3f");
      primSpec(tex, usd::Specifier::Def, "Shader");
      attribute(tex, "info:id", usd::Value::text(Kind::Token, "UsdUVTexture"), "token", false, usd::Variability::Uniform);
      attribute(tex, "inputs:file", toUsd(Value::makeAsset(texture), assets_).value, "asset");
      attribute(tex, "inputs:sourceColorSpace", usd::Value::text(Kind::Token, "sRGB"), "token");
      connect(tex, "inputs:st", reader + ".outputs:result", "float2");
      attribute(tex, "outputs:rgb", {}, "float3");
      finishProperties(tex);
      primSpec(reader, usd::Specifier::Def, "Shader");
      attribute(reader, "info:id", usd::Value::text(Kind::Token, "UsdPrimvarReader_float2"), "token", false,
                usd::Variability::Uniform);
      attribute(reader, "inputs:varname", usd::Value::text(Kind::String, "st"), "string");
      attribute(reader, "outputs:result", {}, "float2");
      finishProperties(reader);
    }
    attribute(preview, "inputs:metallic", usd::Value::scalar(Kind::Float, {prim.getFloat("inputs:metallic_constant")}),
              "float");
    attribute(preview, "inputs:roughness",
              usd::Value::scalar(Kind::Float, {prim.getFloat("inputs:reflection_roughness_constant")}), "float");
    attribute(preview, "outputs:surface", {}, "token");
    finishProperties(preview);
    layer_.specs[path].fields[field::kPrimChildren] = usd::Value::textArray(Kind::TokenVector, shaders);
  }

  // Isaac's Semantics schema, one instance per label, and UsdSemantics'
  // LabelsAPI per taxonomy; sdgbehave's import reads both and merges them.
  // A calibrated lens applies its omni_lens_distortion schema, as Isaac
  // Sim authors it (the attributes themselves are written with the others).
  static void writeLensSchema(const Prim& prim, std::vector<std::string>& apiSchemas) {
    const std::string& model = prim.getString("omni:lensdistortion:model");
    for (const UsdLensSchema& lens : kUsdLensSchemas)
      if (model == lens.model) apiSchemas.emplace_back(lens.schema);
  }

  void writeSemantics(const Prim& prim, std::vector<std::string>& apiSchemas) {
    size_t n = 0;
    for (const auto& [taxonomy, labels] : prim.semantics())
      for (const std::string& label : labels) {
        std::string instance = "Semantics_" + std::to_string(n++);
        apiSchemas.push_back("SemanticsAPI:" + instance);
        attribute(prim.path(), "semantic:" + instance + ":params:semanticType", usd::Value::text(Kind::String, taxonomy),
                  "string");
        attribute(prim.path(), "semantic:" + instance + ":params:semanticData", usd::Value::text(Kind::String, label),
                  "string");
      }
    for (const auto& [taxonomy, labels] : prim.semantics()) {
      apiSchemas.push_back("SemanticsLabelsAPI:" + taxonomy);
      attribute(prim.path(), "semantics:labels:" + taxonomy, usd::Value::textArray(Kind::Token, labels), "token[]",
                false, usd::Variability::Uniform);
    }
  }

  // omni:scripting:scripts lists each behavior's script; the exposedVar:
  // attributes themselves were written with the prim's custom attributes.
  void writeBehaviors(const Prim& prim) {
    if (prim.behaviors().empty()) return;
    std::vector<std::string> scripts;
    for (const std::string& behavior : prim.behaviors()) {
      std::string file = isaacScriptForBuiltin(behavior);
      std::string script = !file.empty() ? options_.isaacScriptsRoot + "/" + file
                                         : (options_.scriptOf ? options_.scriptOf(behavior) : std::string());
      if (script.empty()) {
        withoutScript_.insert(behavior);
        continue;
      }
      if (std::find(scripts.begin(), scripts.end(), script) == scripts.end()) scripts.push_back(script);
    }
    if (!scripts.empty())
      attribute(prim.path(), "omni:scripting:scripts", usd::Value::textArray(Kind::AssetPath, scripts), "asset[]", true);
  }

  // What the stage has no prim for: sdgbehave's run settings and events.
  usd::Value sceneSettings() const {
    nlohmann::ordered_json j = nlohmann::ordered_json::object();
    j["render"] = optionsJson(scene_.render);
    j["capture"] = optionsJson(scene_.capture);
    j["physics"] = optionsJson(scene_.physics);
    j["run"] = optionsJson(scene_.run);
    nlohmann::ordered_json writers = nlohmann::ordered_json::object();
    for (size_t i = 0; i < scene_.writers.size(); ++i) {
      nlohmann::ordered_json w = optionsJson(scene_.writers[i].options);
      w["type"] = scene_.writers[i].type;
      writers["writer" + std::to_string(i)] = w;
    }
    j["writers"] = writers;
    nlohmann::ordered_json events = nlohmann::ordered_json::object();
    for (size_t i = 0; i < scene_.events.size(); ++i) {
      const EventStep& e = scene_.events[i];
      events["event" + std::to_string(i)] = {{"publish", e.publish},
                                            {"payload", payloadJson(e.payload)},
                                            {"payload_keys", payloadKeys(e.payload)},
                                            {"wait_event", e.waitEvent},
                                            {"wait_for", payloadJson(e.waitFor)},
                                            {"wait_for_keys", payloadKeys(e.waitFor)},
                                            {"max_updates", e.maxUpdates}};
    }
    j["events"] = events;
    if (!withoutScript_.empty())
      j["behaviorsWithoutScript"] = std::vector<std::string>(withoutScript_.begin(), withoutScript_.end());
    return jsonToUsd(j);
  }

  const Scene& scene_;
  const AssetResolver& assets_;
  const UsdExportOptions& options_;
  usd::Layer layer_;
  std::map<std::string, std::vector<std::string>> properties_;  // prim path -> property names in write order
  std::map<std::string, std::string> prototypes_;               // mesh key id -> prototype path
  std::vector<std::pair<std::string, std::string>> prototypeOrder_;
  std::set<std::string> withoutScript_;
  std::vector<std::string> fallbacks_;  // of the prim being written
};

}  // namespace

usd::Layer exportUsdLayer(const Scene& scene, const AssetResolver& assets, const UsdExportOptions& options) {
  return Exporter(scene, assets, options).build();
}

}  // namespace sdg
