#include "scene_io/scene_writer.h"

#include <yaml-cpp/yaml.h>

#include "core/text.h"
#include "scene_io/prim_reader.h"

namespace sdg {
namespace {

void emitNumber(YAML::Emitter& out, double v) { out << text::formatDouble(v); }
void emitNumber(YAML::Emitter& out, float v) { out << text::formatFloat(v); }

template <typename Vector>
void emitVector(YAML::Emitter& out, const Vector& v) {
  out << YAML::Flow << YAML::BeginSeq;
  for (Eigen::Index i = 0; i < v.size(); ++i) {
    if constexpr (std::is_integral_v<typename Vector::Scalar>) out << std::to_string(v[i]);
    else emitNumber(out, v[i]);
  }
  out << YAML::EndSeq;
}

void emitValue(YAML::Emitter& out, const Value& value) {
  switch (value.type()) {
    case ValueType::Bool: out << (value.get<bool>() ? "true" : "false"); break;
    case ValueType::Int: out << std::to_string(value.get<int32_t>()); break;
    case ValueType::UInt: out << std::to_string(value.get<uint32_t>()); break;
    case ValueType::Float: emitNumber(out, value.get<float>()); break;
    case ValueType::Double: emitNumber(out, value.get<double>()); break;
    case ValueType::Int2: emitVector(out, value.get<Vec2i>()); break;
    case ValueType::Float2: emitVector(out, value.get<Vec2f>()); break;
    case ValueType::Float3:
    case ValueType::Color3f: emitVector(out, value.get<Vec3f>()); break;
    case ValueType::Double3:
    case ValueType::Vector3d: emitVector(out, value.get<Vec3d>()); break;
    case ValueType::Quatf: {
      const Quatf& q = value.get<Quatf>();
      emitVector(out, Eigen::Vector4f(q.w(), q.x(), q.y(), q.z()));
      break;
    }
    case ValueType::Quatd: {
      const Quatd& q = value.get<Quatd>();
      emitVector(out, Eigen::Vector4d(q.w(), q.x(), q.y(), q.z()));
      break;
    }
    case ValueType::Matrix4d: {
      // USD's row-vector rows are our columns.
      const Matrix4d& m = value.get<Matrix4d>();
      out << YAML::Flow << YAML::BeginSeq;
      for (int c = 0; c < 4; ++c) emitVector(out, Eigen::Vector4d(m.col(c)));
      out << YAML::EndSeq;
      break;
    }
    case ValueType::String:
    case ValueType::Token:
    case ValueType::Asset: out << YAML::DoubleQuoted << value.get<std::string>(); break;
    case ValueType::AssetArray:
    case ValueType::StringArray:
      out << YAML::Flow << YAML::BeginSeq;
      for (const std::string& s : value.get<std::vector<std::string>>()) out << YAML::DoubleQuoted << s;
      out << YAML::EndSeq;
      break;
    case ValueType::IntArray:
      out << YAML::Flow << YAML::BeginSeq;
      for (int32_t i : value.get<IntArray>().items()) out << std::to_string(i);
      out << YAML::EndSeq;
      break;
    case ValueType::FloatArray:
    case ValueType::Point3fArray:
    case ValueType::Normal3fArray:
    case ValueType::Color3fArray:
    case ValueType::TexCoord2fArray: {
      // Written inline: flat for float[], one [x, y(, z)] per item otherwise.
      const size_t width = size_t(arrayWidth(value.type()));
      const FloatArray& a = value.get<FloatArray>();
      out << YAML::Flow << YAML::BeginSeq;
      for (size_t i = 0; i < a.size(); i += width) {
        if (width > 1) out << YAML::Flow << YAML::BeginSeq;
        for (size_t k = 0; k < width; ++k) emitNumber(out, a[i + k]);
        if (width > 1) out << YAML::EndSeq;
      }
      out << YAML::EndSeq;
      break;
    }
  }
}

// Options that differ from their defaults; nothing when all are defaults.
void emitOptions(YAML::Emitter& out, const char* key, std::span<const AttributeSpec> specs, const OptionSet& options) {
  std::vector<const AttributeSpec*> changed;
  for (const AttributeSpec& spec : specs)
    if (!(options.get(spec.name) == spec.defaultValue)) changed.push_back(&spec);
  if (changed.empty()) return;
  out << YAML::Key << key << YAML::Value << YAML::BeginMap;
  for (const AttributeSpec* spec : changed) {
    out << YAML::Key << spec->name << YAML::Value;
    emitValue(out, options.get(spec->name));
  }
  out << YAML::EndMap;
}

void emitStringList(YAML::Emitter& out, const char* key, const std::vector<std::string>& items) {
  if (items.empty()) return;
  out << YAML::Key << key << YAML::Value;
  emitValue(out, Value::makeStringArray(items));
}

void emitWriter(YAML::Emitter& out, const WriterConfig& writer) {
  out << YAML::BeginMap << YAML::Key << "type" << YAML::Value << writer.type;
  for (const AttributeSpec& spec : findWriterType(writer.type)->options) {
    const Value& v = writer.options.get(spec.name);
    if (v == spec.defaultValue) continue;
    out << YAML::Key << spec.name << YAML::Value;
    emitValue(out, v);
  }
  out << YAML::EndMap;
}

void emitPayload(YAML::Emitter& out, const char* key, const Payload& payload) {
  if (payload.empty()) return;
  out << YAML::Key << key << YAML::Value << YAML::Flow << YAML::BeginMap;
  for (const auto& [k, v] : payload.entries()) {
    out << YAML::Key << k << YAML::Value;
    if (const auto* s = std::get_if<std::string>(&v)) out << YAML::DoubleQuoted << *s;
    else if (const auto* d = std::get_if<double>(&v)) emitNumber(out, *d);
    else out << (std::get<bool>(v) ? "true" : "false");
  }
  out << YAML::EndMap;
}

void emitEvents(YAML::Emitter& out, const std::vector<EventStep>& events) {
  if (events.empty()) return;
  out << YAML::Key << "events" << YAML::Value << YAML::BeginSeq;
  for (const EventStep& e : events) {
    out << YAML::Flow << YAML::BeginMap;
    out << YAML::Key << "publish" << YAML::Value << YAML::DoubleQuoted << e.publish;
    emitPayload(out, "payload", e.payload);
    out << YAML::Key << "wait_event" << YAML::Value << YAML::DoubleQuoted << e.waitEvent;
    emitPayload(out, "wait_for", e.waitFor);
    out << YAML::Key << "max_updates" << YAML::Value << std::to_string(e.maxUpdates);
    out << YAML::EndMap;
  }
  out << YAML::EndSeq;
}

bool isExposedOfAttached(const Prim& prim, const std::string& name) {
  for (const std::string& behavior : prim.behaviors())
    if (name.rfind(exposedAttributeName(behavior, ""), 0) == 0) return true;
  return false;
}

void emitPrim(YAML::Emitter& out, const Prim& prim, const BehaviorCatalog& catalog) {
  out << YAML::Key << prim.path() << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "type" << YAML::Value << std::string(prim.typeInfo().name);
  for (const AttributeSpec& spec : prim.typeInfo().attributes)
    if (const Attribute* a = prim.findAttribute(spec.name)) {
      out << YAML::Key << spec.name << YAML::Value;
      emitValue(out, a->value);
    }
  for (const XformOp& op : prim.xformOps()) {
    out << YAML::Key << op.attributeName().substr(8) << YAML::Value;  // drop "xformOp:"
    emitValue(out, op.value);
  }
  if (!prim.semantics().empty()) {
    out << YAML::Key << "semantics" << YAML::Value << YAML::BeginMap;
    for (const auto& [taxonomy, labels] : prim.semantics()) {
      out << YAML::Key << taxonomy << YAML::Value;
      emitValue(out, Value::makeStringArray(labels));
    }
    out << YAML::EndMap;
  }
  if (const auto& binding = prim.material()) {
    out << YAML::Key << "material" << YAML::Value << YAML::Flow << YAML::BeginMap;
    out << YAML::Key << "path" << YAML::Value << binding->path;
    out << YAML::Key << "strength" << YAML::Value << binding->strength << YAML::EndMap;
  }
  bool anyCustom = false;
  for (const auto& [name, a] : prim.attributes())
    anyCustom = anyCustom || (!findSchemaAttribute(prim.type(), name) && !isExposedOfAttached(prim, name));
  if (anyCustom) {
    out << YAML::Key << "attributes" << YAML::Value << YAML::BeginMap;
    for (const auto& [name, a] : prim.attributes()) {
      if (findSchemaAttribute(prim.type(), name) || isExposedOfAttached(prim, name)) continue;
      out << YAML::Key << name << YAML::Value << YAML::Flow << YAML::BeginMap;
      out << YAML::Key << "type" << YAML::Value << std::string(valueTypeName(a.value.type()));
      out << YAML::Key << "value" << YAML::Value;
      emitValue(out, a.value);
      if (!a.doc.empty()) out << YAML::Key << "doc" << YAML::Value << YAML::DoubleQuoted << a.doc;
      out << YAML::EndMap;
    }
    out << YAML::EndMap;
  }
  if (!prim.behaviors().empty()) {
    out << YAML::Key << "behaviors" << YAML::Value << YAML::BeginMap;
    for (const std::string& behavior : prim.behaviors()) {
      out << YAML::Key << behavior << YAML::Value << YAML::BeginMap;
      if (const BehaviorSpec* spec = catalog.find(behavior))
        for (const AttributeSpec& var : spec->variables) {
          const Attribute* a = prim.findAttribute(exposedAttributeName(behavior, var.name));
          if (!a || a->value == var.defaultValue) continue;
          out << YAML::Key << var.name << YAML::Value;
          emitValue(out, a->value);
        }
      out << YAML::EndMap;
    }
    out << YAML::EndMap;
  }
  if (!prim.metadata().empty()) {
    out << YAML::Key << "metadata" << YAML::Value << YAML::BeginMap;
    for (const auto& [k, v] : prim.metadata()) out << YAML::Key << k << YAML::Value << YAML::DoubleQuoted << v;
    out << YAML::EndMap;
  }
  out << YAML::EndMap;
}

}  // namespace

std::string writeSceneYaml(const Scene& scene, const BehaviorCatalog& catalog, const std::string& schemaRef) {
  YAML::Emitter out;
  out.SetIndent(2);
  out << YAML::BeginMap;
  out << YAML::Key << "version" << YAML::Value << std::to_string(kSceneFormatVersion);

  OptionSet stageOptions(stageOptionSpecs());
  stageOptions.set("timeCodesPerSecond", Value::makeDouble(scene.stage.metadata().timeCodesPerSecond));
  stageOptions.set("metersPerUnit", Value::makeDouble(scene.stage.metadata().metersPerUnit));
  stageOptions.set("upAxis", Value::makeToken(scene.stage.metadata().upAxis));
  emitOptions(out, "stage", stageOptionSpecs(), stageOptions);
  emitStringList(out, "asset_roots", scene.assetRoots);
  emitStringList(out, "plugins", scene.plugins);
  emitStringList(out, "scripts", scene.scripts);
  if (!scene.isaacAssets.empty()) out << YAML::Key << "isaac_assets" << YAML::Value << scene.isaacAssets;
  emitOptions(out, "render", renderOptionSpecs(), scene.render);
  emitOptions(out, "physics", physicsOptionSpecs(), scene.physics);
  emitOptions(out, "capture", captureOptionSpecs(), scene.capture);
  emitOptions(out, "run", runOptionSpecs(), scene.run);
  if (scene.writers.size() == 1) {
    out << YAML::Key << "writer" << YAML::Value;
    emitWriter(out, scene.writers.front());
  } else if (!scene.writers.empty()) {
    out << YAML::Key << "writer" << YAML::Value << YAML::BeginSeq;
    for (const WriterConfig& w : scene.writers) emitWriter(out, w);
    out << YAML::EndSeq;
  }
  emitEvents(out, scene.events);
  out << YAML::Key << "prims" << YAML::Value << YAML::BeginMap;
  scene.stage.traverse([&](const Prim& prim) { emitPrim(out, prim, catalog); });
  out << YAML::EndMap;
  out << YAML::EndMap;

  std::string text;
  if (!schemaRef.empty()) text = "# yaml-language-server: $schema=" + schemaRef + "\n";
  text += out.c_str();
  text += '\n';
  return text;
}

}  // namespace sdg
