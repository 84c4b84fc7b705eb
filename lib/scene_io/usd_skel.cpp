#include "scene_io/usd_skel.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <set>

#include "scene_io/usd_mesh_topology.h"
#include "stage/path.h"

namespace sdg {
namespace {

using usd::ComposedPrim;
using usd::ComposedProperty;
using usd::ComposedStage;
using usd::Kind;

// USD writes matrices row-major for row vectors (translation in the last
// row); the stage's are column-vector: the transpose.
Matrix4d matrixAt(const usd::Value& v, size_t i) {
  Matrix4d m;
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) m(r, c) = v.numbers[16 * i + size_t(c) * 4 + size_t(r)];
  return m;
}

std::vector<Matrix4d> matrices(const usd::Value& v) {
  std::vector<Matrix4d> out;
  if (v.kind != Kind::Matrix4d) return out;
  for (size_t i = 0; i < v.numbers.size() / 16; ++i) out.push_back(matrixAt(v, i));
  return out;
}

// The property's value at a stage time code: its samples where they vary.
usd::Value valueAt(const ComposedProperty& p, double timeCode) {
  if (p.samples && p.samples->varies()) return p.samples->valueAt(timeCode);
  return p.value;
}

// A property of `path` or of its nearest ancestor that authors it (the
// skel: binding properties are inherited down namespace).
const ComposedProperty* inherited(const ComposedStage& composed, std::string path, const std::string& name) {
  while (!path.empty() && path != "/") {
    if (const ComposedPrim* prim = composed.prim(path))
      if (const ComposedProperty* p = prim->property(name); p && (!p->value.empty() || !p->targets.empty())) return p;
    path = std::string(path::parent(path));
  }
  return nullptr;
}

bool underSkelRoot(const ComposedStage& composed, std::string path) {
  while (!path.empty() && path != "/") {
    if (const ComposedPrim* prim = composed.prim(path); prim && prim->typeName == "SkelRoot") return true;
    path = std::string(path::parent(path));
  }
  return false;
}

int elementSize(const ComposedProperty& p) {
  auto it = p.metadata.find("elementSize");
  if (it == p.metadata.end() || !usd::isNumeric(it->second.kind) || it->second.numbers.empty()) return 1;
  const double v = it->second.numbers[0];
  return v >= 1 && v <= 64 ? int(v) : 0;  // 0: refused below
}

// One Skeleton and its animation, read once for every mesh bound to it.
struct SkelBinding {
  const ComposedPrim* skeleton = nullptr;
  SkelTopology topology;
  std::vector<Matrix4d> bind, rest;
  std::map<std::string, int> jointIndex;
  const ComposedPrim* animation = nullptr;
  std::vector<int> animatedJoint;  // per joint of the animation: the skeleton's index (-1: unknown)
  std::vector<double> times;       // the animation's varying sample times
  std::string stagePath;

  // Local transforms at a time code: the animation's where it names a
  // joint, the rest transforms elsewhere.
  std::vector<Matrix4d> locals(double timeCode) const {
    std::vector<Matrix4d> out = rest;
    if (!animation) return out;
    auto array = [&](const char* name) {
      const ComposedProperty* p = animation->property(name);
      return p ? valueAt(*p, timeCode) : usd::Value{};
    };
    const usd::Value t = array("translations"), r = array("rotations"), s = array("scales");
    for (size_t k = 0; k < animatedJoint.size(); ++k) {
      const int j = animatedJoint[k];
      if (j < 0) continue;
      Vec3d translation = Vec3d::Zero(), scale = Vec3d::Ones();
      Quatd rotation = Quatd::Identity();
      if (t.numbers.size() >= 3 * (k + 1)) translation = Vec3d(t.numbers[3 * k], t.numbers[3 * k + 1], t.numbers[3 * k + 2]);
      if (s.numbers.size() >= 3 * (k + 1)) scale = Vec3d(s.numbers[3 * k], s.numbers[3 * k + 1], s.numbers[3 * k + 2]);
      if (r.numbers.size() >= 4 * (k + 1)) {
        rotation = Quatd(r.numbers[4 * k], r.numbers[4 * k + 1], r.numbers[4 * k + 2], r.numbers[4 * k + 3]);
        if (rotation.norm() > 0) rotation.normalize();
        else rotation = Quatd::Identity();
      }
      out[size_t(j)] = skelLocalTransform(translation, rotation, scale);
    }
    return out;
  }
};

bool isFiniteMatrix(const Matrix4d& m) { return m.allFinite(); }

class SkelPoser {
 public:
  SkelPoser(const ComposedStage& composed, const std::function<std::string(const std::string&)>& stageOf,
            const AnimationClock& clock, Stage& stage, UsdLosses& losses, const UsdSkelWarn& warn, Diagnostics& diag)
      : composed_(composed), stageOf_(stageOf), clock_(clock), stage_(stage), losses_(losses), warn_(warn), diag_(diag) {}

