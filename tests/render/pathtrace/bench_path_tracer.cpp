// Not a test: the path tracer's ray rates on bundled scenes, against plain
// Embree ray casting of the same scene (each pixel's centre ray, closest
// hit only). Hidden from the default run; start it with
//   build/release/tests/sdg_unit_tests "[pathtrace-bench]"
// It writes the tone-mapped frames next to the test binary for a look.
#include "pt_test_scenes.h"

#include <chrono>
#include <cstdio>

#include "writers/png_encoder.h"

using namespace sdg;
using namespace sdg::pttest;

TEST_CASE("path tracer benchmark: rays per second per core on bundled scenes", "[.][pathtrace-bench]") {
  struct Bench {
    const char* name;
    const char* file;
  };
  const Bench benches[] = {{"cornell_box", SDG_SOURCE_DIR "/scenes/examples/cornell_box.yaml"},
                           {"warehouse", SDG_SOURCE_DIR "/scenes/warehouse.yaml"}};
  const int width = 320, height = 240;
  for (const Bench& b : benches) {
    Scene scene = loadScene(b.file, builtinRegistry().catalog());
    const RenderList list = buildRenderList(scene.stage);
    const AssetResolver assets = makeSceneResolver(scene.sourceDir, scene.assetRoots, {});
    PathTraceSettings settings;
    settings.samples = 16;
    settings.maxBounces = 8;
    settings.threads = 1;
    PathTracer tracer(assets, settings);
    PathTracedFrame frame;
    tracer.render(list, 0, width, height, 1, frame);  // warm: meshes, textures, BVHs
    tracer.render(list, 0, width, height, 1, frame);
    const PathTraceStats s = tracer.stats();
    const double plain = tracer.primaryRayRate(list, 0, width, height, 8);
    std::printf("%s (%zu items, %zu lights), %dx%d, %d spp, 1 thread: %.2f s, %.3g rays (%.2f per sample), "
                "%.3g rays/s; set-up %.3f s; plain Embree primary rays %.3g rays/s\n",
                b.name, list.items.size(), list.lights.size(), width, height, settings.samples, s.seconds, double(s.rays),
                double(s.rays) / double(s.samples), double(s.rays) / s.seconds, s.setupSeconds, plain);
    std::vector<uint8_t> rgba(size_t(width) * height * 4);
    toneMap(frame, 0.002f, rgba.data());
    const std::vector<uint8_t> png = encodePng(rgba, uint32_t(width), uint32_t(height), PngPixels::Rgba8);
    std::ofstream(scratchFolder("bench") / (std::string(b.name) + ".png"), std::ios::binary)
        .write(reinterpret_cast<const char*>(png.data()), std::streamsize(png.size()));
  }
}
