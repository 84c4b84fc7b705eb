#include "writers/bop_writer.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/diagnostics.h"
#include "core/file_io.h"
#include "core/text.h"
#include "render/camera_math.h"
#include "stage/path.h"
#include "writers/bop_json.h"
#include "writers/png_encoder.h"

namespace sdg {
namespace {

using Json = nlohmann::json;

// OpenCV's camera axes (x right, y down, looking along +z) from USD's
// (x right, y up, looking along -z).
const Matrix3d kCvFromUsdCamera = Vec3d(1, -1, -1).asDiagonal();

struct Intrinsics {
  double fx = 0, fy = 0, cx = 0, cy = 0;
};

// K from the camera's projection, in the BOP renderers' pixel convention:
// the image spans [0, W] x [0, H], pixel (i, j)'s centre at (i + 0.5, j + 0.5).
Intrinsics intrinsicsOf(const RenderCamera& camera, int width, int height) {
  const Matrix4d p = projectionMatrix(camera, width, height);
  return {p(0, 0) * width / 2.0, p(1, 1) * height / 2.0, (1.0 - p(0, 2)) * width / 2.0, (1.0 + p(1, 2)) * height / 2.0};
}

Json rowWise(const Matrix3d& m) {
  Json a = Json::array();
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) a.push_back(m(r, c));
  return a;
}

Json vec(const Vec3d& v) { return Json::array({v.x(), v.y(), v.z()}); }

std::vector<uint8_t> textBytes(const std::string& s) { return std::vector<uint8_t>(s.begin(), s.end()); }

std::string imageName(const char* folder, uint64_t imageId, const char* suffix = "") {
  char name[64];
  std::snprintf(name, sizeof name, "%s/%06llu%s.png", folder, static_cast<unsigned long long>(imageId), suffix);
  return name;
}

std::string maskName(const char* folder, uint64_t imageId, size_t gtId) {
  char name[64];
  std::snprintf(name, sizeof name, "%s/%06llu_%06zu.png", folder, static_cast<unsigned long long>(imageId), gtId);
  return name;
}

// BOP's boxes: [x, y, width, height] with width = x_max - x_min (the toolkit's
// calc_2d_bbox), [-1, -1, -1, -1] when the object is not visible.
Json bopBox(int xMin, int yMin, int xMax, int yMax) { return Json::array({xMin, yMin, xMax - xMin, yMax - yMin}); }

std::string trimmed(const std::string& s) {
  const size_t a = s.find_first_not_of(" \t"), b = s.find_last_not_of(" \t");
  return a == std::string::npos ? std::string() : s.substr(a, b - a + 1);
}

std::vector<BopSymmetry> symmetriesOf(const std::string& label, const std::vector<std::string>& declared,
                                      const SourceLoc& loc) {
  std::vector<BopSymmetry> out;
  for (const std::string& entry : declared) {
    const size_t colon = entry.find(':');
    const std::string name = trimmed(entry.substr(0, colon));
    if (colon == std::string::npos || name != label) continue;
    std::istringstream words(entry.substr(colon + 1));
    std::string kind, axisWord;
    words >> kind >> axisWord;
    BopSymmetry s;
    s.continuous = kind == "continuous";
    const bool known = s.continuous || kind == "discrete";
    if (axisWord == "x") s.axis = Vec3d::UnitX();
    else if (axisWord == "y") s.axis = Vec3d::UnitY();
    else if (axisWord == "z") s.axis = Vec3d::UnitZ();
    else s.axis = Vec3d::Zero();
    if (!s.continuous && !(words >> s.angleDegrees)) s.angleDegrees = 0;
    std::string extra;
    if (!known || s.axis.isZero() || (!s.continuous && s.angleDegrees == 0) || (words >> extra))
      throw SceneError(loc, "writer.symmetries: cannot read " + text::quote(entry) +
                                "; expected '<label>: continuous <x|y|z>' or '<label>: discrete <x|y|z> <degrees>'");
    out.push_back(s);
  }
  return out;
}

}  // namespace

uint64_t bopImageId(uint64_t frameInIteration, size_t product, size_t products) {
  return frameInIteration * products + product;
}