  void pose(const UsdSkinnedMesh& skinned) {
    const ComposedPrim& mesh = *skinned.mesh;
    if (!underSkelRoot(composed_, mesh.path)) {
      warn_(mesh.loc, "skel:noroot:" + mesh.path,
            mesh.path + ": has skel:jointIndices but no SkelRoot above it; USD does not skin it, neither does this");
      return;
    }
    const ComposedProperty* skelRel = inherited(composed_, mesh.path, "skel:skeleton");
    if (!skelRel || skelRel->targets.empty()) {
      warn_(mesh.loc, "skel:noskel:" + mesh.path,
            mesh.path + ": has skel:jointIndices but no skel:skeleton binding on it or above it; drawn unposed");
      return;
    }
    const SkelBinding* skel = binding(skelRel->targets[0], *skelRel);
    if (!skel) return;
    noteLosses(mesh);

    const size_t errorsBefore = diag_.errorCount();
    std::vector<int> meshToSkel = meshJointMap(mesh, *skel);
    SkinInfluences influences = readInfluences(mesh, meshToSkel.size());
    if (diag_.errorCount() > errorsBefore) return;
    Matrix4d geomBind = Matrix4d::Identity();
    if (const ComposedProperty* g = inherited(composed_, mesh.path, "primvars:skel:geomBindTransform");
        g && g->value.kind == Kind::Matrix4d && !g->value.isArray && g->value.numbers.size() == 16)
      geomBind = matrixAt(g->value, 0);

    // Skeleton space into each stage prim's own (the mesh's transform does
    // not apply to skinned points in USD; its children keep it).
    const Prim* skelPrim = stage_.find(skel->stagePath);
    const Matrix4d skelWorld = skelPrim ? stage_.worldMatrix(*skelPrim) : Matrix4d::Identity();

    struct Target {
      Prim* prim;
      Matrix4d after;
      FloatArray points, normals;
      std::vector<int32_t> cornerPoints;  // for per-corner normals
      AnimatedValue pointsTrack, normalsTrack;
    };
    std::vector<Target> targets;
    for (const std::string& path : skinned.stagePaths) {
      Prim* prim = stage_.find(path);
      if (!prim || !prim->findAttribute("points")) continue;
      Target t{prim, stage_.worldMatrix(*prim).inverse() * skelWorld, prim->findAttribute("points")->value.get<FloatArray>(),
               {}, {}, {}, {}};
      if (const Attribute* n = prim->findAttribute("normals")) {
        t.normals = n->value.get<FloatArray>();
        if (t.normals.size() != t.points.size())
          if (const Attribute* idx = prim->findAttribute("faceVertexIndices")) {
            const auto items = idx->value.get<IntArray>().items();
            t.cornerPoints.assign(items.begin(), items.end());
          }
      }
      targets.push_back(std::move(t));
    }
    if (targets.empty()) return;
    const size_t pointCount = targets.front().points.size() / 3;
    if (!influences.rigid && influences.joints.size() != pointCount * size_t(influences.perPoint)) {
      const ComposedProperty* ji = mesh.property("primvars:skel:jointIndices");
      diag_.error(ji->loc, mesh.path + ".primvars:skel:jointIndices: expected " +
                               std::to_string(pointCount * size_t(influences.perPoint)) + " items (" +
                               std::to_string(influences.perPoint) + " per point, elementSize), found " +
                               std::to_string(influences.joints.size()));
      return;
    }

    std::vector<Matrix4d> meshSkinning(meshToSkel.size());
    std::vector<float> outPoints, outNormals;
    auto posedAt = [&](double timeCode, Target& t) {
      const std::vector<Matrix4d> all =
          skinningTransforms(skel->topology, skel->locals(timeCode), skel->bind);
      for (size_t k = 0; k < meshToSkel.size(); ++k) meshSkinning[k] = all[size_t(meshToSkel[k])];
      skinPoints(t.points.items(), t.normals.items(), t.cornerPoints, geomBind, influences, meshSkinning, t.after,
                 outPoints, outNormals);
    };
    // A pose from non-finite animation values (a hostile file) is refused, never drawn.
    auto finite = [&](double time) {
      if (std::all_of(outPoints.begin(), outPoints.end(), [](float v) { return std::isfinite(v); })) return true;
      diag_.error(skel->animation ? skel->animation->loc : skel->skeleton->loc,
                  mesh.path + ": skinning at time code " + std::to_string(time) +
                      " gives points that are not finite (the animation's translations, rotations or scales)");
      return false;
    };
    for (Target& t : targets) {
      posedAt(clock_.startTimeCode, t);
      if (!finite(clock_.startTimeCode)) return;
      t.prim->setAttribute("points", Value::makeFloatArray(ValueType::Point3fArray, outPoints));
      if (!(t.normals.size() == 0)) t.prim->setAttribute("normals", Value::makeFloatArray(ValueType::Normal3fArray, outNormals));
      if (skel->times.size() < 2) continue;
      if (stage_.animation().find(t.prim->path(), "points")) {
        warn_(mesh.loc, "skel:sampledpoints:" + mesh.path,
              mesh.path + ": its points are time-sampled and skinned; the time samples play, the skinning is at the start only");
        continue;
      }
      for (AnimatedValue* track : {&t.pointsTrack, &t.normalsTrack}) {
        track->primPath = t.prim->path();
        track->clock = clock_;
      }
      t.pointsTrack.name = "points";
      t.normalsTrack.name = "normals";
      t.pointsTrack.imported = t.prim->findAttribute("points")->value;
      if (!(t.normals.size() == 0)) t.normalsTrack.imported = t.prim->findAttribute("normals")->value;
      for (double time : skel->times) {
        posedAt(time, t);
        if (!finite(time)) return;
        t.pointsTrack.times.push_back(time);
        t.pointsTrack.values.push_back(Value::makeFloatArray(ValueType::Point3fArray, outPoints));
        if (!(t.normals.size() == 0)) {
          t.normalsTrack.times.push_back(time);
          t.normalsTrack.values.push_back(Value::makeFloatArray(ValueType::Normal3fArray, outNormals));
        }
      }
      stage_.animation().add(std::move(t.pointsTrack));
      if (!(t.normals.size() == 0)) stage_.animation().add(std::move(t.normalsTrack));
    }
  }

