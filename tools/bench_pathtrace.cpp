// Path tracer benchmark: one frame of a scene file's first camera, path
// traced (and denoised) at W x H with N samples on T threads: the time per
// frame (median of 3 after a warm-up frame that loads meshes and builds
// BVHs), the rays per second per core, and beside it what plain Embree ray
// casting reaches on the same scene (the centre rays alone); with `replay`,
// also on the very same rays (recorded from one more frame, kept in memory,
// 36 bytes a ray, then cast again without shading: one call per ray, and
// through Embree's ray streams), and the tracer's rate as a share of
// each. Prints one JSON object per figure; the radiance's
// FNV-1a hash goes to stderr, to check that a change keeps frames
// byte-identical. With `gpu`, the GPU tracer
// (render/pathtrace/gpu) traces and denoises instead, and its rays per
// second are the whole device's (the denoiser's time counted in).
//   sdg_bench_pathtrace SCENE WIDTH HEIGHT SAMPLES THREADS [denoise] [gpu] [replay]
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "render/pathtrace/denoiser.h"
#include "render/pathtrace/gpu/gpu_path_tracer.h"
#include "render/pathtrace/path_tracer.h"
#include "tool_scene.h"

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

int runMain(int argc, char** argv) {
  if (argc < 6) {
    std::fprintf(stderr, "usage: sdg_bench_pathtrace SCENE WIDTH HEIGHT SAMPLES THREADS [denoise] [gpu] [replay]\n");
    return 2;
  }
  const std::string file = argv[1];
  const int width = toolInt("WIDTH", argv[2], 1), height = toolInt("HEIGHT", argv[3], 1);
  const int samples = toolInt("SAMPLES", argv[4], 1), threads = toolInt("THREADS", argv[5], 1);
  bool denoise = false, gpu = false, replay = false;
  for (int a = 6; a < argc; ++a) {
    const std::string flag = argv[a];
    if (flag == "replay") replay = true;
    else if (flag == "denoise") denoise = true;
    else if (flag == "gpu") gpu = true;
    else {
      std::fprintf(stderr, "sdg_bench_pathtrace: unknown argument '%s' (expected denoise, gpu or replay)\n", argv[a]);
      return 2;
    }
  }
  const ToolScene loaded = loadToolScene(file);
  const RenderList& list = loaded.list;
  const AssetResolver& assets = loaded.assets;
  const PathTraceSettings settings = loaded.tracing(samples, threads);
  PathTracer tracer(assets, settings);
  std::unique_ptr<GpuPathTracer> gpuTracer = gpu ? std::make_unique<GpuPathTracer>(assets, settings) : nullptr;
  if (gpuTracer && denoise) gpuTracer->setDenoiser(DenoiseSettings{});  // on the GPU, before the read-back
  DenoiseSettings ds;
  ds.threads = unsigned(threads);
  Denoiser denoiser(ds);
  PathTracedFrame frame;
  std::vector<double> seconds, raysPerSecond;
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
    raysPerSecond.push_back(double(stats.rays) / stats.seconds);
  }
  std::sort(seconds.begin(), seconds.end());
  std::sort(raysPerSecond.begin(), raysPerSecond.end());
  uint64_t hash = 0xcbf29ce484222325ull;
  for (float v : frame.radiance) {
    uint32_t bits;
    std::memcpy(&bits, &v, 4);
    for (int b = 0; b < 4; ++b) hash = (hash ^ ((bits >> (8 * b)) & 0xffu)) * 0x100000001b3ull;
  }
  std::fprintf(stderr, "radiance hash (seed 3): %016llx\n", static_cast<unsigned long long>(hash));
  const std::string what = file.substr(file.find_last_of('/') + 1) + " " + std::to_string(width) + "x" +
                           std::to_string(height) + ", " + std::to_string(samples) + " spp" +
                           (denoise ? " + denoiser" : "") + ", " + std::to_string(threads) + " threads" +
                           (gpuTracer ? ", GPU tracer on " + gpuTracer->device() : "");
  std::printf("{\"name\": \"path tracer: %s, per frame\", \"unit\": \"s\", \"median\": %.4f, \"min\": %.4f, "
              "\"max\": %.4f}\n",
              what.c_str(), seconds[1], seconds[0], seconds[2]);
  auto figure = [&](const std::string& name, const char* unit, double median, double min, double max) {
    std::printf("{\"name\": \"path tracer: %s, %s\", \"unit\": \"%s\", \"median\": %.3f, \"min\": %.3f, "
                "\"max\": %.3f}\n",
                what.c_str(), name.c_str(), unit, median, min, max);
  };
  if (gpuTracer) {
    figure("rays per second (the whole GPU)", "Mrays/s", raysPerSecond[1] / 1e6, raysPerSecond[0] / 1e6,
           raysPerSecond[2] / 1e6);
    printGpuDisplayFigures(*gpuTracer, list, width, height, what);
    return 0;
  }
  const double perCore = 1e-6 / threads;
  figure("rays per second per core", "Mrays/s", raysPerSecond[1] * perCore, raysPerSecond[0] * perCore,
         raysPerSecond[2] * perCore);
  const double plain = tracer.primaryRayRate(list, 0, width, height, 8);
  figure("plain Embree casting of each pixel's centre ray (closest hit) per second per core", "Mrays/s",
         plain * perCore, plain * perCore, plain * perCore);
  if (!replay) return 0;
  // The same rays again through Embree alone: one more frame recorded.
  RayLog log;
  tracer.recordRays(&log);
  tracer.render(list, 0, width, height, 3, frame);
  tracer.recordRays(nullptr);
  for (bool streams : {false, true}) {
    std::vector<double> rates;
    for (int run = 0; run < 5; ++run) rates.push_back(tracer.replayRate(list, log, streams, 1));
    std::sort(rates.begin(), rates.end());
    const std::string how =
        streams ? "as ray streams (camera rays coherent)" : "one rtcIntersect1/rtcOccluded1 call a ray";
    figure("plain Embree casting of the tracer's own rays per second per core, " + how, "Mrays/s", rates[2] * perCore,
           rates[0] * perCore, rates[4] * perCore);
    figure("the tracer's rays per second as a share of plain Embree casting of the same rays, " + how, "%",
           100 * raysPerSecond[1] / rates[2], 100 * raysPerSecond[0] / rates[2], 100 * raysPerSecond[2] / rates[2]);
  }
  return 0;
}

int main(int argc, char** argv) { return runTool("sdg_bench_pathtrace", [&] { return runMain(argc, argv); }); }
