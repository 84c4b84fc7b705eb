// UsdGeomPointInstancer read and expanded onto the stage (usd_point_instancer.h).
#include "scene_io/usd_point_instancer.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <unordered_map>

#include "stage/path.h"

namespace sdg {
namespace {

constexpr const char* kVelocityAttribute = "sdgbehave:instanceVelocity";
constexpr const char* kInstanceSuffix = "instance";
// Prims the copies may add to a stage in all (the composer's own limit on
// composed prims): a 10-instance instancer of a 10-instance instancer ...
// must not eat the machine.
constexpr size_t kMaxInstancePrims = size_t(1) << 22;

const usd::ComposedProperty* authored(const usd::ComposedPrim& prim, const std::string& name) {
  const usd::ComposedProperty* p = prim.property(name);
  return p && !p->value.empty() && p->value.kind != usd::Kind::ValueBlock ? p : nullptr;
}

std::string where(const usd::ComposedPrim& prim, const std::string& name) { return prim.path + "." + name; }

// The numbers of an array attribute of `width` components of one of `kinds`;
// nullopt after an error naming what was found.
std::optional<std::vector<double>> numbersOf(const usd::ComposedPrim& prim, const usd::ComposedProperty& p, int width,
                                             std::initializer_list<usd::Kind> kinds, const char* expected,
                                             Diagnostics& diag) {
  const bool kindOk = std::find(kinds.begin(), kinds.end(), p.value.kind) != kinds.end();
  if (!kindOk || !p.value.isArray || usd::componentCount(p.value.kind) != width) {
    diag.error(p.loc, where(prim, p.name) + ": expected " + expected + ", found " + p.typeName);
    return std::nullopt;
  }
  for (size_t i = 0; i < p.value.numbers.size(); ++i)
    if (!std::isfinite(p.value.numbers[i])) {
      diag.error(p.loc, where(prim, p.name) + ": item " + std::to_string(i / size_t(width)) + " is not finite");
      return std::nullopt;
    }
  return p.value.numbers;
}

std::vector<Vec3d> vec3s(const std::vector<double>& n) {
  std::vector<Vec3d> out(n.size() / 3);
  for (size_t i = 0; i < out.size(); ++i) out[i] = Vec3d(n[3 * i], n[3 * i + 1], n[3 * i + 2]);
  return out;
}

bool lengthFits(const usd::ComposedPrim& prim, const usd::ComposedProperty& p, size_t items, size_t expected,
                Diagnostics& diag) {
  if (items == expected) return true;
  diag.error(p.loc, where(prim, p.name) + ": " + std::to_string(items) + " items, but protoIndices has " +
                        std::to_string(expected) + " (one per instance)");
  return false;
}

// A prim name for an instance id (ids are signed 64-bit).
std::string instanceName(int64_t id) {
  return id < 0 ? "instance_n" + std::to_string(uint64_t(0) - uint64_t(id)) : "instance_" + std::to_string(id);
}

bool beneath(const std::string& path, const std::string& ancestor) {
  return path != ancestor && path::isAtOrBelow(path, ancestor);
}

// xformOp:<kind>:instance.
XformOp instanceOp(XformOpKind kind, Value value) {
  XformOp op;
  op.kind = kind;
  op.suffix = kInstanceSuffix;
  op.value = std::move(value);
  return op;
}

// Copies `from` (everything the stage keeps of a prim) onto `to`.
void copyPrimContent(const Prim& from, Prim& to) {
  for (const auto& [name, attr] : from.attributes()) to.setAttribute(name, attr.value, attr.custom) = attr;
  to.xformOps() = from.xformOps();
  to.semantics() = from.semantics();
  to.material() = from.material();
  to.behaviors() = from.behaviors();
  to.metadata() = from.metadata();
  to.loc() = from.loc();
}

class Expander {
 public:
  Expander(Stage& stage, const std::function<std::string(const std::string&)>& mapPath,
           const std::function<void(const SourceLoc&, const std::string&, const std::string&)>& warn,
           const AnimationClock& clock, Diagnostics& diag)
      : stage_(stage), mapPath_(mapPath), warn_(warn), clock_(clock), diag_(diag) {}