 private:
  // What UsdSkel would apply and this does not.
  void noteLosses(const ComposedPrim& mesh) {
    if (const ComposedProperty* shapes = inherited(composed_, mesh.path, "skel:blendShapes"))
      losses_.note(UsdLossKind::Attribute, "skel:blendShapes (blend shapes)", shapes->loc, mesh.path);
    if (const ComposedProperty* method = mesh.property("primvars:skel:skinningMethod");
        method && usd::isText(method->value.kind) && !method->value.strings.empty() &&
        method->value.strings[0] == "dualQuaternion")
      losses_.note(UsdLossKind::Attribute, "primvars:skel:skinningMethod dualQuaternion (skinned linearly)",
                   method->loc, mesh.path);
  }

  // The skeleton's joints, bind and rest transforms and its animation,
  // read once; null (reported) when it cannot be used.
  const SkelBinding* binding(const std::string& skeletonPath, const ComposedProperty& rel) {
    if (auto it = bindings_.find(skeletonPath); it != bindings_.end()) return it->second ? &*it->second : nullptr;
    std::optional<SkelBinding>& slot = bindings_[skeletonPath];
    const ComposedPrim* skeleton = composed_.prim(skeletonPath);
    if (!skeleton || skeleton->typeName != "Skeleton") {
      diag_.error(rel.loc, "skel:skeleton targets " + skeletonPath + ", which is " +
                               (skeleton ? "a " + skeleton->typeName + ", not a Skeleton" : "not on the stage"));
      return nullptr;
    }
    SkelBinding b;
    b.skeleton = skeleton;
    b.stagePath = stageOf_(skeletonPath);
    const ComposedProperty* joints = skeleton->property("joints");
    if (!joints || !usd::isText(joints->value.kind) || joints->value.strings.empty()) {
      diag_.error(skeleton->loc, skeletonPath + ".joints: a Skeleton needs its joints (token[])");
      return nullptr;
    }
    b.topology = skelTopology(joints->value.strings);
    for (size_t j = 0; j < b.topology.joints.size(); ++j) b.jointIndex.emplace(b.topology.joints[j], int(j));
    const size_t n = b.topology.joints.size();
    auto readMatrices = [&](const char* name, std::vector<Matrix4d>& out) {
      const ComposedProperty* p = skeleton->property(name);
      if (!p || p->value.empty()) return false;
      out = matrices(p->value);
      if (out.size() != n || !std::all_of(out.begin(), out.end(), isFiniteMatrix)) {
        diag_.error(p->loc, skeletonPath + "." + name + ": expected " + std::to_string(n) +
                                " finite matrix4d (one per joint), found " + std::to_string(out.size()) + " " +
                                p->typeName);
        return false;
      }
      return true;
    };
    const size_t errorsBefore = diag_.errorCount();
    if (!readMatrices("bindTransforms", b.bind)) {
      if (diag_.errorCount() == errorsBefore)
        diag_.error(skeleton->loc, skeletonPath + ".bindTransforms: a Skeleton needs its bind transforms (matrix4d[])");
      return nullptr;
    }
    if (!readMatrices("restTransforms", b.rest)) {
      if (diag_.errorCount() > errorsBefore) return nullptr;
      // No rest pose: the bind pose in local terms, where the animation does not say.
      b.rest.resize(n);
      for (size_t j = 0; j < n; ++j) {
        const int parent = b.topology.parent[j];
        b.rest[j] = parent < 0 ? b.bind[j] : b.bind[size_t(parent)].inverse() * b.bind[j];
      }
    }
    const ComposedProperty* anim = inherited(composed_, skeletonPath, "skel:animationSource");
    if (anim && !anim->targets.empty()) {
      const ComposedPrim* a = composed_.prim(anim->targets[0]);
      if (!a || a->typeName != "SkelAnimation") {
        diag_.error(anim->loc, "skel:animationSource targets " + anim->targets[0] + ", which is " +
                                   (a ? "a " + a->typeName + ", not a SkelAnimation" : "not on the stage"));
        return nullptr;
      }
      b.animation = a;
      const ComposedProperty* animJoints = a->property("joints");
      if (animJoints && usd::isText(animJoints->value.kind))
        for (const std::string& name : animJoints->value.strings) {
          auto it = b.jointIndex.find(name);
          b.animatedJoint.push_back(it == b.jointIndex.end() ? -1 : it->second);
        }
      std::set<double> times;
      for (const char* name : {"translations", "rotations", "scales"})
        if (const ComposedProperty* p = a->property(name); p && p->samples && p->samples->varies())
          for (double t : p->samples->stageTimes()) times.insert(t);
      b.times.assign(times.begin(), times.end());
      if (a->property("blendShapeWeights"))
        losses_.note(UsdLossKind::Attribute, "blendShapeWeights (blend shapes)", a->loc, a->path);
    }
    slot = std::move(b);
    return &*slot;
  }

