#include "writers/bop_models.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <map>

#include "assets/mesh_source.h"
#include "writers/bop_json.h"

namespace sdg {
namespace {

constexpr double kPi = 3.14159265358979323846;

template <typename T>
void put(std::vector<uint8_t>& out, const T& v) {
  const auto* p = reinterpret_cast<const uint8_t*>(&v);
  out.insert(out.end(), p, p + sizeof(T));
}

std::vector<uint8_t> plyBytes(const BopObject& o) {
  const std::string header = "ply\nformat binary_little_endian 1.0\ncomment sdgbehave BOP model of '" + o.label +
                             "', millimetres\nelement vertex " + std::to_string(o.positions.size()) +
                             "\nproperty float x\nproperty float y\nproperty float z\nproperty float nx\n"
                             "property float ny\nproperty float nz\nelement face " +
                             std::to_string(o.indices.size() / 3) +
                             "\nproperty list uchar int vertex_indices\nend_header\n";
  std::vector<uint8_t> out(header.begin(), header.end());
  for (size_t v = 0; v < o.positions.size(); ++v) {
    for (int c = 0; c < 3; ++c) put(out, o.positions[v][c]);
    for (int c = 0; c < 3; ++c) put(out, o.normals[v][c]);
  }
  for (size_t t = 0; t + 2 < o.indices.size(); t += 3) {
    put(out, uint8_t(3));
    for (int c = 0; c < 3; ++c) put(out, int32_t(o.indices[t + size_t(c)]));
  }
  return out;
}

// Row-wise 4 x 4 rotation about `axis` through the model origin.
nlohmann::json discreteSymmetry(const BopSymmetry& s) {
  const Matrix3d r = Eigen::AngleAxisd(s.angleDegrees * kPi / 180.0, s.axis.normalized()).toRotationMatrix();
  nlohmann::json m = nlohmann::json::array();
  for (int row = 0; row < 4; ++row)
    for (int col = 0; col < 4; ++col) {
      double v = row < 3 && col < 3 ? r(row, col) : (row == 3 && col == 3 ? 1.0 : 0.0);
      if (std::abs(v) < 1e-12) v = 0.0;  // exact zeros, not 6e-17
      m.push_back(v);
    }
  return m;
}

nlohmann::json modelInfo(const BopObject& o) {
  nlohmann::json j;
  Eigen::AlignedBox3d box;
  for (const Vec3f& p : o.positions) box.extend(p.cast<double>());
  if (box.isEmpty()) box.extend(Vec3d::Zero());
  j["diameter"] = pointsDiameter(o.positions);
  const char* axes[] = {"x", "y", "z"};
  for (int a = 0; a < 3; ++a) {
    j[std::string("min_") + axes[a]] = box.min()[a];
    j[std::string("size_") + axes[a]] = box.max()[a] - box.min()[a];
  }
  nlohmann::json continuous = nlohmann::json::array(), discrete = nlohmann::json::array();
  for (const BopSymmetry& s : o.symmetries) {
    if (s.continuous) {
      const Vec3d axis = s.axis.normalized();
      continuous.push_back({{"axis", {axis.x(), axis.y(), axis.z()}}, {"offset", {0.0, 0.0, 0.0}}});
    } else {
      discrete.push_back(discreteSymmetry(s));
    }
  }
  if (!continuous.empty()) j["symmetries_continuous"] = continuous;
  if (!discrete.empty()) j["symmetries_discrete"] = discrete;
  return j;
}

// Appends an entity's render items to the object's model, in the root's
// frame with the root's scale applied, in millimetres.
void addEntityGeometry(BopObject& o, const SemanticEntity& entity, const RenderList& list, double mmPerUnit,
                       const AssetResolver& assets) {
  const ScaledPose root = splitScale(entity.worldFromRoot);
  // model = mm * R^T (world - t): the root's frame without its scale.
  Matrix4d modelFromWorld = Matrix4d::Identity();
  modelFromWorld.block<3, 3>(0, 0) = mmPerUnit * root.rotation.transpose();
  modelFromWorld.block<3, 1>(0, 3) = -mmPerUnit * (root.rotation.transpose() * root.translation);
  for (size_t item : entity.items) {
    const RenderItem& it = list.items[item];
    const MeshData mesh = meshDataFor(it.mesh, assets, it.primPath);
    const Matrix4d modelFromLocal = modelFromWorld * it.worldFromLocal;
    const Matrix3d normalMatrix = modelFromLocal.block<3, 3>(0, 0).inverse().transpose();
    const uint32_t base = uint32_t(o.positions.size());
    for (size_t v = 0; v < mesh.positions.size(); ++v) {
      const Vec3d p = (modelFromLocal * mesh.positions[v].cast<double>().homogeneous()).head<3>();
      o.positions.push_back(p.cast<float>());
      Vec3d n = v < mesh.normals.size() ? Vec3d(normalMatrix * mesh.normals[v].cast<double>()) : Vec3d(Vec3d::Zero());
      if (n.norm() > 0) n.normalize();
      o.normals.push_back(n.cast<float>());
    }
    for (uint32_t index : mesh.indices) o.indices.push_back(base + index);
  }
}

}  // namespace

ScaledPose splitScale(const Matrix4d& m) {
  ScaledPose pose;
  for (int c = 0; c < 3; ++c) {
    const Vec3d column = m.block<3, 1>(0, c);
    pose.scale[c] = column.norm();
    pose.rotation.col(c) = pose.scale[c] > 0 ? Vec3d(column / pose.scale[c]) : Vec3d(Vec3d::Unit(c));
  }
  if (pose.rotation.determinant() < 0) {  // a mirrored prim: keep R a rotation, the flip in the scale
    pose.rotation.col(2) *= -1;
    pose.scale[2] *= -1;
  }
  pose.translation = m.block<3, 1>(0, 3);
  return pose;
}

double pointsDiameter(const std::vector<Vec3f>& points) {
  std::vector<Vec3d> candidates;
  if (points.size() <= 4000) {
    for (const Vec3f& p : points) candidates.push_back(p.cast<double>());
  } else {
    // The two ends of a diameter are extreme along the direction joining
    // them; keep the extremes along directions spread over the sphere.
    constexpr int kDirections = 2000;
    const double golden = kPi * (3.0 - std::sqrt(5.0));
    std::vector<size_t> keep;
    for (int d = 0; d < kDirections; ++d) {
      const double z = 1.0 - 2.0 * (d + 0.5) / kDirections, r = std::sqrt(1.0 - z * z);
      const Vec3d dir(r * std::cos(golden * d), r * std::sin(golden * d), z);
      size_t lo = 0, hi = 0;
      for (size_t i = 0; i < points.size(); ++i) {
        const double v = dir.dot(points[i].cast<double>());
        if (v < dir.dot(points[lo].cast<double>())) lo = i;
        if (v > dir.dot(points[hi].cast<double>())) hi = i;
      }
      keep.push_back(lo);
      keep.push_back(hi);
    }
    std::sort(keep.begin(), keep.end());
    keep.erase(std::unique(keep.begin(), keep.end()), keep.end());
    for (size_t i : keep) candidates.push_back(points[i].cast<double>());
  }
  double best = 0;
  for (size_t i = 0; i < candidates.size(); ++i)
    for (size_t j = i + 1; j < candidates.size(); ++j) best = std::max(best, (candidates[i] - candidates[j]).squaredNorm());
  return std::sqrt(best);
}

std::vector<BopObject> collectBopObjects(const Stage& stage, const std::vector<std::string>& labels,
                                         const std::string& taxonomy, const std::vector<std::string>& semanticTypes,
                                         const AssetResolver& assets) {
  const RenderList list = buildRenderList(stage);
  const FrameSemantics semantics = computeSemantics(stage, list, semanticTypes);
  const double mmPerUnit = list.metersPerUnit * 1000.0;
  std::vector<BopObject> objects;
  for (size_t i = 0; i < labels.size(); ++i) {
    BopObject o;
    o.id = uint32_t(i + 1);
    o.label = labels[i];
    for (const SemanticEntity& e : semantics.entities) {
      auto label = e.labels.find(taxonomy);
      if (label == e.labels.end() || label->second != o.label) continue;
      o.modelPrim = e.primPath;
      o.scale = splitScale(e.worldFromRoot).scale;
      addEntityGeometry(o, e, list, mmPerUnit, assets);
      break;
    }
    objects.push_back(std::move(o));
  }
  return objects;
}

std::optional<std::string> addSpawnedModel(BopObject& object, const std::string& taxonomy,
                                           const std::vector<LabelledMesh>& spawned, const Stage& loaded,
                                           const std::vector<std::string>& semanticTypes, const AssetResolver& assets) {
  std::vector<const LabelledMesh*> files;
  for (const LabelledMesh& m : spawned)
    if (m.taxonomy == taxonomy && m.label == object.label &&
        std::none_of(files.begin(), files.end(), [&](const LabelledMesh* f) { return f->url == m.url; }))
      files.push_back(&m);
  if (files.empty()) return "no prim is labelled " + taxonomy + ": '" + object.label + "' in the scene as loaded, " +
                            "and no behavior spawns a mesh with that label; a BOP object's model is taken from the first one";
  std::optional<BopObject> first;
  for (const LabelledMesh* file : files) {
    Stage alone;
    alone.metadata() = loaded.metadata();
    Prim& prim = alone.definePrim("/Model", PrimType::Mesh);
    prim.setAttribute("asset", Value::makeAsset(file->url));
    prim.semantics()[taxonomy] = {object.label};
    BopObject model = collectBopObjects(alone, {object.label}, taxonomy, semanticTypes, assets).front();
    if (!first) {
      first = std::move(model);
      first->modelPrim = file->url + " (spawned by " + file->spawner + ")";
      continue;
    }
    bool same = model.positions.size() == first->positions.size() && model.indices == first->indices;
    for (size_t v = 0; same && v < model.positions.size(); ++v)
      same = (model.positions[v] - first->positions[v]).norm() < 1e-3f;  // millimetres
    if (!same)
      return "'" + object.label + "' is spawned from meshes of different shapes (" + files.front()->url + " and " +
             file->url + ", by " + file->spawner + "); a BOP object has one model: give each mesh its own label " +
             "('file#label') and list the labels";
  }
  object.modelPrim = first->modelPrim;
  object.scale = Vec3d::Ones();
  object.positions = std::move(first->positions);
  object.normals = std::move(first->normals);
  object.indices = std::move(first->indices);
  return std::nullopt;
}

std::vector<OutputFile> bopModelFiles(const std::vector<BopObject>& objects) {
  std::vector<OutputFile> files;
  std::vector<std::pair<uint64_t, nlohmann::json>> info;
  for (const BopObject& o : objects) {
    char name[40];
    std::snprintf(name, sizeof name, "models/obj_%06u.ply", o.id);
    files.push_back({name, plyBytes(o)});
    info.emplace_back(o.id, modelInfo(o));
  }
  const std::string text = bopJsonFile(info);
  files.push_back({"models/models_info.json", std::vector<uint8_t>(text.begin(), text.end())});
  return files;
}

}  // namespace sdg