BopWriter::BopWriter(const WriterConfig& config, const WriterSetup& setup, const std::string& taxonomy,
                     const std::vector<std::string>& semanticTypes)
    : split_(config.options.getString("split")),
      depthScale_(config.options.get("depth_scale").get<double>()),
      taxonomy_(taxonomy),
      products_(setup.productNames.size()),
      width_(setup.width),
      height_(setup.height) {
  auto locOf = [&config](const char* option) {
    const SourceLoc* at = config.options.locOf(option);
    return at ? *at : config.loc;
  };
  const auto labels = config.options.get("objects").get<std::vector<std::string>>();
  if (labels.empty())
    throw SceneError(locOf("objects"), "writer.objects: list the " + taxonomy_ +
                                           " labels of the BOP objects, e.g. `objects: [drill, mug]` (obj_id 1, 2)");
  if (split_.empty() || split_.find('/') != std::string::npos || split_ == "." || split_ == "..")
    throw SceneError(locOf("split"), "writer.split: expected a folder name such as train_pbr, found " + text::quote(split_));
  objects_ = collectBopObjects(*setup.stage, labels, taxonomy_, semanticTypes, *setup.assets);
  const auto declared = config.options.get("symmetries").get<std::vector<std::string>>();
  for (const std::string& entry : declared) {
    const std::string name = trimmed(entry.substr(0, entry.find(':')));
    if (std::find(labels.begin(), labels.end(), name) == labels.end())
      throw SceneError(locOf("symmetries"), "writer.symmetries: " + text::quote(name) + " is not one of `objects`" +
                                                text::didYouMean(name, labels));
  }
  for (BopObject& o : objects_) {
    if (o.modelPrim.empty())
      if (std::optional<std::string> problem =
              addSpawnedModel(o, taxonomy_, setup.spawnedMeshes, *setup.stage, semanticTypes, *setup.assets))
        throw SceneError(locOf("objects"), "writer.objects: " + *problem);
    o.symmetries = symmetriesOf(o.label, declared, locOf("symmetries"));
  }
  const RenderList list = buildRenderList(*setup.stage);
  for (const RenderCamera& c : list.cameras)
    if (path::name(c.path) == setup.productNames.front()) firstCamera_ = c;
  for (const RenderCamera& c : list.cameras)
    if (c.orthographic)
      throw SceneError(config.loc, "BopWriter: camera " + c.path + " is orthographic; BOP's cam_K describes a pinhole");
}

AnnotatorNeeds BopWriter::needs() const {
  // Depth, visible masks from the ids, full silhouettes from the coverage masks.
  return AnnotatorNeeds{.imagePlane = true, .ids = true, .labels = true, .coverage = true};
}

std::vector<OutputFile> BopWriter::runFiles() const {
  std::vector<OutputFile> files = bopModelFiles(objects_);
  const Intrinsics k = intrinsicsOf(firstCamera_, width_, height_);
  Json camera{{"cx", k.cx}, {"cy", k.cy}, {"depth_scale", depthScale_}, {"fx", k.fx}, {"fy", k.fy},
              {"height", height_}, {"width", width_}};
  files.push_back({"camera.json", textBytes(bopJsonValue(camera))});
  return files;
}

