// The GPU path tracer (render/pathtrace/gpu) against the CPU tracer: on
// Mesa's llvmpipe in CI, a real GPU elsewhere. Both trace the same sample
// streams, so with one seed their images agree far closer than two seeds
// of either tracer do; block means agree within a fraction of their noise;
// reruns are byte-identical whatever the samples per dispatch.
#include "pt_test_scenes.h"

#include <cstring>
#include <fstream>
#include <memory>

#include "render/pathtrace/gpu/gl_compute.h"
#include "render/pathtrace/gpu/gpu_path_tracer.h"
#include "render/pathtrace/gpu/gpu_scene.h"
#include "render/test_images.h"

using namespace sdg;
using namespace sdg::pttest;
namespace fs = std::filesystem;

namespace {

// A Cornell-like room: white floor, back and ceiling, red and green walls, a
// white box and a metal ball, an area lamp under the ceiling.
const char* kCornell = R"(version: 1
prims:
  /Looks: {type: Scope}
  /Looks/White: {type: Material, inputs:diffuse_color_constant: [0.73, 0.73, 0.73], inputs:reflection_roughness_constant: 1.0}
  /Looks/Red: {type: Material, inputs:diffuse_color_constant: [0.65, 0.05, 0.05], inputs:reflection_roughness_constant: 1.0}
  /Looks/Green: {type: Material, inputs:diffuse_color_constant: [0.12, 0.45, 0.15], inputs:reflection_roughness_constant: 1.0}
  /Looks/Metal: {type: Material, inputs:diffuse_color_constant: [0.9, 0.8, 0.6], inputs:reflection_roughness_constant: 0.3, inputs:metallic_constant: 1}
  /Floor: {type: Plane, width: 2, length: 2, material: /Looks/White}
  /Ceiling: {type: Plane, width: 2, length: 2, translate: [0, 0, 2], material: /Looks/White}
  /Back: {type: Plane, axis: Y, width: 2, length: 2, translate: [0, 1, 1], material: /Looks/White}
  /Left: {type: Plane, axis: X, width: 2, length: 2, translate: [-1, 0, 1], material: /Looks/Red}
  /Right: {type: Plane, axis: X, width: 2, length: 2, translate: [1, 0, 1], material: /Looks/Green}
  /Box: {type: Cube, size: 0.6, translate: [0.35, 0.3, 0.3], rotateZ: 20, material: /Looks/White}
  /Ball: {type: Sphere, radius: 0.3, translate: [-0.4, -0.1, 0.3], material: /Looks/Metal}
  /Lamp: {type: RectLight, inputs:width: 0.5, inputs:height: 0.5, inputs:intensity: 30, translate: [0, 0, 1.98]}
  /Camera: {type: Camera, focalLength: 18, clippingRange: [0.1, 100], translate: [0, -2.6, 1], rotateX: 90}
)";

std::unique_ptr<GpuPathTracer> gpuTracer(const PathTraceSettings& settings) {
  try {
    return std::make_unique<GpuPathTracer>(testAssets(), settings);
  } catch (const GpuUnavailable& e) {
    WARN("skipped: " << e.what());
    return nullptr;
  }
}

PathTracedFrame gpuTrace(GpuPathTracer& tracer, const RenderList& list, int w, int h, uint64_t seed) {
  PathTracedFrame f;
  tracer.render(list, 0, w, h, seed, f);
  return f;
}

// The share of pixels whose label ray hit the same instance in both frames.
double sameInstanceShare(const PathTracedFrame& a, const PathTracedFrame& b) {
  size_t same = 0;
  for (size_t p = 0; p < a.instance.size(); ++p) same += a.instance[p] == b.instance[p];
  return double(same) / double(a.instance.size());
}

double rms(const PathTracedFrame& a, const PathTracedFrame& b) {
  double sum = 0;
  for (size_t i = 0; i < a.radiance.size(); ++i) sum += double(a.radiance[i] - b.radiance[i]) * (a.radiance[i] - b.radiance[i]);
  return std::sqrt(sum / double(a.radiance.size()));
}

double meanOf(const PathTracedFrame& f) {
  double sum = 0;
  for (float v : f.radiance) sum += v;
  return sum / double(f.radiance.size());
}

