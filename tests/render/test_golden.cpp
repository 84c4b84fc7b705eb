// Golden images, compared with two named tolerances. On failure the actual
// and the diff images are written next to the test binary and the worst
// pixels are printed. Regenerate only on purpose: SDG_UPDATE_GOLDEN=1.
#include "render_fixtures.h"

#include <cstdlib>
#include <filesystem>
#include <sstream>

#include "assets/image.h"
#include "core/file_io.h"
#include "run/scene_setup.h"
#include "writers/png_encoder.h"

using namespace sdg;

namespace {
// Largest per-channel difference allowed anywhere: llvmpipe releases differ
// in edge coverage and rounding, which moves single silhouette pixels.
constexpr int kMaxChannelDelta = 48;
// Mean absolute difference over all channels: a real change of shading,
// lighting or geometry moves this well above 1.5 levels.
constexpr double kMeanChannelDelta = 1.5;
// Diagnosis aid: SDG_GOLDEN_TOLERANCE_SCALE=2 doubles both.
double toleranceScale() {
  const char* s = std::getenv("SDG_GOLDEN_TOLERANCE_SCALE");
  return s ? std::atof(s) : 1.0;
}

void compareWithGolden(const std::string& scene, const std::string& golden) {
  LoadedScene loaded = loadSceneForRun(SceneRequest{.scenePath = scene});
  RenderList list = buildRenderList(loaded.scene.stage);
  RenderSettings settings = defaultRenderSettings();
  Vec2i size = loaded.scene.render.get("resolution").get<Vec2i>();
  settings.width = size.x();
  settings.height = size.y();
  settings.subframes = int(loaded.scene.render.getUInt("subframes"));
  Renderer renderer(test::sharedContext(), loaded.assets, settings);
  FramePasses frame;
  renderer.render(list, 0, frame);
  std::vector<uint8_t> png = encodePng(frame.rgba, uint32_t(frame.width), uint32_t(frame.height), PngPixels::Rgba8);
  if (std::getenv("SDG_UPDATE_GOLDEN")) {
    writeFileAtomic(golden, png);
    WARN("golden image updated: " << golden);
    return;
  }
  ImageRgba8 expected = loadImageRgba8(golden, TextureData::Color);
  REQUIRE(expected.width == uint32_t(frame.width));
  REQUIRE(expected.height == uint32_t(frame.height));
  int worst = 0;
  size_t worstAt = 0;
  double sum = 0;
  std::vector<uint8_t> diff(frame.rgba.size());
  for (size_t i = 0; i < frame.rgba.size(); ++i) {
    int d = std::abs(int(frame.rgba[i]) - int(expected.pixels[i]));
    diff[i] = (i % 4 == 3) ? 255 : uint8_t(std::min(255, d * 8));
    sum += d;
    if (d > worst) {
      worst = d;
      worstAt = i / 4;
    }
  }
  double mean = sum / double(frame.rgba.size());
  bool ok = worst <= kMaxChannelDelta * toleranceScale() && mean <= kMeanChannelDelta * toleranceScale();
  // Failure artifacts go under the build folder, never the source tree or
  // whatever folder the test binary happened to be started in.
  const std::filesystem::path failures = std::filesystem::path(SDG_BINARY_DIR) / "golden_failures";
  const std::string stem = (failures / std::filesystem::path(golden).stem()).string();
  if (!ok) {
    std::filesystem::create_directories(failures);
    writeFileAtomic(stem + ".actual.png", png);
    writeFileAtomic(stem + ".diff.png", encodePng(diff, uint32_t(frame.width), uint32_t(frame.height), PngPixels::Rgba8));
  }
  INFO("max delta " << worst << " at pixel (" << worstAt % size_t(frame.width) << ", " << worstAt / size_t(frame.width)
                    << "), mean delta " << mean << "; actual and diff written to " << stem << ".actual.png and "
                    << stem << ".diff.png");
  CHECK(ok);
}
}  // namespace

TEST_CASE("golden: shapes, textures, a mesh file and four kinds of light", "[render][golden]") {
  compareWithGolden(SDG_SOURCE_DIR "/tests/data/golden/shapes.yaml", SDG_SOURCE_DIR "/tests/data/golden/shapes.png");
}
