#include "scene_io/inspect.h"

#include <sstream>

#include "core/text.h"
#include "stage/behavior_spec.h"
#include "stage/path.h"

namespace sdg {
namespace {

std::string options(const OptionSet& set) {
  std::string out;
  for (const auto& [name, value] : set.values()) {
    if (!out.empty()) out += ", ";
    out += name + " " + value.toString();
  }
  return out;
}

// Where a value comes from, as a trailing comment: its file:line:col (a
// smart asset's, with the chain of references), a --set flag, or the default.
std::string origin(const SourceLoc& loc) { return "  # " + valueOrigin(loc); }

// "  (animated: 3 samples, time codes 0 to 8)" for a value the stage's own
// animation plays (a USD stage's time samples); "" otherwise.
std::string animatedNote(const Stage& stage, const Prim& prim, const std::string& name) {
  const AnimatedValue* a = stage.animation().find(prim.path(), name);
  if (!a) return "";
  return "  (animated: " + std::to_string(a->times.size()) + " samples, time codes " +
         text::formatDouble(a->times.front()) + " to " + text::formatDouble(a->times.back()) + ")";
}

void inspectPrim(const Stage& stage, const Prim& prim, std::ostringstream& out) {
  std::string indent(2 * (path::depth(prim.path()) - 1), ' ');
  std::string detail = indent + "    ";
  out << indent << prim.path() << "  " << prim.typeInfo().name << (prim.loc().via ? origin(prim.loc()) : "") << "\n";
  for (const XformOp& op : prim.xformOps())
    out << detail << op.attributeName() << " " << op.value.toString() << animatedNote(stage, prim, op.attributeName())
        << "\n";
  if (!prim.xformOps().empty() || prim.typeInfo().xformable) {
    Vec3d t = stage.worldMatrix(prim).block<3, 1>(0, 3);
    if (!prim.xformOps().empty())
      out << detail << "world position " << Value::makeDouble3(t).toString() << "\n";
  }
  for (const auto& [taxonomy, labels] : prim.semantics())
    out << detail << "semantics " << taxonomy << ": " << text::join(labels, ", ") << "\n";
  if (prim.material()) out << detail << "material " << prim.material()->path << " (" << prim.material()->strength << ")\n";
  for (const auto& [name, attribute] : prim.attributes()) {
    if (name.rfind("exposedVar:", 0) == 0) continue;  // listed under their behavior
    out << detail << name << " " << attribute.value.toString() << (attribute.custom ? "  (custom)" : "")
        << animatedNote(stage, prim, name) << origin(attribute.loc) << "\n";
  }
  for (const std::string& behavior : prim.behaviors()) {
    out << detail << "behavior " << behavior << "\n";
    std::string prefix = exposedAttributeName(behavior, "");
    for (const auto& [name, attribute] : prim.attributes())
      if (name.rfind(prefix, 0) == 0)
        out << detail << "  " << name.substr(prefix.size()) << " " << attribute.value.toString()
            << origin(attribute.loc) << "\n";
  }
  for (const auto& [key, value] : prim.metadata()) out << detail << "metadata " << key << ": " << value << "\n";
}

}  // namespace

std::string valueOrigin(const SourceLoc& loc) {
  if (!loc.known()) return "default";
  return loc.str() + (loc.via ? ", " + loc.referenceChain() : std::string());
}

std::string inspectScene(const Scene& scene) {
  std::ostringstream out;
  const StageMetadata& meta = scene.stage.metadata();
  out << "scene " << scene.sourcePath << "\n";
  out << "stage: timeCodesPerSecond " << text::formatDouble(meta.timeCodesPerSecond) << ", metersPerUnit "
      << text::formatDouble(meta.metersPerUnit) << ", upAxis " << meta.upAxis << "\n";
  if (!scene.assetRoots.empty()) out << "asset_roots: " << text::join(scene.assetRoots, ", ") << "\n";
  if (!scene.plugins.empty()) out << "plugins: " << text::join(scene.plugins, ", ") << "\n";
  if (!scene.scripts.empty()) out << "scripts: " << text::join(scene.scripts, ", ") << "\n";
  if (!scene.isaacAssets.empty()) out << "isaac_assets: " << scene.isaacAssets << "\n";
  out << "render: " << options(scene.render) << "\n";
  out << "physics: " << options(scene.physics) << "\n";
  out << "capture: " << options(scene.capture) << "\n";
  out << "run: " << options(scene.run) << "\n";
  for (const WriterConfig& w : scene.writers) {
    // Only what differs from the defaults: the enabled annotators, mostly.
    std::string changed;
    for (const AttributeSpec& spec : findWriterType(w.type)->options) {
      const Value& v = w.options.get(spec.name);
      if (v == spec.defaultValue) continue;
      changed += (changed.empty() ? "" : ", ") + spec.name + " " + v.toString();
    }
    out << "writer " << w.type << ": " << (changed.empty() ? "defaults" : changed) << "\n";
  }
  for (const EventStep& e : scene.events)
    out << "event: publish " << e.publish << " " << e.payload.toString() << ", wait on " << e.waitEvent << " for "
        << e.waitFor.toString() << " (at most " << e.maxUpdates << " updates)\n";
  out << "prims (" << scene.stage.primCount() << "):\n";
  scene.stage.traverse([&](const Prim& prim) { inspectPrim(scene.stage, prim, out); });
  return out.str();
}

}  // namespace sdg