// The largest difference of 8 x 8 block means (all channels), over the image's mean.
double worstBlockBias(const PathTracedFrame& a, const PathTracedFrame& b) {
  double worst = 0;
  for (int by = 0; by + 8 <= a.height; by += 8)
    for (int bx = 0; bx + 8 <= a.width; bx += 8) {
      double sa = 0, sb = 0;
      for (int y = by; y < by + 8; ++y)
        for (int x = bx; x < bx + 8; ++x)
          for (int c = 0; c < 3; ++c) {
            sa += a.radiance[3 * size_t(y * a.width + x) + size_t(c)];
            sb += b.radiance[3 * size_t(y * a.width + x) + size_t(c)];
          }
      worst = std::max(worst, std::abs(sa - sb) / (8 * 8 * 3));
    }
  return worst / meanOf(b);
}

// Compares the tracers at one size and sample count (nothing where the GPU tracer cannot run).
void checkAgreement(const RenderList& list, int w, int h, int samples) {
  PathTraceSettings settings;
  settings.samples = samples;
  settings.maxBounces = 8;
  auto gpu = gpuTracer(settings);
  if (!gpu) return;
  INFO("device: " << gpu->device());
  const PathTracedFrame cpu1 = trace(list, w, h, settings, 1), cpu2 = trace(list, w, h, settings, 2);
  const PathTracedFrame gpu1 = gpuTrace(*gpu, list, w, h, 1), gpu2 = gpuTrace(*gpu, list, w, h, 2);
  // Labels: the same centre rays and surfaces.
  CHECK(sameInstanceShare(gpu1, cpu1) >= 0.98);
  const double noise = rms(cpu1, cpu2);
  const double sameSeed = rms(gpu1, cpu1), otherSeed = rms(gpu2, cpu1);
  INFO("rms: cpu seed 1 vs 2 " << noise << ", gpu vs cpu same seed " << sameSeed << ", other seed " << otherSeed);
  INFO("means: cpu " << meanOf(cpu1) << " gpu " << meanOf(gpu1));
  INFO("block bias: same seed " << worstBlockBias(gpu1, cpu1) << ", cpu seeds " << worstBlockBias(cpu2, cpu1));
  REQUIRE(noise > 0);
  // One sample stream: most paths are the same paths; where rounding sends
  // one elsewhere, it is an independent sample of the same pixel.
  CHECK(sameSeed < 0.5 * noise);
  // Independent streams: the pixels differ by the tracers' noise, no more.
  CHECK(otherSeed < 1.15 * noise);
  CHECK(std::abs(meanOf(gpu1) / meanOf(cpu1) - 1) < 0.01);
  CHECK(worstBlockBias(gpu1, cpu1) < 0.5 * worstBlockBias(cpu2, cpu1) + 0.005);
}

}  // namespace

TEST_CASE("gpu path tracer: agrees with the CPU tracer on a Cornell-like box", "[pathtrace][gpu]") {
  checkAgreement(renderListOf(kCornell), 32, 32, 16);
}

