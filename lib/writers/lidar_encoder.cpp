// The lidar annotator's files: per sweep of the frame, lidar_<sensor>_X.npy
// (a structured array, one row per point), lidar_<sensor>_X.json (the
// sensor's pose and pattern, and the labels of the ids its points carry)
// and, with lidar_kitti, KITTI's lidar_<sensor>_X.bin. Written once per
// frame, with the first render product, at the folder's root.
#include <set>

#include "core/text.h"
#include "stage/path.h"
#include "writers/annotator_encoders.h"
#include "writers/npy.h"
#include "writers/py_json.h"

namespace sdg::encoders {
namespace {

// One row per point, packed (38 bytes): docs/writers.md's field list.
constexpr const char* kLidarDescr =
    "[('x', '<f4'), ('y', '<f4'), ('z', '<f4'), ('range', '<f4'), ('intensity', '<f4'), ('ring', '<u2'), "
    "('azimuth', '<f4'), ('time', '<f4'), ('semantic_id', '<u4'), ('instance_id', '<u4')]";

using Json = nlohmann::ordered_json;

struct PointIds {
  uint32_t semantic = kBackgroundId, instance = kBackgroundId;
};

// The camera annotators' ids of a render id (writers/annotators.cpp): the
// entity's, UNLABELLED for unlabelled geometry, BACKGROUND for a miss.
PointIds idsOf(uint32_t renderId, const FrameSemantics& semantics) {
  if (renderId == 0) return {};
  const auto& ofRender = semantics.entityOfRenderId;
  const uint32_t e = renderId < ofRender.size() ? ofRender[renderId] : 0;
  if (e == 0) return {kUnlabelledId, kUnlabelledId};
  return {semantics.entities[e - 1].semanticId, semantics.entities[e - 1].instanceId};
}

Json matrixJson(const Matrix4d& m) {
  Json rows = Json::array();
  for (int r = 0; r < 4; ++r) {
    Json row = Json::array();
    for (int c = 0; c < 4; ++c) row.push_back(m(r, c));
    rows.push_back(row);
  }
  return rows;
}

// A float as its shortest decimal (0.2, not 0.20000000298023224).
double shortest(float v) { return std::stod(text::formatFloat(v)); }

Json sweepJson(const LidarSweep& sweep, uint64_t frame, size_t points, const std::set<uint32_t>& semanticIds,
               const std::set<uint32_t>& instanceIds, const FrameSemantics& semantics) {
  const LidarPattern& p = sweep.pattern;
  Json j;
  j["sensor"] = sweep.path;
  j["frame"] = frame;
  j["points"] = points;
  j["world_from_sensor"] = matrixJson(sweep.worldFromSensor);
  j["meters_per_unit"] = sweep.metersPerUnit;
  Json pattern;
  pattern["preset"] = sweep.preset;
  pattern["pattern"] = p.solidState ? "solidState" : "spinning";
  pattern["channels"] = p.channels();
  Json elevations = Json::array();
  for (float e : p.elevations) elevations.push_back(shortest(e));
  pattern["elevations"] = elevations;
  pattern["horizontal_resolution"] = p.azimuths;
  pattern["horizontal_fov"] = shortest(p.horizontalFov);
  pattern["rotation_rate"] = shortest(p.rotationRate);
  pattern["range"] = Json::array({shortest(p.rangeMin), shortest(p.rangeMax)});
  pattern["range_noise"] = shortest(p.rangeNoise);
  pattern["dropout"] = shortest(p.dropout);
  pattern["beam_divergence"] = shortest(p.beamDivergence);
  j["pattern"] = pattern;
  Json labels = Json::object();
  for (uint32_t id : semanticIds)
    if (id < semantics.semanticLabels.size()) labels[std::to_string(id)] = labelsJson(semantics.semanticLabels[id]);
  j["semantic_labels"] = labels;
  Json paths = Json::object();
  for (uint32_t id : instanceIds) {
    std::string path = id == kBackgroundId ? "BACKGROUND" : id == kUnlabelledId ? "UNLABELLED" : "";
    for (const SemanticEntity& e : semantics.entities)
      if (e.instanceId == id) path = e.primPath;
    paths[std::to_string(id)] = path;
  }
  j["instance_paths"] = paths;
  return j;
}

}  // namespace

void lidar(const AnnotatorOutput& out) {
  const ProductFrame& in = out.frame;
  if (in.product != 0) return;  // the sweeps belong to the frame, not to a camera
  const FrameSemantics& semantics = in.scene->semantics;
  const bool keepMisses = out.options.getBool("lidar_keep_misses");
  const bool kitti = out.options.getBool("lidar_kitti");
  for (const LidarSweep& sweep : in.scene->lidars) {
    std::vector<uint8_t> rows;
    std::vector<float> kittiRows;
    rows.reserve(sweep.returns.size() * 38);
    std::set<uint32_t> semanticIds, instanceIds;
    size_t points = 0;
    for (const LidarReturn& r : sweep.returns) {
      if (!keepMisses && !r.hit()) continue;
      const PointIds ids = idsOf(r.renderId, semantics);
      for (float v : {r.x, r.y, r.z, r.range, r.intensity}) put(rows, v);
      put(rows, uint16_t(r.ring));
      put(rows, r.azimuth);
      put(rows, r.time);
      put(rows, ids.semantic);
      put(rows, ids.instance);
      semanticIds.insert(ids.semantic);
      instanceIds.insert(ids.instance);
      if (kitti) kittiRows.insert(kittiRows.end(), {r.x, r.y, r.z, r.intensity});
      ++points;
    }
    const std::string kind = "lidar_" + std::string(path::name(sweep.path));
    out.files.push_back({out.layout.rootPath(in.frame, kind, "npy"), encodeNpy(kLidarDescr, npyShape({points}), rows)});
    out.files.push_back({out.layout.rootPath(in.frame, kind, "json"),
                         textBytes(pythonJsonDumps(sweepJson(sweep, in.frame, points, semanticIds, instanceIds, semantics)))});
    if (kitti) {
      const auto bytes = bytesOf(kittiRows);
      out.files.push_back({out.layout.rootPath(in.frame, kind, "bin"), std::vector<uint8_t>(bytes.begin(), bytes.end())});
    }
  }
}

}  // namespace sdg::encoders
