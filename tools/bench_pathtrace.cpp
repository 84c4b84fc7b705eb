// Path tracer benchmark: one frame of a scene file's first camera, path
// traced (and denoised) at W x H with N samples on T threads: the time per
// frame (median of 3 after a warm-up frame that loads meshes and builds
// BVHs), the rays per second per core, and beside it what plain Embree ray
// casting reaches on the same scene (each pixel's centre ray, closest hit
// only). Prints one JSON object per figure. With `gpu`, the GPU tracer
// (render/pathtrace/gpu) traces and denoises instead, and its rays per
// second are the whole device's (the denoiser's time counted in).
//   sdg_bench_pathtrace SCENE WIDTH HEIGHT SAMPLES THREADS [denoise] [gpu]
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>
#include <vector>

#include "assets/asset_resolver.h"
#include "builtin_behaviors/builtin_behaviors.h"
#include "render/pathtrace/denoiser.h"
#include "render/pathtrace/gpu/gpu_path_tracer.h"
#include "render/pathtrace/path_tracer.h"
#include "scene_io/scene_loader.h"

using namespace sdg;

// What a run gets from the GPU tracer (queueDisplay/collectDisplay: the
// frame tone mapped on the device, 1 MB read back): one frame alone, and
// 20 frames queued two deep as a run queues them, per frame.
void printGpuDisplayFigures(GpuPathTracer& tracer, const RenderList& list, int width, int height,
                            const std::string& what) {
  std::vector<uint8_t> rgba;
  std::vector<double> alone;
  for (int run = 0; run < 4; ++run) {
    const auto start = std::chrono::steady_clock::now();
    tracer.queueDisplay(list, 0, width, height, uint64_t(run), 0.002f, false, 0);
    tracer.collectDisplay(0, rgba, nullptr);
    alone.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  }
  std::sort(alone.begin() + 1, alone.end());
  constexpr int kFrames = 20;
  const auto start = std::chrono::steady_clock::now();
  for (int f = 0; f < kFrames; ++f) {
    tracer.queueDisplay(list, 0, width, height, uint64_t(f), 0.002f, false, f & 1);
    if (f > 0) tracer.collectDisplay((f - 1) & 1, rgba, nullptr);
  }
  tracer.collectDisplay((kFrames - 1) & 1, rgba, nullptr);
  const double queued = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() / kFrames;
  std::printf("{\"name\": \"path tracer: %s, per frame as a run reads it (tone mapped on the GPU)\", \"unit\": "
              "\"s\", \"median\": %.4f, \"min\": %.4f, \"max\": %.4f}\n",
              what.c_str(), alone[2], alone[1], alone[3]);
  std::printf("{\"name\": \"path tracer: %s, per frame, %d frames queued two deep\", \"unit\": \"s\", "
              "\"median\": %.4f, \"min\": %.4f, \"max\": %.4f}\n",
              what.c_str(), kFrames, queued, queued, queued);
}

int main(int argc, char** argv) {
  if (argc < 6) {
    std::fprintf(stderr, "usage: sdg_bench_pathtrace SCENE WIDTH HEIGHT SAMPLES THREADS [denoise] [gpu]\n");
    return 2;
  }
  const std::string file = argv[1];
  const int width = std::atoi(argv[2]), height = std::atoi(argv[3]), samples = std::atoi(argv[4]);
  const int threads = std::atoi(argv[5]);
  bool denoise = false, gpu = false;
  for (int a = 6; a < argc; ++a) {
    denoise = denoise || std::string(argv[a]) == "denoise";
    gpu = gpu || std::string(argv[a]) == "gpu";
  }
  Scene scene = loadScene(file, builtinRegistry().catalog());
  const RenderList list = buildRenderList(scene.stage);
  const AssetResolver assets = makeSceneResolver(scene.sourceDir, scene.assetRoots, {});
  PathTraceSettings settings;
  settings.samples = samples;
  settings.maxBounces = int(scene.render.getUInt("max_bounces"));
  settings.threads = threads;
  PathTracer tracer(assets, settings);
  std::unique_ptr<GpuPathTracer> gpuTracer = gpu ? std::make_unique<GpuPathTracer>(assets, settings) : nullptr;
  if (gpuTracer && denoise) gpuTracer->setDenoiser(DenoiseSettings{});  // on the GPU, before the read-back
  DenoiseSettings ds;
  ds.threads = unsigned(threads);
  Denoiser denoiser(ds);
  PathTracedFrame frame;
  std::vector<double> seconds;
  double raysPerSecond = 0;
  for (int run = 0; run < 4; ++run) {
    const auto start = std::chrono::steady_clock::now();
    if (gpuTracer) gpuTracer->render(list, 0, width, height, uint64_t(run), frame);
    else tracer.render(list, 0, width, height, uint64_t(run), frame);
    if (denoise && !gpuTracer)
      denoiser.run({frame.width, frame.height, frame.radiance.data(), frame.albedo.data(), frame.normal.data(),
                    frame.depth.data(), frame.instance.data()},
                   frame.radiance.data());
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (run == 0) continue;  // meshes, textures, BVHs
    seconds.push_back(s);
    const PathTraceStats& stats = gpuTracer ? gpuTracer->stats() : tracer.stats();
    raysPerSecond = std::max(raysPerSecond, double(stats.rays) / stats.seconds);
  }
  std::sort(seconds.begin(), seconds.end());
  const double plain = tracer.primaryRayRate(list, 0, width, height, 8);
  const std::string what = file.substr(file.find_last_of('/') + 1) + " " + std::to_string(width) + "x" +
                           std::to_string(height) + ", " + std::to_string(samples) + " spp" +
                           (denoise ? " + denoiser" : "") + ", " + std::to_string(threads) + " threads" +
                           (gpuTracer ? ", GPU tracer on " + gpuTracer->device() : "");
  std::printf("{\"name\": \"path tracer: %s, per frame\", \"unit\": \"s\", \"median\": %.4f, \"min\": %.4f, "
              "\"max\": %.4f}\n",
              what.c_str(), seconds[1], seconds[0], seconds[2]);
  if (gpuTracer) {
    std::printf("{\"name\": \"path tracer: %s, rays per second (the whole GPU)\", \"unit\": \"Mrays/s\", "
                "\"median\": %.3f, \"min\": %.3f, \"max\": %.3f}\n",
                what.c_str(), raysPerSecond / 1e6, raysPerSecond / 1e6, raysPerSecond / 1e6);
    printGpuDisplayFigures(*gpuTracer, list, width, height, what);
    return 0;
  }
  std::printf("{\"name\": \"path tracer: %s, rays per second per core (plain Embree casting: %.3g)\", \"unit\": "
              "\"Mrays/s\", \"median\": %.3f, \"min\": %.3f, \"max\": %.3f}\n",
              what.c_str(), plain / 1e6 / threads, raysPerSecond / 1e6 / threads, raysPerSecond / 1e6 / threads,
              raysPerSecond / 1e6 / threads);
  return 0;
}