TEST_CASE("gpu path tracer: agrees with the CPU tracer with textures, a normal map, a cut-out and a dome map",
          "[pathtrace][gpu]") {
  const fs::path dir = scratchFolder("gpu_textures");
  test::writeSectorSky(dir / "sky.hdr");
  test::writePng(dir / "checker.png", 8, 8, [](int x, int y) {
    const uint8_t v = ((x / 2 + y / 2) % 2) ? 220 : 40;
    return std::array<uint8_t, 4>{v, uint8_t(255 - v), 90, 255};
  });
  test::writePng(dir / "bumps.png", 8, 8, [](int x, int y) {
    return std::array<uint8_t, 4>{uint8_t(128 + 60 * ((x % 4) - 1.5) / 1.5), uint8_t(128 + 40 * ((y % 4) - 1.5) / 1.5), 230, 255};
  });
  test::writePng(dir / "holes.png", 8, 8, [](int x, int y) {
    const uint8_t v = (x + y) % 4 == 0 ? 0 : 255;
    return std::array<uint8_t, 4>{v, v, v, 255};
  });
  const std::string yaml = "version: 1\nprims:\n  /Looks: {type: Scope}\n"
                           "  /Looks/Floor: {type: Material, inputs:diffuse_texture: " + (dir / "checker.png").string() +
                           ", inputs:normalmap_texture: " + (dir / "bumps.png").string() +
                           ", inputs:reflection_roughness_constant: 0.6, inputs:texture_scale: [3, 3]}\n"
                           "  /Looks/Card: {type: Material, inputs:diffuse_color_constant: [0.2, 0.3, 0.8], "
                           "inputs:enable_opacity: true, inputs:enable_opacity_texture: true, inputs:opacity_threshold: 0.5, "
                           "inputs:opacity_texture: " + (dir / "holes.png").string() + R"(}
  /Looks/Gold: {type: Material, inputs:diffuse_color_constant: [0.9, 0.7, 0.3], inputs:reflection_roughness_constant: 0.25, inputs:metallic_constant: 1}
  /Floor: {type: Plane, width: 6, length: 6, material: /Looks/Floor}
  /Card: {type: Plane, axis: Y, width: 1.5, length: 1.5, translate: [-0.6, 0.3, 0.75], material: /Looks/Card}
  /Ball: {type: Sphere, radius: 0.4, translate: [0.6, 0, 0.4], material: /Looks/Gold}
  /Sky: {type: DomeLight, inputs:intensity: 1, inputs:texture:file: )" + (dir / "sky.hdr").string() + R"(}
  /Sun: {type: DistantLight, inputs:angle: 3, inputs:intensity: 3, rotateXYZ: [35, 15, 0]}
  /Camera: {type: Camera, focalLength: 20, clippingRange: [0.1, 100], translate: [0, -3.5, 1.4], rotateX: 72}
)";
  checkAgreement(renderListOf(yaml), 32, 32, 16);
}

TEST_CASE("gpu path tracer: agrees with the CPU tracer on specular_level, treatAsPoint and the lights' lobe multipliers",
          "[pathtrace][gpu]") {
  std::string yaml = kCornell;
  yaml.replace(yaml.find("inputs:reflection_roughness_constant: 1.0}"), 42,
               "inputs:reflection_roughness_constant: 0.4, inputs:specular_level: 0.9}");
  const std::string lamp = "inputs:intensity: 30,";
  yaml.replace(yaml.find(lamp), lamp.size(), lamp + " inputs:diffuse: 0.4, inputs:specular: 3,");
  yaml += "  /Bulb: {type: SphereLight, inputs:radius: 0.05, inputs:intensity: 200, treatAsPoint: true, "
          "translate: [0.5, -0.5, 1.5]}\n";
  checkAgreement(renderListOf(yaml), 32, 32, 16);
}

// A mesh whose triangles include degenerate ones across the view: three
// points on a line, a repeated vertex, a point triangle. The GPU tests each
// triangle in its own unit-triangle space (gpu_scene.cpp's unitTriangle),
// which a degenerate triangle does not have: it must be met by no ray, and
// leave no sample NaN, as in Embree.
TEST_CASE("gpu path tracer: degenerate triangles are met by no ray, as on the CPU", "[pathtrace][gpu]") {
  const fs::path file = scratchFolder("gpu_degenerate") / "card.obj";
  {
    std::ofstream out(file);
    out << "v -1 0 0\nv 1 0 0\nv 1 0 2\nv -1 0 2\n"          // the card, 1..4
        << "v -1.5 -1 1\nv 0 -1 1\nv 1.5 -1 1\n"               // a line in front of it, 5..7
        << "v 0.2 -1 0.4\nv 0.7 -1 1.6\n"                      // a segment, 8..9
        << "f 1 2 3\nf 1 3 4\nf 5 6 7\nf 8 9 8\nf 6 6 6\n";
  }
  const std::string yaml = "version: 1\nprims:\n"
                           "  /Card: {type: Mesh, asset: " + file.string() + "}\n"
                           "  /Floor: {type: Plane, width: 8, length: 8}\n"
                           "  /Sky: {type: DomeLight, inputs:intensity: 1}\n"
                           "  /Camera: {type: Camera, focalLength: 18, clippingRange: [0.1, 100], "
                           "translate: [0, -4, 1], rotateX: 90}\n";
  checkAgreement(renderListOf(yaml), 32, 32, 16);
  PathTraceSettings settings;
  settings.samples = 4;
  auto gpu = gpuTracer(settings);
  if (!gpu) return;
  const PathTracedFrame frame = gpuTrace(*gpu, renderListOf(yaml), 32, 32, 3);
  CHECK(gpu->stats().droppedSamples == 0);
  // The degenerate triangles cross the middle row in front of the card: the
  // label rays there meet the card (or the floor below it), as on the CPU.
  const PathTracedFrame cpu = trace(renderListOf(yaml), 32, 32, settings, 3);
  CHECK(sameInstanceShare(frame, cpu) == 1.0);
}