  void expand(const usd::ComposedPrim& composed) {
    std::optional<PointInstancerData> data = readPointInstancer(composed, diag_);
    if (!data) return;
    Prim* instancer = stage_.find(mapPath_(composed.path));
    if (!instancer) return;  // not imported (under an inactive or undefined prim)
    const usd::ComposedProperty* rel = composed.property("prototypes");
    const SourceLoc relLoc = rel ? rel->loc : composed.loc;
    // The prototypes' stage prims; null where one is not on the stage.
    std::vector<Prim*> prototypes;
    std::vector<size_t> subtreeSizes;
    for (const std::string& target : data->prototypes) {
      Prim* p = stage_.find(mapPath_(target));
      if (p && (p == instancer || beneath(instancer->path(), p->path()))) {
        diag_.error(relLoc, composed.path + ".prototypes: " + target + " contains the instancer itself");
        return;
      }
      prototypes.push_back(p && p->type() != PrimType::Material ? p : nullptr);
      subtreeSizes.push_back(p ? stage_.subtree(*p).size() : 0);
    }
    std::vector<size_t> unusable;
    size_t added = 0;
    for (size_t i = 0; i < data->size(); ++i) {
      const size_t proto = size_t(data->protoIndices[i]);
      if (!prototypes[proto]) {
        if (std::find(unusable.begin(), unusable.end(), proto) == unusable.end()) unusable.push_back(proto);
        continue;
      }
      if (!data->inactiveIds.count(data->idOf(i))) added += subtreeSizes[proto];
    }
    for (size_t proto : unusable)
      warn_(relLoc, "instancer-proto:" + composed.path + ":" + std::to_string(proto),
            composed.path + ".prototypes[" + std::to_string(proto) + "]: " + data->prototypes[proto] +
                " is not a defined prim on the stage (or is a Material); its instances are skipped");
    if (totalAdded_ + added > kMaxInstancePrims) {
      diag_.error(composed.loc, composed.path + ": its instances would add " + std::to_string(added) +
                                    " prims to the stage, over the limit of " + std::to_string(kMaxInstancePrims) +
                                    " for all instancers");
      return;
    }
    totalAdded_ += added;
    for (size_t i = 0; i < data->size(); ++i) {
      Prim* proto = prototypes[size_t(data->protoIndices[i])];
      const int64_t id = data->idOf(i);
      if (!proto || data->inactiveIds.count(id)) continue;
      std::string name = instanceName(id);
      std::string clonePath = instancer->path() + "/" + name;
      if (stage_.find(clonePath)) {
        diag_.error(composed.loc, composed.path + ": instance id " + std::to_string(id) +
                                      " appears twice in ids, or the instancer has a child named " + name);
        return;
      }
      cloneInstance(*data, i, *proto, clonePath);
    }
    // Prototypes beneath the instancer are drawn only as its instances.
    for (Prim* proto : prototypes)
      if (proto && beneath(proto->path(), instancer->path())) {
        rememberVisibility(*proto);
        proto->setAttribute("visibility", Value::makeToken("invisible")).loc = composed.loc;
      }
  }

 private:
  void rememberVisibility(const Prim& proto) {
    if (visibility_.count(proto.path())) return;
    const Attribute* v = proto.findAttribute("visibility");
    visibility_[proto.path()] = v ? std::optional<Attribute>(*v) : std::nullopt;
  }