  // Each of the mesh's joint indices as the skeleton's: through skel:joints
  // (on the mesh or above it) where authored, else one to one.
  std::vector<int> meshJointMap(const ComposedPrim& mesh, const SkelBinding& skel) {
    std::vector<int> map;
    const ComposedProperty* joints = inherited(composed_, mesh.path, "skel:joints");
    if (!joints || !usd::isText(joints->value.kind)) {
      for (size_t j = 0; j < skel.topology.joints.size(); ++j) map.push_back(int(j));
      return map;
    }
    for (const std::string& name : joints->value.strings) {
      auto it = skel.jointIndex.find(name);
      if (it == skel.jointIndex.end()) {
        diag_.error(joints->loc, mesh.path + ".skel:joints: " + name + " is not a joint of " + skel.skeleton->path);
        return {};
      }
      map.push_back(it->second);
    }
    return map;
  }

  SkinInfluences readInfluences(const ComposedPrim& mesh, size_t joints) {
    SkinInfluences in;
    const ComposedProperty* indices = mesh.property("primvars:skel:jointIndices");
    const ComposedProperty* weights = mesh.property("primvars:skel:jointWeights");
    if (!weights || weights->value.empty()) {
      diag_.error(indices->loc, mesh.path + ": primvars:skel:jointIndices needs primvars:skel:jointWeights beside it");
      return in;
    }
    in.perPoint = elementSize(*indices);
    in.rigid = usd_map::primvarInterpolation(*indices) == "constant";
    if (in.perPoint < 1 || elementSize(*weights) != in.perPoint) {
      diag_.error(weights->loc, mesh.path + ": primvars:skel:jointWeights has elementSize " +
                                    std::to_string(elementSize(*weights)) + ", jointIndices " +
                                    std::to_string(in.perPoint) + "; expected the same, at least 1");
      return in;
    }
    for (double v : indices->value.numbers) in.joints.push_back(int32_t(v));
    for (double v : weights->value.numbers) in.weights.push_back(float(v));
    if (in.joints.size() != in.weights.size()) {
      diag_.error(weights->loc, mesh.path + ".primvars:skel:jointWeights: expected " + std::to_string(in.joints.size()) +
                                    " items (as jointIndices), found " + std::to_string(in.weights.size()));
      return in;
    }
    if (in.rigid && in.joints.size() != size_t(in.perPoint)) {
      diag_.error(indices->loc, mesh.path + ".primvars:skel:jointIndices: constant interpolation expects " +
                                    std::to_string(in.perPoint) + " items (elementSize), found " +
                                    std::to_string(in.joints.size()));
      return in;
    }
    for (size_t i = 0; i < in.joints.size(); ++i)
      if (in.joints[i] < 0 || size_t(in.joints[i]) >= joints || !std::isfinite(in.weights[i])) {
        diag_.error(indices->loc, mesh.path + ".primvars:skel:jointIndices[" + std::to_string(i) + "] is " +
                                      std::to_string(in.joints[i]) + ", outside the " + std::to_string(joints) +
                                      " joints (or its weight is not finite)");
        return in;
      }
    return in;
  }

