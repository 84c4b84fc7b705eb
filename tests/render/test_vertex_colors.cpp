// Per-vertex colour (USD's non-constant displayColor and displayOpacity) as
// the rasterizer, the CPU path tracer and the GPU path tracer draw it, on
// tests/data/usd/display_colors.usda: rows of two quads seen from above,
// left red and right green through uniform, vertex (a gradient over shared
// points) and indexed faceVarying colours, and a row whose right quad has
// opacity 0 (a cut-out). Each quad's centre is checked, in every renderer.
#include <catch2/catch.hpp>

#include <memory>

#include "render/camera_math.h"
#include "render/pathtrace/gpu/gl_compute.h"
#include "render/pathtrace/gpu/gpu_path_tracer.h"
#include "render/pathtrace/gpu/gpu_scene.h"
#include "render/pathtrace/path_tracer.h"
#include "render/render_fixtures.h"
#include "scene_io/scene_fixtures.h"
#include "scene_io/usd_import.h"

using namespace sdg;

namespace {

constexpr int kSize = 96;

struct Loaded {
  Scene scene;
  RenderList list;
};

const Loaded& displayColors() {
  static const Loaded loaded = [] {
    Loaded l;
    UsdImportReport report;
    l.scene = importUsdScene(std::string(SDG_SOURCE_DIR) + "/tests/data/usd/display_colors.usda", test::testCatalog(),
                             UsdImportOptions{}, report);
    l.list = buildRenderList(l.scene.stage);
    return l;
  }();
  return loaded;
}

const AssetResolver& assets() {
  static const AssetResolver resolver({SDG_SOURCE_DIR "/tests/data"});
  return resolver;
}

uint32_t instanceOf(const std::string& path) {
  for (const RenderItem& item : displayColors().list.items)
    if (item.primPath == path) return item.instanceId;
  FAIL("no render item " << path);
  return 0;
}

// A renderer's frame, reduced to what the checks read: a colour (any
// monotonic encoding of radiance) and the instance id per pixel.
struct Frame {
  std::vector<Vec3f> color;
  std::vector<uint32_t> instance;
};

Frame fromPathTraced(const PathTracedFrame& f) {
  Frame out;
  for (size_t p = 0; p < f.instance.size(); ++p)
    out.color.emplace_back(f.radiance[3 * p], f.radiance[3 * p + 1], f.radiance[3 * p + 2]);
  out.instance = f.instance;
  return out;
}

// The pixel where the camera sees the world point (x, y, 0).
size_t pixelAt(double x, double y) {
  const Vec3d p = projectToPixel(displayColors().list.cameras.at(0), kSize, kSize, Vec3d(x, y, 0));
  const int px = int(p.x()), py = int(p.y());
  REQUIRE(px >= 0);
  REQUIRE(py >= 0);
  REQUIRE(px < kSize);
  REQUIRE(py < kSize);
  return size_t(py) * kSize + size_t(px);
}

// Row centres (y) and the two quads' centres (x = -1 left, +1 right).
struct Row {
  const char* prim;
  double y;
  float share;  // the dominant channel's least share of red + green at a quad's centre
};

void checkFrame(const Frame& f) {
  // Uniform and indexed faceVarying rows are pure red | green; the vertex
  // row's gradient is 3:1 at the quads' centres (0.75 red, 0.25 green on
  // the left), less after the rasterizer's tone curve. The quads are refined
  // (no subdivisionScheme: catmullClark at render.subdivision_level 2), so the
  // colours pass through OpenSubdiv's face-varying refinement too.
  const Row rows[] = {{"/World/Uniform", 1.9, 0.85f}, {"/World/Vertex", 0.7, 0.58f}, {"/World/Indexed", -0.5, 0.85f}};
  for (const Row& row : rows) {
    CAPTURE(row.prim);
    const size_t left = pixelAt(-1, row.y), right = pixelAt(1, row.y);
    CHECK(f.instance[left] == instanceOf(row.prim));
    CHECK(f.instance[right] == instanceOf(row.prim));
    const Vec3f l = f.color[left], r = f.color[right];
    CAPTURE(l.transpose(), r.transpose());
    CHECK(l.x() > 0.01f);  // lit (the rasterizer's dome-only frame is dark: about 0.02-0.03)
    CHECK(r.y() > 0.01f);
    CHECK(l.x() / (l.x() + l.y()) > row.share);
    CHECK(r.y() / (r.x() + r.y()) > row.share);
    CHECK(l.z() < 0.5f * l.x());
    CHECK(r.z() < 0.5f * r.y());
  }
  // The cut-out row: the left quad is there (grey), the right one clear.
  const size_t left = pixelAt(-1, -1.7), right = pixelAt(1, -1.7);
  CHECK(f.instance[left] == instanceOf("/World/Cut"));
  CHECK(f.instance[right] == 0);
  const Vec3f l = f.color[left];
  CHECK(std::abs(l.x() - l.y()) < 0.1f * l.x());
  CHECK(std::abs(l.x() - l.z()) < 0.1f * l.x());
}

PathTraceSettings tracerSettings() {
  PathTraceSettings s;
  s.samples = 16;
  s.maxBounces = 2;
  return s;
}

}  // namespace

TEST_CASE("vertex colours: the rasterizer draws uniform, vertex and faceVarying colours and cuts out opacity",
          "[render][vertex_colors]") {
  const Loaded& loaded = displayColors();
  RenderSettings settings;
  settings.width = settings.height = kSize;
  Renderer renderer(test::sharedContext(), assets(), settings);
  FramePasses frame;
  renderer.render(loaded.list, 0, frame);
  Frame f;
  for (size_t p = 0; p < frame.instanceIds.size(); ++p)
    f.color.emplace_back(float(frame.rgba[4 * p]) / 255.0f, float(frame.rgba[4 * p + 1]) / 255.0f,
                         float(frame.rgba[4 * p + 2]) / 255.0f);
  f.instance = frame.instanceIds;
  checkFrame(f);
}

TEST_CASE("vertex colours: the CPU path tracer draws them as the rasterizer does", "[render][pathtrace][vertex_colors]") {
  PathTracer tracer(assets(), tracerSettings());
  PathTracedFrame frame;
  tracer.render(displayColors().list, 0, kSize, kSize, 1, frame);
  checkFrame(fromPathTraced(frame));
}

TEST_CASE("vertex colours: the GPU path tracer draws them as the CPU tracer does", "[render][pathtrace][gpu][vertex_colors]") {
  std::unique_ptr<GpuPathTracer> tracer;
  try {
    tracer = std::make_unique<GpuPathTracer>(assets(), tracerSettings());
  } catch (const GpuUnavailable& e) {
    WARN("skipped: " << e.what());
    return;
  }
  PathTracedFrame frame;
  tracer->render(displayColors().list, 0, kSize, kSize, 1, frame);
  checkFrame(fromPathTraced(frame));
  CHECK((tracer->stageFeatures() & kGpuVertexColors) != 0);
}