TEST_CASE("gpu path tracer: byte-identical reruns, whatever the samples per dispatch", "[pathtrace][gpu]") {
  PathTraceSettings settings;
  settings.samples = 6;
  settings.maxBounces = 6;
  auto gpu = gpuTracer(settings);
  if (!gpu) return;
  const RenderList list = renderListOf(kCornell);
  const PathTracedFrame a = gpuTrace(*gpu, list, 24, 16, 7);
  gpu->setSamplesPerDispatch(1);
  const PathTracedFrame b = gpuTrace(*gpu, list, 24, 16, 7);
  gpu->setSamplesPerDispatch(4);
  const PathTracedFrame c = gpuTrace(*gpu, list, 24, 16, 7);
  for (const PathTracedFrame* other : {&b, &c}) {
    CHECK(std::memcmp(a.radiance.data(), other->radiance.data(), a.radiance.size() * sizeof(float)) == 0);
    CHECK(std::memcmp(a.albedo.data(), other->albedo.data(), a.albedo.size() * sizeof(float)) == 0);
    CHECK(std::memcmp(a.normal.data(), other->normal.data(), a.normal.size() * sizeof(float)) == 0);
    CHECK(std::memcmp(a.depth.data(), other->depth.data(), a.depth.size() * sizeof(float)) == 0);
    CHECK(a.instance == other->instance);
  }
  // A fresh tracer (everything uploaded again) gives the same bytes; another seed does not.
  auto again = gpuTracer(settings);
  REQUIRE(again);
  const PathTracedFrame d = gpuTrace(*again, list, 24, 16, 7);
  CHECK(std::memcmp(a.radiance.data(), d.radiance.data(), a.radiance.size() * sizeof(float)) == 0);
  const PathTracedFrame e = gpuTrace(*again, list, 24, 16, 8);
  CHECK(std::memcmp(a.radiance.data(), e.radiance.data(), a.radiance.size() * sizeof(float)) != 0);
  CHECK(gpu->stats().rays > gpu->stats().cameraRays);
}

TEST_CASE("gpu path tracer: a pixel's every sample counts, however many (llvmpipe cuts long invocations short)",
          "[pathtrace][gpu]") {
  // Few pixels and many samples: the default split would give one dispatch
  // with every sample, whose invocations llvmpipe stops after 65,535 loop
  // iterations (the frame came out a quarter as bright before the tracer
  // capped the samples per dispatch on a software device).
  PathTraceSettings settings;
  settings.samples = 2048;
  settings.maxBounces = 8;
  auto gpu = gpuTracer(settings);
  if (!gpu) return;
  INFO("device: " << gpu->device());
  const RenderList list = renderListOf(kCornell);
  const PathTracedFrame cpu = trace(list, 4, 4, settings, 3), onGpu = gpuTrace(*gpu, list, 4, 4, 3);
  INFO("means: cpu " << meanOf(cpu) << " gpu " << meanOf(onGpu));
  CHECK(std::abs(meanOf(onGpu) / meanOf(cpu) - 1) < 0.01);
}

