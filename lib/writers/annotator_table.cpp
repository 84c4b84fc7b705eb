#include "writers/annotator_table.h"

#include <algorithm>

#include "writers/annotator_encoders.h"
#include "writers/colors.h"
#include "writers/npy.h"
#include "writers/png_encoder.h"
#include "writers/py_json.h"

namespace sdg {

AnnotatorNeeds& AnnotatorNeeds::operator|=(const AnnotatorNeeds& o) {
  normals = normals || o.normals;
  imagePlane = imagePlane || o.imagePlane;
  ids = ids || o.ids;
  labels = labels || o.labels;
  coverage = coverage || o.coverage;
  radiance = radiance || o.radiance;
  motion = motion || o.motion;
  lidar = lidar || o.lidar;
  return *this;
}

PassSelection AnnotatorNeeds::passes() const {
  PassSelection p;
  p.normals = normals;
  p.imagePlane = imagePlane;
  p.ids = ids || labels;  // every label comes from the ids
  return p;
}

BasicLayout::BasicLayout(std::vector<std::string> products, uint32_t framePadding, bool commonOutputDir)
    : products_(std::move(products)), framePadding_(framePadding), commonOutputDir_(commonOutputDir) {}

std::string BasicLayout::prefix(size_t product, const std::string& annotator) const {
  if (products_.size() == 1) return "";
  if (commonOutputDir_) return annotator + "/" + products_[product] + "_";
  return products_[product] + "/" + annotator + "/";
}

std::string BasicLayout::path(size_t product, uint64_t frame, const std::string& annotator, const std::string& kind,
                              const char* ext) const {
  return prefix(product, annotator) + rootPath(frame, kind, ext);
}

std::string BasicLayout::rootPath(uint64_t frame, const std::string& kind, const char* ext) const {
  std::string n = std::to_string(frame);
  if (n.size() < framePadding_) n.insert(0, framePadding_ - n.size(), '0');
  return kind + "_" + n + "." + ext;
}

void AnnotatorOutput::add(const std::string& annotator, const std::string& kind, const char* ext,
                          std::vector<uint8_t> bytes) const {
  files.push_back({layout.path(frame.product, frame.frame, annotator, kind, ext), std::move(bytes)});
}

namespace encoders {

std::vector<uint8_t> textBytes(const std::string& s) { return std::vector<uint8_t>(s.begin(), s.end()); }

nlohmann::ordered_json labelsJson(const LabelSet& labels) {
  nlohmann::ordered_json j = nlohmann::ordered_json::object();
  for (const auto& [taxonomy, value] : labels) j[taxonomy] = value;
  return j;
}

void rgb(const AnnotatorOutput& out) {
  const FramePasses& f = out.frame.passes;
  out.add("rgb", "rgb", "png",
          encodePng(f.rgba, uint32_t(f.width), uint32_t(f.height), PngPixels::Rgba8, PngOptions::renderedImage()));
}

void hdrColor(const AnnotatorOutput& out) {
  const FramePasses& f = out.frame.passes;
  out.add("hdr_color", "hdr_color", "npy",
          encodeNpy("'<f4'", npyShape({size_t(f.height), size_t(f.width), 3}), bytesOf(f.hdrColor)));
}

namespace {
void distance(const AnnotatorOutput& out, const char* kind, const std::vector<float>& d) {
  const FramePasses& f = out.frame.passes;
  const uint32_t w = uint32_t(f.width), h = uint32_t(f.height);
  out.add(kind, kind, "npy", encodeNpy("'<f4'", npyShape({h, w}), bytesOf(d)));
  if (out.options.getBool("colorize_depth"))
    out.add(kind, kind, "png", encodePng(colorizeDistance(d), w, h, PngPixels::Gray8, PngOptions::renderedImage()));
}
}  // namespace

void distanceToCamera(const AnnotatorOutput& out) {
  distance(out, "distance_to_camera", out.frame.passes.distanceToCamera);
}

void distanceToImagePlane(const AnnotatorOutput& out) {
  distance(out, "distance_to_image_plane", out.frame.passes.distanceToImagePlane);
}

void normals(const AnnotatorOutput& out) {
  const FramePasses& f = out.frame.passes;
  std::vector<uint8_t> rgba(f.normals.size());
  for (size_t i = 0; i < f.normals.size(); ++i)
    rgba[i] = uint8_t(std::clamp((f.normals[i] * 0.5f + 0.5f) * 255.0f, 0.0f, 255.0f));
  out.add("normals", "normals", "png",
          encodePng(rgba, uint32_t(f.width), uint32_t(f.height), PngPixels::Rgba8, PngOptions::renderedImage()));
}

void cameraParams(const AnnotatorOutput& out) {
  const ProductFrame& in = out.frame;
  out.add("camera_params", "camera_params", "json",
          textBytes(pythonJsonDumps(sdg::cameraParams(in.camera, in.passes.width, in.passes.height, in.metersPerUnit))));
}

namespace {
void flow(const AnnotatorOutput& out, const char* kind, const std::vector<float>& flow) {
  const FramePasses& f = out.frame.passes;
  out.add(kind, kind, "npy", encodeNpy("'<f4'", npyShape({size_t(f.height), size_t(f.width), 2}), bytesOf(flow)));
}
}  // namespace

void forwardFlow(const AnnotatorOutput& out) { flow(out, "forward_flow", out.frame.forwardFlow); }
void backwardFlow(const AnnotatorOutput& out) { flow(out, "backward_flow", out.frame.backwardFlow); }

void motionVectors(const AnnotatorOutput& out) {
  // Isaac's layout: x, y, and two unused channels; x positive when the
  // surface moved left since the previous frame, y when it moved up, in
  // pixels: the backward flow's column and row.
  const FramePasses& f = out.frame.passes;
  const std::vector<float>& back = out.frame.backwardFlow;
  std::vector<float> vectors(f.pixelCount() * 4, 0.0f);
  for (size_t i = 0; i < f.pixelCount(); ++i) {
    vectors[i * 4] = back[i * 2 + 1];
    vectors[i * 4 + 1] = back[i * 2];
  }
  out.add("motion_vectors", "motion_vectors", "npy",
          encodeNpy("'<f4'", npyShape({size_t(f.height), size_t(f.width), 4}), bytesOf(vectors)));
}

}  // namespace encoders

std::span<const AnnotatorInfo> annotatorTable() {
  // Needs: labels for everything computed from the semantic entities,
  // coverage where an entity's unoccluded extent counts.
  constexpr AnnotatorNeeds none{}, normalsPass{.normals = true}, imagePlane{.imagePlane = true}, ids{.ids = true},
      labels{.labels = true}, covered{.labels = true, .coverage = true}, radiance{.radiance = true},
      cloud{.normals = true, .labels = true}, motion{.imagePlane = true, .ids = true, .motion = true},
      lidar{.lidar = true};
  static const AnnotatorInfo table[] = {
      {"rgb", none, encoders::rgb},
      {"semantic_segmentation", labels, encoders::semanticSegmentation},
      {"instance_id_segmentation", ids, encoders::instanceIdSegmentation},
      {"instance_segmentation", labels, encoders::instanceSegmentation},
      {"distance_to_camera", normalsPass, encoders::distanceToCamera},
      {"hdr_color", radiance, encoders::hdrColor},
      {"distance_to_image_plane", imagePlane, encoders::distanceToImagePlane},
      {"bounding_box_2d_tight", covered, encoders::boundingBox2dTight},
      {"bounding_box_2d_loose", covered, encoders::boundingBox2dLoose},
      {"bounding_box_3d", covered, encoders::boundingBox3d},
      {"motion_vectors", motion, encoders::motionVectors},
      {"occlusion", covered, encoders::occlusion},
      {"normals", normalsPass, encoders::normals},
      {"camera_params", none, encoders::cameraParams},
      {"pointcloud", cloud, encoders::pointcloud},
      {"forward_flow", motion, encoders::forwardFlow},
      {"backward_flow", motion, encoders::backwardFlow},
      {"lidar", lidar, encoders::lidar},
  };
  return table;
}

const AnnotatorInfo* findAnnotator(std::string_view name) {
  for (const AnnotatorInfo& a : annotatorTable())
    if (a.name == name) return &a;
  return nullptr;
}

}  // namespace sdg