void BopWriter::encode(const ProductFrame& frame, FrameFiles& out) const {
  const FramePasses& f = frame.passes;
  const size_t n = f.pixelCount();
  const uint32_t w = uint32_t(f.width), h = uint32_t(f.height);
  char sceneFolder[64];
  std::snprintf(sceneFolder, sizeof sceneFolder, "%s/%06llu/", split_.c_str(),
                static_cast<unsigned long long>(frame.iteration));
  const std::string folder = sceneFolder;
  const uint64_t imageId = bopImageId(frame.frameInIteration, frame.product, products_);

  // Colour without alpha, depth in depth_scale units (0: nothing, or too far).
  std::vector<uint8_t> rgb(n * 3);
  for (size_t i = 0; i < n; ++i)
    for (int c = 0; c < 3; ++c) rgb[i * 3 + size_t(c)] = f.rgba[i * 4 + size_t(c)];
  out.dataset.push_back({folder + imageName("rgb", imageId), encodePng(rgb, w, h, PngPixels::Rgb8, PngOptions::renderedImage())});
  std::vector<uint16_t> depth(n, 0);
  const double unitsPerMetre = 1000.0 / depthScale_;
  for (size_t i = 0; i < n; ++i) {
    const double d = double(f.distanceToImagePlane[i]) * unitsPerMetre;
    if (std::isfinite(d) && d > 0 && d < 65535.5) depth[i] = uint16_t(std::lround(d));
  }
  out.dataset.push_back({folder + imageName("depth", imageId),
                         encodePng({reinterpret_cast<const uint8_t*>(depth.data()), n * 2}, w, h, PngPixels::Gray16,
                                   PngOptions::renderedImage())});

  // The camera, OpenCV axes, millimetres.
  const double mm = frame.metersPerUnit * 1000.0;
  const Matrix3d worldToCamera = kCvFromUsdCamera * frame.camera.worldFromCamera.block<3, 3>(0, 0).transpose();
  const Vec3d eye = frame.camera.worldFromCamera.block<3, 1>(0, 3);
  const Intrinsics k = intrinsicsOf(frame.camera, f.width, f.height);
  Json camera{{"cam_K", Json::array({k.fx, 0.0, k.cx, 0.0, k.fy, k.cy, 0.0, 0.0, 1.0})},
              {"cam_R_w2c", rowWise(worldToCamera)},
              {"cam_t_w2c", vec(-mm * (worldToCamera * eye))},
              {"depth_scale", depthScale_}};

  Json gt = Json::array(), gtInfo = Json::array();
  const auto& entities = frame.scene->semantics.entities;
  const FrameAnnotations& a = frame.annotations;
  std::vector<uint8_t> mask(n), visible(n);
  for (size_t e = 0; e < entities.size(); ++e) {
    auto label = entities[e].labels.find(taxonomy_);
    if (label == entities[e].labels.end()) continue;
    const BopObject* object = nullptr;
    for (const BopObject& o : objects_)
      if (o.label == label->second) object = &o;
    if (!object || e >= frame.coverage.size() || frame.coverage[e].pixels == 0) continue;  // not an object, or out of view
    const ScaledPose pose = splitScale(entities[e].worldFromRoot);
    if (!pose.scale.isApprox(object->scale, 1e-4))
      throw RunError("BopWriter: " + entities[e].primPath + " is scaled differently from " + object->modelPrim +
                     ", whose geometry is obj_id " + std::to_string(object->id) +
                     "'s model; BOP poses are rigid, so every instance of an object needs one scale");
    const size_t gtId = gt.size();
    gt.push_back({{"cam_R_m2c", rowWise(worldToCamera * pose.rotation)},
                  {"cam_t_m2c", vec(mm * (worldToCamera * (pose.translation - eye)))},
                  {"obj_id", object->id}});
    // Full silhouette (the entity drawn alone) and its visible part.
    const MaskCoverage& all = frame.coverage[e];
    uint64_t valid = 0, visibleCount = 0;
    int vx0 = f.width, vy0 = f.height, vx1 = -1, vy1 = -1;
    // Both masks lie inside the silhouette's bounds (what is visible is
    // part of it): only those pixels are looked at.
    std::fill(mask.begin(), mask.end(), 0);
    std::fill(visible.begin(), visible.end(), 0);
    for (int y = all.yMin; y <= all.yMax; ++y)
      for (int x = all.xMin; x <= all.xMax; ++x) {
        const size_t i = size_t(y) * w + size_t(x);
        const bool in = frame.masks.covers(e, x, y);
        mask[i] = in ? 255 : 0;
        valid += in && depth[i] > 0;
        const bool seen = a.instanceIds[i] == entities[e].instanceId;
        visible[i] = seen ? 255 : 0;
        if (seen) {
          ++visibleCount;
          vx0 = std::min(vx0, x), vy0 = std::min(vy0, y), vx1 = std::max(vx1, x), vy1 = std::max(vy1, y);
        }
      }
    out.dataset.push_back({folder + maskName("mask", imageId, gtId), encodePng(mask, w, h, PngPixels::Gray8, PngOptions::labelMap())});
    out.dataset.push_back(
        {folder + maskName("mask_visib", imageId, gtId), encodePng(visible, w, h, PngPixels::Gray8, PngOptions::labelMap())});
    const Json none = Json::array({-1, -1, -1, -1});
    gtInfo.push_back({{"bbox_obj", visibleCount ? bopBox(all.xMin, all.yMin, all.xMax, all.yMax) : none},
                      {"bbox_visib", visibleCount ? bopBox(vx0, vy0, vx1, vy1) : none},
                      {"px_count_all", all.pixels},
                      {"px_count_valid", valid},
                      {"px_count_visib", visibleCount},
                      {"visib_fract", double(visibleCount) / double(all.pixels)}});
  }
  Json fragment{{"scene_id", frame.iteration}, {"im_id", imageId}, {"camera", camera}, {"gt", gt}, {"gt_info", gtInfo}};
  out.parts.push_back({bopFragmentPath(frame.frame, frame.product), textBytes(bopJsonValue(fragment))});
}

uint64_t assembleBopScenes(const std::string& dir, const std::string& split, uint64_t iterations,
                           uint64_t framesPerIteration, size_t products) {
  namespace fs = std::filesystem;
  uint64_t written = 0;
  for (uint64_t scene = 0; scene < iterations; ++scene) {
    std::vector<std::pair<uint64_t, Json>> cameras, gts, infos;
    for (uint64_t frame = 0; frame < framesPerIteration; ++frame)
      for (size_t product = 0; product < products; ++product) {
        const std::string file = (fs::path(dir) / bopFragmentPath(scene * framesPerIteration + frame, product)).string();
        std::ifstream in(file, std::ios::binary);
        std::stringstream text;
        text << in.rdbuf();
        Json fragment = Json::parse(text.str(), nullptr, false);
        if (!in || fragment.is_discarded() || !fragment.is_object() || !fragment.contains("gt_info"))
          throw RunError("BOP: the fragment " + file + " is missing or corrupt; rerun with --resume to redo its frame");
        const uint64_t imageId = fragment["im_id"].get<uint64_t>();
        cameras.emplace_back(imageId, fragment["camera"]);
        gts.emplace_back(imageId, fragment["gt"]);
        infos.emplace_back(imageId, fragment["gt_info"]);
      }
    char folder[64];
    std::snprintf(folder, sizeof folder, "%06llu", static_cast<unsigned long long>(scene));
    const fs::path sceneDir = fs::path(dir) / split / folder;
    writeFileAtomic((sceneDir / "scene_camera.json").string(), bopJsonFile(cameras));
    writeFileAtomic((sceneDir / "scene_gt.json").string(), bopJsonFile(gts));
    writeFileAtomic((sceneDir / "scene_gt_info.json").string(), bopJsonFile(infos));
    written += 3;
  }
  return written;
}

}  // namespace sdg