TEST_CASE("gpu path tracer: a moved instance moves in the image, the meshes stay uploaded", "[pathtrace][gpu]") {
  PathTraceSettings settings;
  settings.samples = 1;
  settings.maxBounces = 1;
  auto gpu = gpuTracer(settings);
  if (!gpu) return;
  RenderList list = renderListOf(kCornell);
  const PathTracedFrame before = gpuTrace(*gpu, list, 32, 32, 1);
  size_t ball = 0;
  for (size_t i = 0; i < list.items.size(); ++i)
    if (list.items[i].primPath == "/Ball") ball = i;
  const uint32_t id = list.items[ball].instanceId;
  list.items[ball].worldFromLocal(0, 3) += 0.8;  // to the right
  const PathTracedFrame after = gpuTrace(*gpu, list, 32, 32, 1);
  auto centreX = [&](const PathTracedFrame& f) {
    double sum = 0, n = 0;
    for (int y = 0; y < f.height; ++y)
      for (int x = 0; x < f.width; ++x)
        if (f.instance[size_t(y * f.width + x)] == id) {
          sum += x;
          n += 1;
        }
    return n > 0 ? sum / n : -1.0;
  };
  CHECK(centreX(before) > 0);
  CHECK(centreX(after) > centreX(before) + 4);
  // The CPU tracer sees the moved ball in the same pixels.
  const PathTracedFrame cpu = trace(list, 32, 32, settings, 1);
  CHECK(sameInstanceShare(after, cpu) >= 0.98);
}

TEST_CASE("gpu path tracer: the denoiser on the GPU matches the CPU denoiser on the same film", "[pathtrace][gpu]") {
  PathTraceSettings settings;
  settings.samples = 4;
  settings.maxBounces = 6;
  auto gpu = gpuTracer(settings);
  if (!gpu) return;
  const RenderList list = renderListOf(kCornell);
  const PathTracedFrame raw = gpuTrace(*gpu, list, 32, 32, 3);
  for (const bool perPixelVariance : {false, true}) {
    INFO((perPixelVariance ? "the samples' own variance" : "the neighbourhood's noise estimate"));
    gpu->setDenoiser(DenoiseSettings{}, perPixelVariance);
    const PathTracedFrame denoised = gpuTrace(*gpu, list, 32, 32, 3);
    CHECK(denoised.instance == raw.instance);
    Denoiser cpu{DenoiseSettings{}};
    PathTracedFrame reference = raw;
    cpu.run({raw.width, raw.height, raw.radiance.data(), raw.albedo.data(), raw.normal.data(), raw.depth.data(),
             raw.instance.data(), perPixelVariance ? raw.variance.data() : nullptr},
            reference.radiance.data());
    // Against the CPU filter: the same image up to float rounding (exp, pow, the variance's sums).
    double worst = 0;
    for (size_t i = 0; i < reference.radiance.size(); ++i)
      worst = std::max(worst, double(std::abs(denoised.radiance[i] - reference.radiance[i])) /
                                  (std::abs(reference.radiance[i]) + 1e-3));
    INFO("largest relative difference " << worst << "; change from the raw film " << rms(denoised, raw));
    CHECK(worst < 1e-3);
    CHECK(rms(denoised, raw) > 0.5 * rms(reference, raw));  // the filter did as much as the CPU's
    const PathTracedFrame again = gpuTrace(*gpu, list, 32, 32, 3);
    CHECK(std::memcmp(again.radiance.data(), denoised.radiance.data(), again.radiance.size() * sizeof(float)) == 0);
  }
}