  const ComposedStage& composed_;
  const std::function<std::string(const std::string&)>& stageOf_;
  AnimationClock clock_;
  Stage& stage_;
  UsdLosses& losses_;
  const UsdSkelWarn& warn_;
  Diagnostics& diag_;
  std::map<std::string, std::optional<SkelBinding>> bindings_;
};

}  // namespace

SkelTopology skelTopology(std::vector<std::string> joints) {
  SkelTopology t;
  t.joints = std::move(joints);
  std::map<std::string, int> index;
  for (size_t j = 0; j < t.joints.size(); ++j) index.emplace(t.joints[j], int(j));
  for (const std::string& joint : t.joints) {
    int parent = -1;
    for (size_t slash = joint.rfind('/'); slash != std::string::npos && parent < 0;
         slash = slash == 0 ? std::string::npos : joint.rfind('/', slash - 1)) {
      auto it = index.find(joint.substr(0, slash));
      if (it != index.end()) parent = it->second;
    }
    t.parent.push_back(parent);
  }
  return t;
}

Matrix4d skelLocalTransform(const Vec3d& translation, const Quatd& rotation, const Vec3d& scale) {
  Matrix4d m = Matrix4d::Identity();
  m.topLeftCorner<3, 3>() = rotation.toRotationMatrix() * scale.asDiagonal();
  m.topRightCorner<3, 1>() = translation;
  return m;
}

