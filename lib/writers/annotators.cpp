#include "writers/annotators.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>

#include "core/text.h"
#include "render/camera_math.h"

namespace sdg {

void annotate(const AnnotatorInputs& in, FrameAnnotations& out) {
  const FramePasses& f = in.frame;
  const size_t n = f.pixelCount();
  const auto& entities = in.semantics.entities;
  out.semanticIds.resize(n);
  out.instanceIds.resize(n);
  out.visiblePixels.assign(entities.size(), 0);
  std::vector<std::array<int, 4>> bounds(entities.size(), {f.width, f.height, -1, -1});
  const auto& ofRender = in.semantics.entityOfRenderId;
  // A row is long runs of one render id: each run is looked up once.
  for (int y = 0; y < f.height; ++y) {
    const size_t rowStart = size_t(y) * size_t(f.width);
    const uint32_t* row = f.instanceIds.data() + rowStart;
    for (int x = 0; x < f.width;) {
      const uint32_t renderId = row[x];
      int end = x + 1;
      while (end < f.width && row[end] == renderId) ++end;
      const uint32_t e = renderId == 0 ? 0 : renderId < ofRender.size() ? ofRender[renderId] : 0;
      uint32_t semanticId = renderId == 0 ? kBackgroundId : kUnlabelledId, instanceId = semanticId;
      if (e != 0) {
        const SemanticEntity& entity = entities[e - 1];
        semanticId = entity.semanticId;
        instanceId = entity.instanceId;
        out.visiblePixels[e - 1] += uint64_t(end - x);
        auto& b = bounds[e - 1];
        b[0] = std::min(b[0], x);
        b[1] = std::min(b[1], y);
        b[2] = std::max(b[2], end - 1);
        b[3] = std::max(b[3], y);
      }
      std::fill(out.semanticIds.begin() + std::ptrdiff_t(rowStart + size_t(x)),
                out.semanticIds.begin() + std::ptrdiff_t(rowStart + size_t(end)), semanticId);
      std::fill(out.instanceIds.begin() + std::ptrdiff_t(rowStart + size_t(x)),
                out.instanceIds.begin() + std::ptrdiff_t(rowStart + size_t(end)), instanceId);
      x = end;
    }
  }
  // Occlusion: the fraction of the entity's unoccluded pixels that are hidden.
  out.occlusion.assign(entities.size(), 0.0f);
  for (size_t e = 0; e < entities.size() && e < in.coverage.size(); ++e)
    if (in.coverage[e].pixels)
      out.occlusion[e] = float(1.0 - double(out.visiblePixels[e]) / double(in.coverage[e].pixels));
  out.tight.clear();
  out.loose.clear();
  for (size_t e = 0; e < entities.size(); ++e) {
    if (out.visiblePixels[e]) {  // fully occluded entities have no tight box
      const auto& b = bounds[e];
      out.tight.push_back({entities[e].semanticId, b[0], b[1], b[2], b[3], out.occlusion[e], e});
    }
    if (e < in.coverage.size() && in.coverage[e].pixels) {
      const EntityCoverage& c = in.coverage[e];
      out.loose.push_back({entities[e].semanticId, c.xMin, c.yMin, c.xMax, c.yMax, out.occlusion[e], e});
    }
  }
  // 3D boxes: local extents in the entity root's frame; entities whose box
  // reaches into the view frustum.
  out.boxes3d.clear();
  const RenderCamera& camera = in.list.cameras[in.camera];
  for (size_t e = 0; e < entities.size(); ++e) {
    const Matrix4d& worldFromRoot = entities[e].worldFromRoot;
    const Matrix4d rootFromWorld = worldFromRoot.inverse();
    Eigen::AlignedBox3d local;
    for (size_t item : entities[e].items) {
      const Eigen::AlignedBox3f& b = in.itemBounds[item];
      for (int c = 0; c < 8; ++c) {
        Vec3d corner = b.corner(static_cast<Eigen::AlignedBox3f::CornerType>(c)).cast<double>();
        Vec3d world = (in.list.items[item].worldFromLocal * corner.homogeneous()).head<3>();
        local.extend((rootFromWorld * world.homogeneous()).head<3>());
      }
    }
    bool inView = false;
    for (int c = 0; c < 8 && !inView; ++c) {
      Vec3d world = (worldFromRoot * local.corner(static_cast<Eigen::AlignedBox3d::CornerType>(c)).homogeneous()).head<3>();
      Vec3d p = projectToPixel(camera, f.width, f.height, world);
      inView = p.z() > 0 && p.x() >= 0 && p.x() <= f.width && p.y() >= 0 && p.y() <= f.height;
    }
    if (!inView && !out.visiblePixels[e]) continue;
    Box3D box;
    box.semanticId = entities[e].semanticId;
    for (int a = 0; a < 3; ++a) {
      box.extentMin[a] = float(local.min()[a]);
      box.extentMax[a] = float(local.max()[a]);
    }
    // Row-vector layout: the transpose of our column-vector matrix.
    for (int r = 0; r < 4; ++r)
      for (int c = 0; c < 4; ++c) box.transform[r * 4 + c] = float(worldFromRoot(c, r));
    box.occlusionRatio = out.occlusion[e];
    box.entity = e;
    out.boxes3d.push_back(box);
  }
}

namespace {
// Camera attributes are 32-bit floats: write their shortest decimal form
// (24.0, 20.955), not the float's exact binary expansion.
double decimal(float f) { return std::strtod(text::formatFloat(f).c_str(), nullptr); }
// The lens holds its float attributes as doubles: their shortest form again.
double decimal(double d) { return decimal(float(d)); }

// A calibrated lens's parameters under the names of its omni:lensdistortion
// attributes (without the prefix), for `cameraLensDistortion`.
nlohmann::ordered_json lensParameters(const LensModel& lens) {
  using Json = nlohmann::ordered_json;
  Json j;
  j["model"] = std::string(lensModelToken(lens.kind));
  auto coefficients = [&](const char* letter, int first, int count, const double* values) {
    for (int i = 0; i < count; ++i) j[letter + std::to_string(first + i)] = decimal(values[i]);
  };
  if (lens.kind == LensModelKind::OpenCvPinhole || lens.kind == LensModelKind::OpenCvFisheye) {
    j["fx"] = decimal(lens.fx), j["fy"] = decimal(lens.fy), j["cx"] = decimal(lens.cx), j["cy"] = decimal(lens.cy);
    j["imageSize"] = Json::array({int(lens.calibratedSize.x()), int(lens.calibratedSize.y())});
    coefficients("k", 1, lens.kind == LensModelKind::OpenCvPinhole ? 6 : 4, lens.k.data());
    if (lens.kind == LensModelKind::OpenCvPinhole) {
      j["p1"] = decimal(lens.p1), j["p2"] = decimal(lens.p2);
      coefficients("s", 1, 4, lens.s.data());
    }
  } else {
    j["nominalWidth"] = decimal(lens.calibratedSize.x()), j["nominalHeight"] = decimal(lens.calibratedSize.y());
    j["opticalCenter"] = Json::array({decimal(lens.cx), decimal(lens.cy)});
    j["maxFov"] = decimal(lens.maxFovDegrees);
    coefficients("k", 0, lens.kind == LensModelKind::FTheta ? 5 : 4, lens.k.data());
  }
  return j;
}
}  // namespace

nlohmann::ordered_json cameraParams(const RenderCamera& camera, int width, int height, double metersPerUnit) {
  using Json = nlohmann::ordered_json;
  // Replicator's projection: reverse-Z with an infinite far plane
  // (NDC z = near / -z_cam), in the row-vector layout.
  Matrix4d p = projectionMatrix(camera, width, height);
  if (!camera.orthographic) {  // orthographic cameras keep the GL projection
    p(2, 2) = 0.0;
    p(2, 3) = camera.nearClip;
    p(3, 2) = -1.0;
    p(3, 3) = 0.0;
  }
  const Matrix4d view = viewMatrix(camera);
  auto flat = [](const Matrix4d& m) {
    Json a = Json::array();
    for (int r = 0; r < 4; ++r)
      for (int c = 0; c < 4; ++c) a.push_back(m(c, r));  // transpose: row-vector layout
    return a;
  };
  const double aspect = double(width) / double(height);
  Json j;
  j["cameraAperture"] = Json::array({decimal(camera.horizontalAperture), decimal(camera.horizontalAperture) / aspect});
  j["cameraApertureOffset"] = Json::array({decimal(camera.horizontalApertureOffset), decimal(camera.verticalApertureOffset)});
  // Isaac's fisheye keys: f-theta and Kannala-Brandt fill the nominal size,
  // optical centre, field of view and polynomial; opencvPinhole the
  // tangential (LensP) and thin-prism (LensS) terms. Every model's full
  // calibration is in cameraLensDistortion (docs/writers.md).
  const LensModel& lens = camera.lens;
  const bool polynomial = lens.kind == LensModelKind::FTheta || lens.kind == LensModelKind::KannalaBrandtK3;
  j["cameraFisheyeLensP"] = lens.kind == LensModelKind::OpenCvPinhole ? Json::array({decimal(lens.p1), decimal(lens.p2)}) : Json::array();
  j["cameraFisheyeLensS"] = lens.kind == LensModelKind::OpenCvPinhole
                                ? Json::array({decimal(lens.s[0]), decimal(lens.s[1]), decimal(lens.s[2]), decimal(lens.s[3])})
                                : Json::array();
  j["cameraFisheyeMaxFOV"] = polynomial ? decimal(lens.maxFovDegrees) : 0.0;
  j["cameraFisheyeNominalHeight"] = polynomial ? int(lens.calibratedSize.y()) : 0;
  j["cameraFisheyeNominalWidth"] = polynomial ? int(lens.calibratedSize.x()) : 0;
  j["cameraFisheyeOpticalCentre"] = polynomial ? Json::array({decimal(lens.cx), decimal(lens.cy)}) : Json::array({0.0, 0.0});
  j["cameraFisheyePolynomial"] =
      polynomial ? Json::array({decimal(lens.k[0]), decimal(lens.k[1]), decimal(lens.k[2]), decimal(lens.k[3]),
                                decimal(lens.kind == LensModelKind::FTheta ? lens.k[4] : 0.0)})
                 : Json::array({0.0, 0.0, 0.0, 0.0, 0.0});
  j["cameraFocalLength"] = decimal(camera.focalLength);
  j["cameraFocusDistance"] = decimal(camera.focusDistance);
  j["cameraFStop"] = decimal(camera.fStop);
  if (lens.calibrated()) j["cameraLensDistortion"] = lensParameters(lens);
  j["cameraModel"] = lens.calibrated() ? std::string(lensModelToken(lens.kind))
                                       : std::string(camera.orthographic ? "orthographic" : "pinhole");
  j["cameraNearFar"] = Json::array({decimal(camera.nearClip), decimal(camera.farClip)});
  j["cameraProjection"] = flat(p);
  j["cameraViewTransform"] = flat(view);
  j["metersPerSceneUnit"] = metersPerUnit;
  j["renderProductResolution"] = Json::array({width, height});
  return j;
}

}  // namespace sdg
