#include "writers/basic_writer.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>
#include <set>

#include "render/camera_math.h"
#include "writers/colors.h"
#include "writers/npy.h"
#include "writers/png_encoder.h"
#include "writers/py_json.h"

namespace sdg {
namespace {

using Json = nlohmann::ordered_json;

std::vector<uint8_t> textBytes(const std::string& s) { return std::vector<uint8_t>(s.begin(), s.end()); }

template <typename T>
std::span<const uint8_t> bytesOf(const std::vector<T>& v) {
  return {reinterpret_cast<const uint8_t*>(v.data()), v.size() * sizeof(T)};
}

Json labelsJson(const LabelSet& labels) {
  Json j = Json::object();
  for (const auto& [taxonomy, value] : labels) j[taxonomy] = value;
  return j;
}

constexpr const char* kBox2dDescr =
    "[('semanticId', '<u4'), ('x_min', '<i4'), ('y_min', '<i4'), ('x_max', '<i4'), ('y_max', '<i4'), "
    "('occlusionRatio', '<f4')]";
constexpr const char* kBox3dDescr =
    "[('semanticId', '<u4'), ('x_min', '<f4'), ('y_min', '<f4'), ('z_min', '<f4'), ('x_max', '<f4'), "
    "('y_max', '<f4'), ('z_max', '<f4'), ('transform', '<f4', (4, 4)), ('occlusionRatio', '<f4')]";
constexpr const char* kOcclusionDescr = "[('instanceId', '<u4'), ('semanticId', '<u4'), ('occlusionRatio', '<f4')]";

template <typename T>
void put(std::vector<uint8_t>& out, const T& v) {
  const auto* p = reinterpret_cast<const uint8_t*>(&v);
  out.insert(out.end(), p, p + sizeof(T));
}

}  // namespace

BasicWriter::BasicWriter(const OptionSet& options, std::vector<std::string> productNames, int64_t seed)
    : options_(options), products_(std::move(productNames)), seed_(seed) {}

bool BasicWriter::needsCoverage() const {
  return options_.getBool("bounding_box_2d_loose") || options_.getBool("occlusion") ||
         options_.getBool("bounding_box_2d_tight") || options_.getBool("bounding_box_3d");
}

PassSelection BasicWriter::passesNeeded() const {
  PassSelection p;
  const bool cloud = options_.getBool("pointcloud");
  p.normals = cloud || options_.getBool("normals") || options_.getBool("distance_to_camera");
  p.imagePlane = options_.getBool("distance_to_image_plane");
  p.ids = cloud || needsAnnotations() || options_.getBool("instance_id_segmentation");
  return p;
}

bool BasicWriter::needsAnnotations() const {
  for (const char* k : {"bounding_box_2d_tight", "bounding_box_2d_loose", "semantic_segmentation",
                        "instance_segmentation", "bounding_box_3d", "occlusion", "pointcloud"})
    if (options_.getBool(k)) return true;
  return false;
}

std::string BasicWriter::prefix(size_t product, const std::string& annotator) const {
  if (products_.size() == 1) return "";
  if (options_.getBool("use_common_output_dir")) return annotator + "/" + products_[product] + "_";
  return products_[product] + "/" + annotator + "/";
}

std::string BasicWriter::frameName(uint64_t frame) const {
  std::string n = std::to_string(frame);
  const size_t padding = options_.getUInt("frame_padding");
  if (n.size() < padding) n.insert(0, padding - n.size(), '0');
  return n;
}

std::string BasicWriter::rgbPath(uint64_t frame, size_t product) const {
  return prefix(product, "rgb") + "rgb_" + frameName(frame) + ".png";
}

std::vector<OutputFile> BasicWriter::metadataFiles() const {
  Json j;
  j["name"] = "BasicWriter";
  j["version"] = "0.0.2";
  j["replicator_global_seed:"] = seed_;  // the key really ends in a colon
  return {{"metadata.txt", textBytes(pythonJsonDumps(j))}};
}

std::vector<OutputFile> BasicWriter::encode(const ProductFrame& in) const {
  std::vector<OutputFile> files;
  const FramePasses& f = in.passes;
  const FrameAnnotations& a = in.annotations;
  const uint32_t w = uint32_t(f.width), h = uint32_t(f.height);
  const std::string x = frameName(in.frame);
  auto name = [&](const std::string& annotator, const std::string& kind, const char* ext) {
    return prefix(in.product, annotator) + kind + "_" + x + "." + ext;
  };

  if (options_.getBool("rgb"))
    files.push_back({name("rgb", "rgb", "png"), encodePng(f.rgba, w, h, PngPixels::Rgba8, PngOptions::renderedImage())});

  // Segmentation images: RGBA colours from the id hash, or 16-bit ids.
  auto segmentation = [&](const std::vector<uint32_t>& ids, bool colorize) {
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
  };
  auto idKey = [](uint32_t id, bool colorize) { return colorize ? colorKey(idColor(id)) : std::to_string(id); };
  // The distinct ids of a frame, ascending. They are small (render and
  // semantic ids count prims), so marking beats a tree of 262,144 inserts.
  auto present = [](const std::vector<uint32_t>& ids) {
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
  };

  if (options_.getBool("semantic_segmentation")) {
    const bool colorize = options_.getBool("colorize_semantic_segmentation");
    files.push_back({name("semantic_segmentation", "semantic_segmentation", "png"), segmentation(a.semanticIds, colorize)});
    Json labels = Json::object();
    for (uint32_t id : present(a.semanticIds))
      if (id < in.semanticLabels.size()) labels[idKey(id, colorize)] = labelsJson(in.semanticLabels[id]);
    files.push_back({name("semantic_segmentation", "semantic_segmentation_labels", "json"), textBytes(pythonJsonDumps(labels))});
  }
  if (options_.getBool("instance_id_segmentation")) {
    // Per geometry prim: the render pass's own ids.
    const bool colorize = options_.getBool("colorize_instance_id_segmentation");
    files.push_back({name("instance_id_segmentation", "instance_id_segmentation", "png"), segmentation(f.instanceIds, colorize)});
    Json mapping = Json::object();
    for (uint32_t id : present(f.instanceIds)) {
      if (id == 0) continue;
      mapping[idKey(id, colorize)] = id < in.renderIdPaths.size() ? in.renderIdPaths[id] : "";
    }
    files.push_back({name("instance_id_segmentation", "instance_id_segmentation_mapping", "json"), textBytes(pythonJsonDumps(mapping))});
  }
  if (options_.getBool("instance_segmentation")) {
    const bool colorize = options_.getBool("colorize_instance_segmentation");
    files.push_back({name("instance_segmentation", "instance_segmentation", "png"), segmentation(a.instanceIds, colorize)});
    Json mapping = Json::object(), semantics = Json::object();
    for (uint32_t id : present(a.instanceIds)) {
      std::string path = id == 0 ? "BACKGROUND" : id == 1 ? "UNLABELLED" : in.entityPaths[id - 2];
      mapping[idKey(id, colorize)] = path;
      const LabelSet labels = id == 0   ? LabelSet{{"class", "BACKGROUND"}}
                              : id == 1 ? LabelSet{{"class", "UNLABELLED"}}
                                        : in.entityLabels[id - 2];
      semantics[idKey(id, colorize)] = labelsJson(labels);
    }
    files.push_back({name("instance_segmentation", "instance_segmentation_mapping", "json"), textBytes(pythonJsonDumps(mapping))});
    files.push_back({name("instance_segmentation", "instance_segmentation_semantics_mapping", "json"), textBytes(pythonJsonDumps(semantics))});
  }
  auto distance = [&](const char* kind, const std::vector<float>& d) {
    files.push_back({name(kind, kind, "npy"), encodeNpy("'<f4'", npyShape({h, w}), bytesOf(d))});
    if (options_.getBool("colorize_depth"))
      files.push_back(
          {name(kind, kind, "png"), encodePng(colorizeDistance(d), w, h, PngPixels::Gray8, PngOptions::renderedImage())});
  };
  if (options_.getBool("distance_to_camera")) distance("distance_to_camera", f.distanceToCamera);
  if (options_.getBool("hdr_color"))
    files.push_back({name("hdr_color", "hdr_color", "npy"), encodeNpy("'<f4'", npyShape({h, w, 3}), bytesOf(f.hdrColor))});
  if (options_.getBool("distance_to_image_plane")) distance("distance_to_image_plane", f.distanceToImagePlane);

  auto boxes2d = [&](const char* kind, const std::vector<Box2D>& boxes) {
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
    files.push_back({name(kind, kind, "npy"), encodeNpy(kBox2dDescr, npyShape({boxes.size()}), data)});
    files.push_back({name(kind, std::string(kind) + "_labels", "json"), textBytes(pythonJsonDumps(labels))});
    files.push_back({name(kind, std::string(kind) + "_prim_paths", "json"), textBytes(pythonJsonDumps(paths))});
  };
  if (options_.getBool("bounding_box_2d_tight")) boxes2d("bounding_box_2d_tight", a.tight);
  if (options_.getBool("bounding_box_2d_loose")) boxes2d("bounding_box_2d_loose", a.loose);
  if (options_.getBool("bounding_box_3d")) {
    const char* kind = "bounding_box_3d";
    std::vector<uint8_t> data;
    Json labels = Json::object(), paths = Json::array();
    std::set<uint32_t> ids;
    for (const Box3D& b : a.boxes3d) {
      put(data, b.semanticId);
      for (float v : b.extentMin) put(data, v);
      for (float v : b.extentMax) put(data, v);
      for (float v : b.transform) put(data, v);
      put(data, b.occlusionRatio);
      paths.push_back(in.entityPaths[b.entity]);
      ids.insert(b.semanticId);
    }
    for (uint32_t id : ids) labels[std::to_string(id)] = labelsJson(in.semanticLabels[id]);
    files.push_back({name(kind, kind, "npy"), encodeNpy(kBox3dDescr, npyShape({a.boxes3d.size()}), data)});
    files.push_back({name(kind, "bounding_box_3d_labels", "json"), textBytes(pythonJsonDumps(labels))});
    files.push_back({name(kind, "bounding_box_3d_prim_paths", "json"), textBytes(pythonJsonDumps(paths))});
  }
  if (options_.getBool("occlusion")) {
    std::vector<uint8_t> data;
    for (size_t e = 0; e < a.occlusion.size(); ++e) {
      put(data, uint32_t(e + 2));
      uint32_t semanticId = 0;
      for (const Box2D& b : a.tight) if (b.entity == e) semanticId = b.semanticId;
      for (const Box2D& b : a.loose) if (b.entity == e) semanticId = b.semanticId;
      put(data, semanticId);
      put(data, a.occlusion[e]);
    }
    files.push_back({name("occlusion", "occlusion", "npy"), encodeNpy(kOcclusionDescr, npyShape({a.occlusion.size()}), data)});
  }
  if (options_.getBool("normals")) {
    std::vector<uint8_t> rgba(f.normals.size());
    for (size_t i = 0; i < f.normals.size(); ++i)
      rgba[i] = uint8_t(std::clamp((f.normals[i] * 0.5f + 0.5f) * 255.0f, 0.0f, 255.0f));
    files.push_back({name("normals", "normals", "png"), encodePng(rgba, w, h, PngPixels::Rgba8, PngOptions::renderedImage())});
  }
  if (options_.getBool("camera_params"))
    files.push_back({name("camera_params", "camera_params", "json"),
                     textBytes(pythonJsonDumps(cameraParams(in.camera, f.width, f.height, in.metersPerUnit)))});
  if (options_.getBool("pointcloud")) {
    const bool unlabelled = options_.getBool("pointcloud_include_unlabelled");
    std::vector<float> points, normals;
    std::vector<uint8_t> rgb;
    std::vector<uint32_t> semantic, instance;
    const Matrix4d worldFromCamera = in.camera.worldFromCamera;
    const Matrix4d worldFromClip =
        (projectionMatrix(in.camera, f.width, f.height) * viewMatrix(in.camera)).inverse();
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
    files.push_back({name("pointcloud", "pointcloud", "npy"), encodeNpy("'<f4'", npyShape({count, 3}), bytesOf(points))});
    files.push_back({name("pointcloud", "pointcloud_rgb", "npy"), encodeNpy("'|u1'", npyShape({count, 4}), rgb)});
    files.push_back({name("pointcloud", "pointcloud_normals", "npy"), encodeNpy("'<f4'", npyShape({count, 4}), bytesOf(normals))});
    files.push_back({name("pointcloud", "pointcloud_semantic", "npy"), encodeNpy("'<u4'", npyShape({count}), bytesOf(semantic))});
    files.push_back({name("pointcloud", "pointcloud_instance", "npy"), encodeNpy("'<u4'", npyShape({count}), bytesOf(instance))});
  }
  return files;
}

}  // namespace sdg