namespace {

// A run's form of the tracer (queueDisplay/collectDisplay) against the film
// form and the CPU's toneMap(): the tone curve on the device within one code
// value, the radiance the film's, frames queued two deep as a run queues them.
void checkDisplayForm() {
  PathTraceSettings settings;
  settings.samples = 4;
  settings.maxBounces = 4;
  auto gpu = gpuTracer(settings);
  if (!gpu) return;
  const RenderList list = renderListOf(kCornell);
  const int w = 24, h = 16;
  const float exposure = 2.0f;  // the Cornell room's radiance is about 0.1-1
  std::vector<PathTracedFrame> films(3);
  std::vector<std::vector<uint8_t>> expected(3);
  for (uint64_t seed = 0; seed < 3; ++seed) {
    films[seed] = gpuTrace(*gpu, list, w, h, seed + 1);
    expected[seed].resize(size_t(w * h * 4));
    toneMap(films[seed], exposure, expected[seed].data());
  }
  std::vector<uint8_t> rgba;
  std::vector<float> radiance;
  auto compare = [&](size_t seed) {
    REQUIRE(rgba.size() == expected[seed].size());
    int worst = 0;
    for (size_t i = 0; i < rgba.size(); ++i) worst = std::max(worst, std::abs(int(rgba[i]) - int(expected[seed][i])));
    CHECK(worst <= 1);
    REQUIRE(radiance.size() == films[seed].radiance.size());
    float worstRadiance = 0;
    for (size_t i = 0; i < radiance.size(); ++i)
      worstRadiance = std::max(worstRadiance, std::abs(radiance[i] - films[seed].radiance[i]) /
                                                  std::max(1e-3f, std::abs(films[seed].radiance[i])));
    CHECK(worstRadiance < 1e-5f);
  };
  // Queued two deep: frame k+1 is queued before frame k is collected.
  gpu->queueDisplay(list, 0, w, h, 1, exposure, true, 0);
  gpu->queueDisplay(list, 0, w, h, 2, exposure, true, 1);
  gpu->collectDisplay(0, rgba, &radiance);
  compare(0);
  gpu->queueDisplay(list, 0, w, h, 3, exposure, true, 0);
  gpu->collectDisplay(1, rgba, &radiance);
  compare(1);
  gpu->collectDisplay(0, rgba, &radiance);
  compare(2);
  // Without the radiance, and a slot collected twice is a caller's bug.
  gpu->queueDisplay(list, 0, w, h, 1, exposure, false, 1);
  radiance.clear();
  gpu->collectDisplay(1, rgba, &radiance);
  CHECK(radiance.empty());
  CHECK_THROWS_AS(gpu->collectDisplay(1, rgba, nullptr), std::logic_error);
}

}  // namespace

TEST_CASE("gpu path tracer: a run's frames, tone mapped on the device and queued two deep, are the film's",
          "[pathtrace][gpu]") {
  checkDisplayForm();
}

TEST_CASE("gpu path tracer: the GL 4.3 read-back (no pinned buffers) gives the same frames", "[pathtrace][gpu]") {
  setenv("SDG_GPU_GL43", "1", 1);
  checkDisplayForm();
  unsetenv("SDG_GPU_GL43");
}

TEST_CASE("gpu path tracer: a kernel compiled for the stage's features traces what the every-feature kernel does",
          "[pathtrace][gpu]") {
  PathTraceSettings settings;
  settings.samples = 4;
  settings.maxBounces = 4;
  auto specialised = gpuTracer(settings), every = gpuTracer(settings);
  if (!specialised || !every) return;
  every->setEveryKernelFeature(true);
  // The Cornell room has one of the optional features (a rect light);
  // with a cut-out screen and a sphere light with a diffuse multiplier, four.
  std::string withFeatures = kCornell;
  withFeatures += "  /Looks/Leaf: {type: Material, inputs:diffuse_color_constant: [0.2, 0.6, 0.2], "
                  "inputs:opacity_constant: 0.2, inputs:enable_opacity: true, inputs:opacity_threshold: 0.5}\n"
                  "  /Screen: {type: Plane, axis: Y, width: 0.6, length: 0.6, translate: [0, -0.5, 0.8], "
                  "material: /Looks/Leaf}\n"
                  "  /Fill: {type: SphereLight, inputs:radius: 0.05, inputs:intensity: 50, inputs:diffuse: 0.5, "
                  "translate: [0.5, -0.5, 1.5]}\n";
  for (const std::string& yaml : {std::string(kCornell), withFeatures}) {
    const RenderList list = renderListOf(yaml);
    const PathTracedFrame a = gpuTrace(*specialised, list, 24, 16, 5), b = gpuTrace(*every, list, 24, 16, 5);
    const uint32_t lamp = kGpuShapeLights;  // the room's rect light
    CHECK(specialised->stageFeatures() ==
          (yaml == kCornell ? lamp : lamp | kGpuOpacity | kGpuLobeMultipliers | kGpuSphereLights));
    const PathTracedFrame other = gpuTrace(*every, list, 24, 16, 6);
    const double noise = rms(b, other);
    INFO("rms specialised vs every feature " << rms(a, b) << ", seed to seed " << noise);
    REQUIRE(noise > 0);
    CHECK(rms(a, b) <= 0.05 * noise);
    CHECK(a.instance == b.instance);
  }
}
