// Render benchmark: frames per second at 512 x 512 with every pass read
// back, for a warehouse-like scene (4 pallets, 60 boxes, a target, 3 lights)
// and for 10 / 100 / 1,000 / 10,000 objects sharing one mesh, or for a scene
// file given as the argument (its first camera). Prints one
// JSON object per figure (median, min and max of 5 runs). llvmpipe's thread
// count comes from LP_NUM_THREADS, so the script runs this once per setting.
// SDG_BACKEND=egl picks the EGL back end, SDG_BENCH_FRAMES the frames per run
// of a scene file, SDG_BENCH_ONLY=TEXT only the figures whose name has TEXT.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "assets/asset_resolver.h"
#include "core/diagnostics.h"
#include "render/raster/renderer.h"
#include "run/scene_setup.h"
#include "scene_io/usd_mesh_asset.h"
#include "writers/png_encoder.h"

using namespace sdg;

namespace {

XformOp translate(const Vec3d& t) {
  XformOp op;
  op.kind = XformOpKind::Translate;
  op.value = Value::makeDouble3(t);
  return op;
}

void addCamera(Stage& stage, const Vec3d& position, double tiltDegrees) {
  Prim& cam = stage.definePrim("/Camera", PrimType::Camera);
  cam.setAttribute("focalLength", Value::makeFloat(18.0f));
  cam.setAttribute("clippingRange", Value::makeFloat2(0.1f, 500.0f));
  cam.xformOps().push_back(translate(position));
  XformOp rot;
  rot.kind = XformOpKind::RotateX;
  rot.value = Value::makeDouble(tiltDegrees);
  cam.xformOps().push_back(rot);
}

void addLights(Stage& stage) {
  Prim& sun = stage.definePrim("/Sun", PrimType::DistantLight);
  sun.setAttribute("inputs:intensity", Value::makeFloat(3000.0f));
  for (int i = 0; i < 2; ++i) {
    Prim& lamp = stage.definePrim("/Lamp" + std::to_string(i), PrimType::SphereLight);
    lamp.setAttribute("inputs:intensity", Value::makeFloat(60000.0f));
    lamp.xformOps().push_back(translate({-2.0 + 4.0 * i, 0, 4}));
  }
}

Stage warehouseLike() {
  Stage stage;
  stage.definePrim("/Floor", PrimType::Plane).setAttribute("width", Value::makeDouble(30.0));
  for (int p = 0; p < 4; ++p) {
    Prim& pallet = stage.definePrim("/Pallet" + std::to_string(p), PrimType::Cube);
    pallet.xformOps().push_back(translate({-3.0 + 2.0 * p, 6, 0.1}));
    XformOp s;
    s.kind = XformOpKind::Scale;
    s.value = Value::makeDouble3({0.6, 0.5, 0.1});
    pallet.xformOps().push_back(s);
    for (int b = 0; b < 15; ++b) {
      Prim& box = stage.definePrim("/Box" + std::to_string(p) + "_" + std::to_string(b), PrimType::Cube);
      box.setAttribute("size", Value::makeDouble(0.3));
      box.xformOps().push_back(translate({-3.2 + 2.0 * p + 0.3 * (b % 3), 5.8 + 0.3 * ((b / 3) % 2), 0.35 + 0.3 * (b / 6)}));
    }
  }
  stage.definePrim("/Target", PrimType::Cylinder).xformOps().push_back(translate({0, 4, 1}));
  addLights(stage);
  addCamera(stage, {0, -2, 2.5}, 75);
  return stage;
}

Stage sharedMeshGrid(int count) {
  Stage stage;
  int side = int(std::ceil(std::sqrt(double(count))));
  double spacing = 20.0 / side;
  for (int i = 0; i < count; ++i) {
    Prim& box = stage.definePrim("/Box" + std::to_string(i), PrimType::Cube);
    box.setAttribute("size", Value::makeDouble(spacing * 0.6));
    box.xformOps().push_back(translate({-10 + spacing * (i % side), -10 + spacing * (i / side), 0}));
  }
  addLights(stage);
  addCamera(stage, {0, 0, 25}, 0);
  return stage;
}

// Median, min and max over runs of the per-frame time (ms). `pipelined`:
// as a dataset run draws, colour only, each frame's read-back collected
// while the next one draws; otherwise every pass read back synchronously.
void measure(const std::string& name, const Stage& stage, Renderer& renderer, int frames, bool pipelined = false) {
  if (const char* only = std::getenv("SDG_BENCH_ONLY"); only && name.find(only) == std::string::npos) return;
  RenderList list = buildRenderList(stage);
  FramePasses frame;
  renderer.render(list, 0, frame);  // upload meshes, size buffers
  auto draw = [&](int f) {
    if (!pipelined) return renderer.render(list, 0, frame);
    renderer.queue(list, 0, PassSelection::colourOnly(), f & 1);
    if (f > 0) renderer.collect((f - 1) & 1, frame);
  };
  std::vector<double> runs;
  for (int run = 0; run < 5; ++run) {
    auto start = std::chrono::steady_clock::now();
    for (int f = 0; f < frames; ++f) draw(f);
    if (pipelined) renderer.collect((frames - 1) & 1, frame);
    double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count() / frames;
    runs.push_back(ms);
  }
  std::sort(runs.begin(), runs.end());
  const char* threads = std::getenv("LP_NUM_THREADS");
  std::printf("{\"name\": \"%s%s, LP_NUM_THREADS=%s\", \"unit\": \"ms/frame\", \"median\": %.3f, \"min\": %.3f, "
              "\"max\": %.3f, \"fps\": %.1f}\n",
              name.c_str(), pipelined ? " (pipelined, colour read back)" : "", threads ? threads : "default", runs[2],
              runs.front(), runs.back(), 1000.0 / runs[2]);
  std::fflush(stdout);
}

int measureAll(int argc, char** argv) {
  const char* backend = std::getenv("SDG_BACKEND");
  auto context = createGlContext(backend ? backend : "osmesa", -1);
  std::fprintf(stderr, "bench_render: %s on %s (%s)\n", context->backend().c_str(), context->device().c_str(),
               context->rendererName().c_str());
  AssetResolver assets;
  // 512 x 512, one sample, all passes read back: the render table's defaults.
  RenderSettings settings = defaultRenderSettings();
  if (argc > 1) {
    // A scene file (e.g. one written by `run --save-stage`): its first camera,
    // its stage as written (behaviors and events do not run here).
    registerUsdMeshAssets();  // `asset: x.usd` meshes
    LoadedScene loaded = loadSceneForRun(SceneRequest{.scenePath = argv[1]});
    Renderer renderer(*context, loaded.assets, settings);
    const std::string name = "render 512x512: " + std::filesystem::path(argv[1]).filename().string();
    // A GPU needs more frames per run than llvmpipe for a steady figure.
    const char* count = std::getenv("SDG_BENCH_FRAMES");
    const int frames = count ? std::max(2, std::atoi(count)) : 10;
    measure(name + " all passes", loaded.scene.stage, renderer, frames);
    measure(name, loaded.scene.stage, renderer, frames, true);
    return 0;
  }
  Renderer renderer(*context, assets, settings);
  measure("render 512x512 all passes: 4 pallets + 60 boxes + target + 3 lights", warehouseLike(), renderer, 10);
  {
    // PNG encode of a rendered 512 x 512 RGBA frame on one thread.
    FramePasses frame;
    RenderList list = buildRenderList(warehouseLike());
    renderer.render(list, 0, frame);
    std::vector<double> runs;
    size_t bytes = 0;
    for (int run = 0; run < 5; ++run) {
      auto start = std::chrono::steady_clock::now();
      for (int i = 0; i < 10; ++i)
        bytes = encodePng(frame.rgba, uint32_t(frame.width), uint32_t(frame.height), PngPixels::Rgba8,
                          PngOptions::renderedImage()).size();
      runs.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count() / 10);
    }
    std::sort(runs.begin(), runs.end());
    std::printf("{\"name\": \"PNG encode 512x512 RGBA (zlib 1, SUB, run-length), one thread, %zu bytes\", \"unit\": "
                "\"ms/frame\", \"median\": %.3f, \"min\": %.3f, \"max\": %.3f, \"fps\": %.1f}\n",
                bytes, runs[2], runs.front(), runs.back(), 1000.0 / runs[2]);
  }
  for (int count : {10, 100, 1000, 10000})
    measure("render 512x512 all passes: " + std::to_string(count) + " objects sharing a mesh", sharedMeshGrid(count),
            renderer, count >= 1000 ? 3 : 10);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return measureAll(argc, argv);
  } catch (const SceneError& e) {
    std::fprintf(stderr, "bench_render: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_render: %s\n", e.what());
    return 1;
  }
}