std::vector<Matrix4d> skinningTransforms(const SkelTopology& topology, std::span<const Matrix4d> local,
                                         std::span<const Matrix4d> bind) {
  const size_t n = topology.joints.size();
  std::vector<Matrix4d> skelSpace(n), out(n);
  std::vector<char> done(n, 0);
  // Parents first, whatever order the joints are listed in (a joint's
  // parent path is shorter, but a file may list children first).
  std::function<const Matrix4d&(size_t)> resolve = [&](size_t j) -> const Matrix4d& {
    if (!done[j]) {
      done[j] = 2;  // in progress: a cycle cannot happen through path prefixes
      const int p = topology.parent[j];
      skelSpace[j] = p < 0 ? local[j] : Matrix4d(resolve(size_t(p)) * local[j]);
      done[j] = 1;
    }
    return skelSpace[j];
  };
  for (size_t j = 0; j < n; ++j) out[j] = resolve(j) * bind[j].inverse();
  return out;
}

void skinPoints(std::span<const float> points, std::span<const float> normals, std::span<const int32_t> cornerPoints,
                const Matrix4d& geomBind, const SkinInfluences& influences, std::span<const Matrix4d> skinning,
                const Matrix4d& after, std::vector<float>& outPoints, std::vector<float>& outNormals) {
  const size_t count = points.size() / 3;
  const int per = influences.perPoint;
  // The blended transform of each point (after * sum w_k S_k * geomBind).
  auto blended = [&](size_t point) {
    const size_t first = influences.rigid ? 0 : point * size_t(per);
    Matrix4d sum = Matrix4d::Zero();
    double total = 0;
    for (int k = 0; k < per; ++k) {
      const float w = influences.weights[first + size_t(k)];
      if (w == 0.0f) continue;
      sum += double(w) * skinning[size_t(influences.joints[first + size_t(k)])];
      total += w;
    }
    if (total == 0) return Matrix4d(after * geomBind);
    return Matrix4d(after * (sum / total) * geomBind);
  };
  std::vector<Matrix4d> perPoint(count);
  for (size_t i = 0; i < count; ++i) perPoint[i] = blended(i);
  outPoints.resize(points.size());
  for (size_t i = 0; i < count; ++i) {
    const Vec3d p = (perPoint[i] * Eigen::Vector4d(points[3 * i], points[3 * i + 1], points[3 * i + 2], 1.0)).head<3>();
    for (int c = 0; c < 3; ++c) outPoints[3 * i + size_t(c)] = float(p[c]);
  }
  outNormals.resize(normals.size());
  if (normals.empty()) return;
  std::vector<Matrix3d> normalMatrix(count);
  for (size_t i = 0; i < count; ++i) normalMatrix[i] = perPoint[i].topLeftCorner<3, 3>().inverse().transpose();
  const bool perCorner = !cornerPoints.empty() && normals.size() == 3 * cornerPoints.size();
  for (size_t i = 0; i < normals.size() / 3; ++i) {
    const size_t point = perCorner ? size_t(cornerPoints[i]) : i;
    Vec3d n(normals[3 * i], normals[3 * i + 1], normals[3 * i + 2]);
    if (point < count) {
      n = normalMatrix[point] * n;
      if (n.norm() > 0) n.normalize();
    }
    for (int c = 0; c < 3; ++c) outNormals[3 * i + size_t(c)] = float(n[c]);
  }
}

bool isSkeletonAttribute(const std::string& name) {
  return name == "joints" || name == "jointNames" || name == "bindTransforms" || name == "restTransforms";
}

void poseUsdSkinnedMeshes(const usd::ComposedStage& composed, const std::vector<UsdSkinnedMesh>& meshes,
                          const std::function<std::string(const std::string&)>& stageOf, const AnimationClock& clock,
                          Stage& stage, UsdLosses& losses, const UsdSkelWarn& warn, Diagnostics& diag) {
  SkelPoser poser(composed, stageOf, clock, stage, losses, warn, diag);
  for (const UsdSkinnedMesh& mesh : meshes) poser.pose(mesh);
}

}  // namespace sdg