  void cloneInstance(const PointInstancerData& data, size_t i, const Prim& proto, const std::string& clonePath) {
    // A prototype root with no transform (a Scope) is grouped by an Xform.
    const PrimType rootType = proto.typeInfo().xformable ? proto.type() : PrimType::Xform;
    Prim& root = stage_.definePrim(clonePath, rootType);
    copyPrimContent(proto, root);
    // The prototype as authored, not as hidden for being beneath an instancer.
    if (auto it = visibility_.find(proto.path()); it != visibility_.end()) {
      root.removeAttribute("visibility");
      if (it->second) root.setAttribute("visibility", it->second->value) = *it->second;
    }
    if (data.invisibleIds.count(data.idOf(i))) root.setAttribute("visibility", Value::makeToken("invisible"));
    std::vector<XformOp> ops = {instanceOp(XformOpKind::Translate, Value::makeDouble3(data.positions[i]))};
    if (!data.orientations.empty()) ops.push_back(instanceOp(XformOpKind::Orient, Value::makeQuatd(data.orientations[i])));
    if (!data.scales.empty()) ops.push_back(instanceOp(XformOpKind::Scale, Value::makeDouble3(data.scales[i])));
    if (proto.typeInfo().xformable)
      for (const XformOp& op : proto.xformOps()) ops.push_back(op);
    root.xformOps() = std::move(ops);
    if (!data.velocities.empty()) {
      root.setAttribute(kVelocityAttribute, Value::makeVector3d(data.velocities[i]), true);
      if (data.velocities[i] != Vec3d::Zero()) moveAtVelocity(root, data.positions[i], data.velocities[i]);
    }
    // The descendants, parents before children, at the same relative paths.
    const std::string& from = proto.path();
    for (const Prim* p : stage_.subtree(const_cast<Prim&>(proto))) {
      if (p == &proto) continue;
      Prim& copy = stage_.definePrim(clonePath + p->path().substr(from.size()), p->type());
      copyPrimContent(*p, copy);
    }
  }

  // USD moves an instance at its velocity (units per second) from the
  // sample its position was read at: its translate is a line through the
  // start time code, extrapolated on the timeline (stage_animation.h), so
  // poses, motion vectors and flow follow.
  void moveAtVelocity(const Prim& root, const Vec3d& position, const Vec3d& velocity) {
    AnimatedValue track;
    track.primPath = root.path();
    track.name = root.xformOps().front().attributeName();
    track.xformOp = true;
    track.clock = clock_;
    track.extrapolate = true;
    track.times = {clock_.startTimeCode, clock_.startTimeCode + 1.0};
    track.values = {Value::makeDouble3(position), Value::makeDouble3(position + velocity / clock_.timeCodesPerSecond)};
    track.imported = track.values.front();
    stage_.animation().add(std::move(track));
  }

