// The label annotators' files: segmentation images with their id maps, 2D
// and 3D boxes, occlusion and the point cloud, in Replicator's layouts.
#include <algorithm>
#include <array>
#include <cstring>
#include <map>
#include <set>

#include "render/camera_math.h"
#include "writers/annotator_encoders.h"
#include "writers/colors.h"
#include "writers/npy.h"
#include "writers/png_encoder.h"
#include "writers/py_json.h"

namespace sdg::encoders {
namespace {

using Json = nlohmann::ordered_json;

constexpr const char* kBox2dDescr =
    "[('semanticId', '<u4'), ('x_min', '<i4'), ('y_min', '<i4'), ('x_max', '<i4'), ('y_max', '<i4'), "
    "('occlusionRatio', '<f4')]";
constexpr const char* kBox3dDescr =
    "[('semanticId', '<u4'), ('x_min', '<f4'), ('y_min', '<f4'), ('z_min', '<f4'), ('x_max', '<f4'), "
    "('y_max', '<f4'), ('z_max', '<f4'), ('transform', '<f4', (4, 4)), ('occlusionRatio', '<f4')]";
constexpr const char* kOcclusionDescr = "[('instanceId', '<u4'), ('semanticId', '<u4'), ('occlusionRatio', '<f4')]";

// Segmentation images: RGBA colours from the id hash, or 16-bit ids.
std::vector<uint8_t> segmentationImage(const std::vector<uint32_t>& ids, uint32_t w, uint32_t h, bool colorize) {
  if (colorize) {
    std::vector<uint8_t> rgba(ids.size() * 4);
    std::map<uint32_t, std::array<uint8_t, 4>> cache;
    // Ids come in long runs along a row: look the colour up once per run.
    uint32_t runId = 0;
    std::array<uint8_t, 4> runColor{};
    for (size_t i = 0; i < ids.size(); ++i) {
      if (i == 0 || ids[i] != runId) {
        runId = ids[i];
        auto it = cache.find(runId);
        if (it == cache.end()) it = cache.emplace(runId, idColor(runId)).first;
        runColor = it->second;
      }
      std::memcpy(&rgba[i * 4], runColor.data(), 4);
    }
    return encodePng(rgba, w, h, PngPixels::Rgba8, PngOptions::labelMap());
  }
  std::vector<uint16_t> grey(ids.size());
  for (size_t i = 0; i < ids.size(); ++i) grey[i] = uint16_t(std::min<uint32_t>(ids[i], 65535));
  return encodePng(bytesOf(grey), w, h, PngPixels::Gray16, PngOptions::labelMap());
}

std::vector<uint8_t> segmentation(const AnnotatorOutput& out, const std::vector<uint32_t>& ids, bool colorize) {
  const FramePasses& f = out.frame.passes;
  return segmentationImage(ids, uint32_t(f.width), uint32_t(f.height), colorize);
}

std::string idKey(uint32_t id, bool colorize) { return colorize ? colorKey(idColor(id)) : std::to_string(id); }

// The distinct ids of a frame, ascending. They are small (render and
// semantic ids count prims), so marking beats a tree of 262,144 inserts.
std::vector<uint32_t> present(const std::vector<uint32_t>& ids) {
  std::vector<uint32_t> distinct;
  const uint32_t top = ids.empty() ? 0 : *std::max_element(ids.begin(), ids.end());
  if (top >= (1u << 24)) {
    distinct = ids;
    std::sort(distinct.begin(), distinct.end());
    distinct.erase(std::unique(distinct.begin(), distinct.end()), distinct.end());
    return distinct;
  }
  std::vector<uint8_t> seen(size_t(top) + 1, 0);
  for (uint32_t id : ids) seen[id] = 1;
  for (uint32_t id = 0; id <= top; ++id)
    if (seen[id]) distinct.push_back(id);
  return distinct;
}

std::vector<uint8_t> dumps(const Json& j) { return textBytes(pythonJsonDumps(j)); }

void boxes2d(const AnnotatorOutput& out, const char* kind, const std::vector<Box2D>& boxes) {
  const ProductFrame& in = out.frame;
  std::vector<uint8_t> data;
  Json labels = Json::object(), paths = Json::array();
  std::set<uint32_t> ids;
  for (const Box2D& b : boxes) {
    put(data, b.semanticId), put(data, b.xMin), put(data, b.yMin), put(data, b.xMax), put(data, b.yMax);
    put(data, b.occlusionRatio);
    paths.push_back(in.entityPaths[b.entity]);
    ids.insert(b.semanticId);
  }
  for (uint32_t id : ids) labels[std::to_string(id)] = labelsJson(in.semanticLabels[id]);
  out.add(kind, kind, "npy", encodeNpy(kBox2dDescr, npyShape({boxes.size()}), data));
  out.add(kind, std::string(kind) + "_labels", "json", dumps(labels));
  out.add(kind, std::string(kind) + "_prim_paths", "json", dumps(paths));
}

}  // namespace

void semanticSegmentation(const AnnotatorOutput& out) {
  const ProductFrame& in = out.frame;
  const std::vector<uint32_t>& ids = in.annotations.semanticIds;
  const bool colorize = out.options.getBool("colorize_semantic_segmentation");
  out.add("semantic_segmentation", "semantic_segmentation", "png", segmentation(out, ids, colorize));
  Json labels = Json::object();
  for (uint32_t id : present(ids))
    if (id < in.semanticLabels.size()) labels[idKey(id, colorize)] = labelsJson(in.semanticLabels[id]);
  out.add("semantic_segmentation", "semantic_segmentation_labels", "json", dumps(labels));
}

void instanceIdSegmentation(const AnnotatorOutput& out) {
  // Per geometry prim: the render pass's own ids.
  const ProductFrame& in = out.frame;
  const std::vector<uint32_t>& ids = in.passes.instanceIds;
  const bool colorize = out.options.getBool("colorize_instance_id_segmentation");
  out.add("instance_id_segmentation", "instance_id_segmentation", "png", segmentation(out, ids, colorize));
  Json mapping = Json::object();
  for (uint32_t id : present(ids)) {
    if (id == 0) continue;
    mapping[idKey(id, colorize)] = id < in.renderIdPaths.size() ? in.renderIdPaths[id] : "";
  }
  out.add("instance_id_segmentation", "instance_id_segmentation_mapping", "json", dumps(mapping));
}

void instanceSegmentation(const AnnotatorOutput& out) {
  const ProductFrame& in = out.frame;
  const std::vector<uint32_t>& ids = in.annotations.instanceIds;
  const bool colorize = out.options.getBool("colorize_instance_segmentation");
  out.add("instance_segmentation", "instance_segmentation", "png", segmentation(out, ids, colorize));
  Json mapping = Json::object(), semantics = Json::object();
  for (uint32_t id : present(ids)) {
    std::string path = id == 0 ? "BACKGROUND" : id == 1 ? "UNLABELLED" : in.entityPaths[id - 2];
    mapping[idKey(id, colorize)] = path;
    const LabelSet labels = id == 0   ? LabelSet{{"class", "BACKGROUND"}}
                            : id == 1 ? LabelSet{{"class", "UNLABELLED"}}
                                      : in.entityLabels[id - 2];
    semantics[idKey(id, colorize)] = labelsJson(labels);
  }
  out.add("instance_segmentation", "instance_segmentation_mapping", "json", dumps(mapping));
  out.add("instance_segmentation", "instance_segmentation_semantics_mapping", "json", dumps(semantics));
}

void boundingBox2dTight(const AnnotatorOutput& out) {
  boxes2d(out, "bounding_box_2d_tight", out.frame.annotations.tight);
}

void boundingBox2dLoose(const AnnotatorOutput& out) {
  boxes2d(out, "bounding_box_2d_loose", out.frame.annotations.loose);
}

void boundingBox3d(const AnnotatorOutput& out) {
  const ProductFrame& in = out.frame;
  const char* kind = "bounding_box_3d";
  std::vector<uint8_t> data;
  Json labels = Json::object(), paths = Json::array();
  std::set<uint32_t> ids;
  for (const Box3D& b : in.annotations.boxes3d) {
    put(data, b.semanticId);
    for (float v : b.extentMin) put(data, v);
    for (float v : b.extentMax) put(data, v);
    for (float v : b.transform) put(data, v);
    put(data, b.occlusionRatio);
    paths.push_back(in.entityPaths[b.entity]);
    ids.insert(b.semanticId);
  }
  for (uint32_t id : ids) labels[std::to_string(id)] = labelsJson(in.semanticLabels[id]);
  out.add(kind, kind, "npy", encodeNpy(kBox3dDescr, npyShape({in.annotations.boxes3d.size()}), data));
  out.add(kind, "bounding_box_3d_labels", "json", dumps(labels));
  out.add(kind, "bounding_box_3d_prim_paths", "json", dumps(paths));
}

void occlusion(const AnnotatorOutput& out) {
  const FrameAnnotations& a = out.frame.annotations;
  std::vector<uint8_t> data;
  for (size_t e = 0; e < a.occlusion.size(); ++e) {
    put(data, uint32_t(e + 2));
    uint32_t semanticId = 0;
    for (const Box2D& b : a.tight)
      if (b.entity == e) semanticId = b.semanticId;
    for (const Box2D& b : a.loose)
      if (b.entity == e) semanticId = b.semanticId;
    put(data, semanticId);
    put(data, a.occlusion[e]);
  }
  out.add("occlusion", "occlusion", "npy", encodeNpy(kOcclusionDescr, npyShape({a.occlusion.size()}), data));
}

void pointcloud(const AnnotatorOutput& out) {
  const ProductFrame& in = out.frame;
  const FramePasses& f = in.passes;
  const FrameAnnotations& a = in.annotations;
  const uint32_t w = uint32_t(f.width), h = uint32_t(f.height);
  const bool unlabelled = out.options.getBool("pointcloud_include_unlabelled");
  std::vector<float> points, normals;
  std::vector<uint8_t> rgb;
  std::vector<uint32_t> semantic, instance;
  const Matrix4d worldFromCamera = in.camera.worldFromCamera;
  const Matrix4d worldFromClip = (projectionMatrix(in.camera, f.width, f.height) * viewMatrix(in.camera)).inverse();
  const Vec3d eye = worldFromCamera.block<3, 1>(0, 3);
  for (uint32_t y = 0; y < h; ++y)
    for (uint32_t xx = 0; xx < w; ++xx) {
      const size_t i = size_t(y) * w + xx;
      if (a.semanticIds[i] == kBackgroundId || (!unlabelled && a.semanticIds[i] == kUnlabelledId)) continue;
      // The pixel centre's ray at the hit distance, back to world space.
      Eigen::Vector4d ndc((xx + 0.5) / w * 2 - 1, 1 - (y + 0.5) / h * 2, 1.0, 1.0);
      Eigen::Vector4d far = worldFromClip * ndc;
      Vec3d dir = (far.head<3>() / far.w() - eye).normalized();
      Vec3d world = eye + dir * (double(f.distanceToCamera[i]) / in.metersPerUnit);
      for (int c = 0; c < 3; ++c) points.push_back(float(world[c]));
      for (int c = 0; c < 4; ++c) rgb.push_back(f.rgba[i * 4 + size_t(c)]);
      for (int c = 0; c < 4; ++c) normals.push_back(f.normals[i * 4 + size_t(c)]);
      semantic.push_back(a.semanticIds[i]);
      instance.push_back(a.instanceIds[i]);
    }
  const size_t count = semantic.size();
  out.add("pointcloud", "pointcloud", "npy", encodeNpy("'<f4'", npyShape({count, 3}), bytesOf(points)));
  out.add("pointcloud", "pointcloud_rgb", "npy", encodeNpy("'|u1'", npyShape({count, 4}), rgb));
  out.add("pointcloud", "pointcloud_normals", "npy", encodeNpy("'<f4'", npyShape({count, 4}), bytesOf(normals)));
  out.add("pointcloud", "pointcloud_semantic", "npy", encodeNpy("'<u4'", npyShape({count}), bytesOf(semantic)));
  out.add("pointcloud", "pointcloud_instance", "npy", encodeNpy("'<u4'", npyShape({count}), bytesOf(instance)));
}

}  // namespace sdg::encoders