  Stage& stage_;
  const std::function<std::string(const std::string&)>& mapPath_;
  const std::function<void(const SourceLoc&, const std::string&, const std::string&)>& warn_;
  AnimationClock clock_;
  Diagnostics& diag_;
  size_t totalAdded_ = 0;
  // Prototype root -> its authored visibility before it was hidden.
  std::map<std::string, std::optional<Attribute>> visibility_;
};

}  // namespace

Matrix4d PointInstancerData::instanceMatrix(size_t i) const {
  Eigen::Affine3d m = Eigen::Affine3d::Identity();
  m.translate(positions[i]);
  if (!orientations.empty()) m.rotate(orientations[i]);
  if (!scales.empty()) m.scale(scales[i]);
  return m.matrix();
}

bool isPointInstancer(const usd::ComposedPrim& prim) { return prim.typeName == "PointInstancer"; }

bool isPointInstancerAttribute(const std::string& name) {
  static const std::vector<std::string> kNames = {
      "protoIndices", "ids",          "positions",         "orientations", "orientationsf", "scales",
      "velocities",   "accelerations", "angularVelocities", "invisibleIds", "prototypes"};
  return std::find(kNames.begin(), kNames.end(), name) != kNames.end();
}

std::optional<PointInstancerData> readPointInstancer(const usd::ComposedPrim& prim, Diagnostics& diag) {
  using K = usd::Kind;
  PointInstancerData d;
  d.path = prim.path;
  const size_t errorsBefore = diag.errorCount();
  if (const usd::ComposedProperty* rel = prim.property("prototypes"); rel && rel->isRelationship)
    d.prototypes = rel->targets;
  const usd::ComposedProperty* indices = authored(prim, "protoIndices");
  const usd::ComposedProperty* positions = authored(prim, "positions");
  if (!indices || !positions) {
    diag.error(prim.loc, prim.path + ": a PointInstancer needs protoIndices (int[]) and positions (point3f[])" +
                             std::string(indices ? "; positions is not authored" : "; protoIndices is not authored"));
    return std::nullopt;
  }
  if (auto n = numbersOf(prim, *indices, 1, {K::Int, K::Int64, K::UInt, K::UInt64}, "int[]", diag)) {
    for (size_t i = 0; i < n->size(); ++i) {
      const double v = (*n)[i];
      if (v < 0 || v >= double(d.prototypes.size())) {
        diag.error(indices->loc, where(prim, "protoIndices") + ": item " + std::to_string(i) + " is " +
                                     std::to_string(int64_t(v)) + ", outside the " +
                                     std::to_string(d.prototypes.size()) + " prototypes");
        return std::nullopt;
      }
      d.protoIndices.push_back(int32_t(v));
    }
  }
  const size_t count = d.protoIndices.size();
  if (auto n = numbersOf(prim, *positions, 3, {K::Vec3f, K::Vec3d, K::Vec3h}, "point3f[]", diag))
    if (lengthFits(prim, *positions, n->size() / 3, count, diag)) d.positions = vec3s(*n);
  // orientationsf (quatf, newer USD) wins over orientations (quath) when not empty.
  const usd::ComposedProperty* orient = authored(prim, "orientationsf");
  if (!orient || orient->value.numbers.empty()) orient = authored(prim, "orientations");
  if (orient && !orient->value.numbers.empty())
    if (auto n = numbersOf(prim, *orient, 4, {K::Quath, K::Quatf, K::Quatd}, "quath[] or quatf[]", diag);
        n && lengthFits(prim, *orient, n->size() / 4, count, diag))
      for (size_t i = 0; i < count; ++i) {
        Quatd q((*n)[4 * i], (*n)[4 * i + 1], (*n)[4 * i + 2], (*n)[4 * i + 3]);  // (real, i, j, k)
        if (q.norm() < 1e-12) {
          diag.error(orient->loc, where(prim, orient->name) + ": item " + std::to_string(i) +
                                      " is a zero quaternion, which is no rotation");
          return std::nullopt;
        }
        d.orientations.push_back(q.normalized());
      }
  for (auto [name, out] : {std::pair{"scales", &d.scales}, std::pair{"velocities", &d.velocities}})
    if (const usd::ComposedProperty* p = authored(prim, name); p && !p->value.numbers.empty())
      if (auto n = numbersOf(prim, *p, 3, {K::Vec3f, K::Vec3d, K::Vec3h}, "float3[]", diag);
          n && lengthFits(prim, *p, n->size() / 3, count, diag))
        *out = vec3s(*n);
  if (const usd::ComposedProperty* p = authored(prim, "ids"); p && !p->value.numbers.empty())
    if (auto n = numbersOf(prim, *p, 1, {K::Int64, K::Int, K::UInt, K::UInt64}, "int64[]", diag);
        n && lengthFits(prim, *p, n->size(), count, diag))
      for (double v : *n) d.ids.push_back(int64_t(v));
  if (const usd::ComposedProperty* p = authored(prim, "invisibleIds"))
    if (auto n = numbersOf(prim, *p, 1, {K::Int64, K::Int, K::UInt, K::UInt64}, "int64[]", diag))
      for (double v : *n) d.invisibleIds.insert(int64_t(v));
  // inactiveIds is list-op metadata (int64ListOp), not an attribute.
  if (auto it = prim.metadata.find("inactiveIds"); it != prim.metadata.end()) {
    if (it->second.intListOp)
      for (int64_t v : it->second.intListOp->applyTo({})) d.inactiveIds.insert(v);
    else if (usd::isNumeric(it->second.kind))
      for (double v : it->second.numbers) d.inactiveIds.insert(int64_t(v));
  }
  if (diag.errorCount() != errorsBefore) return std::nullopt;
  return d;
}

std::optional<Vec3d> instanceVelocity(const Prim& prim) {
  const Attribute* a = prim.findAttribute(kVelocityAttribute);
  if (!a || a->value.type() != ValueType::Vector3d) return std::nullopt;
  return a->value.get<Vec3d>();
}

void expandPointInstancers(const std::vector<const usd::ComposedPrim*>& instancers, Stage& stage,
                           const std::function<std::string(const std::string&)>& mapPath,
                           const std::function<void(const SourceLoc&, const std::string&, const std::string&)>& warn,
                           const AnimationClock& clock, Diagnostics& diag) {
  Expander expander(stage, mapPath, warn, clock, diag);
  // Imported parents first: reversed, an instancer inside another's
  // prototype is expanded before the copies of that prototype are made.
  for (auto it = instancers.rbegin(); it != instancers.rend(); ++it) expander.expand(**it);
}

}  // namespace sdg
