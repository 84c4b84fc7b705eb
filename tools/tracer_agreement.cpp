// How closely the CPU and GPU path tracers agree on one scene: both render
// the scene's first camera at W x H with N samples (no denoiser), the CPU
// tracer with two seeds, the GPU tracer with the first. Prints, as JSON
// rows: the block bias between the tracers (the largest |difference| of
// 16 x 16-pixel block means over the image's mean, where noise averages
// out) on the same sample streams and on independent ones (GPU seed 2),
// the same between the CPU tracer's two seeds (the noise floor of that
// figure), and the per-pixel RMS difference of the tracers over the CPU's
// own seed-to-seed RMS (within their noise: about 1 or less).
//   sdg_tracer_agreement SCENE WIDTH HEIGHT SAMPLES THREADS
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "render/pathtrace/gpu/gpu_path_tracer.h"
#include "render/pathtrace/path_tracer.h"
#include "tool_scene.h"

using namespace sdg;

namespace {

constexpr int kBlock = 16;

double meanOf(const PathTracedFrame& f) {
  double sum = 0;
  for (float v : f.radiance) sum += v;
  return sum / double(f.radiance.size());
}

double worstBlockBias(const PathTracedFrame& a, const PathTracedFrame& b) {
  double worst = 0;
  for (int by = 0; by + kBlock <= a.height; by += kBlock)
    for (int bx = 0; bx + kBlock <= a.width; bx += kBlock) {
      double difference = 0;
      for (int y = by; y < by + kBlock; ++y)
        for (int x = bx; x < bx + kBlock; ++x)
          for (int c = 0; c < 3; ++c) {
            const size_t i = 3 * size_t(y * a.width + x) + size_t(c);
            difference += double(a.radiance[i]) - double(b.radiance[i]);
          }
      worst = std::max(worst, std::abs(difference) / (kBlock * kBlock * 3));
    }
  return worst / meanOf(b);
}

double rms(const PathTracedFrame& a, const PathTracedFrame& b) {
  double sum = 0;
  for (size_t i = 0; i < a.radiance.size(); ++i) {
    const double d = double(a.radiance[i]) - double(b.radiance[i]);
    sum += d * d;
  }
  return std::sqrt(sum / double(a.radiance.size()));
}

void row(const std::string& what, const char* unit, double value) {
  std::printf("{\"name\": \"%s\", \"unit\": \"%s\", \"median\": %.5g, \"min\": %.5g, \"max\": %.5g}\n", what.c_str(),
              unit, value, value, value);
}

}  // namespace

int runMain(int argc, char** argv) {
  if (argc != 6) {
    std::fprintf(stderr, "usage: sdg_tracer_agreement SCENE WIDTH HEIGHT SAMPLES THREADS\n");
    return 2;
  }
  const std::string file = argv[1];
  const int width = toolInt("WIDTH", argv[2], 1), height = toolInt("HEIGHT", argv[3], 1);
  const int samples = toolInt("SAMPLES", argv[4], 1), threads = toolInt("THREADS", argv[5], 1);
  const ToolScene loaded = loadToolScene(file);
  const RenderList& list = loaded.list;
  const AssetResolver& assets = loaded.assets;
  const PathTraceSettings settings = loaded.tracing(samples, threads);
  PathTracer cpu(assets, settings);
  GpuPathTracer gpu(assets, settings);
  PathTracedFrame cpu1, cpu2, gpu1, gpu2;
  cpu.render(list, 0, width, height, 1, cpu1);
  cpu.render(list, 0, width, height, 2, cpu2);
  gpu.render(list, 0, width, height, 1, gpu1);
  gpu.render(list, 0, width, height, 2, gpu2);
  const std::string what = "tracer agreement: " + file.substr(file.find_last_of('/') + 1) + " " +
                           std::to_string(width) + "x" + std::to_string(height) + ", " + std::to_string(samples) +
                           " spp, GPU tracer on " + gpu.device();
  row(what + ", block bias CPU vs GPU (16 x 16 blocks)", "%", 100 * worstBlockBias(gpu1, cpu1));
  row(what + ", block bias CPU seed 1 vs GPU seed 2 (independent samples)", "%", 100 * worstBlockBias(gpu2, cpu1));
  row(what + ", block bias CPU seed 1 vs seed 2 (the noise floor)", "%", 100 * worstBlockBias(cpu2, cpu1));
  row(what + ", per-pixel RMS CPU vs GPU over CPU seed 1 vs 2", "ratio", rms(gpu1, cpu1) / rms(cpu2, cpu1));
  row(what + ", mean radiance GPU over CPU", "ratio", meanOf(gpu1) / meanOf(cpu1));
  return 0;
}

int main(int argc, char** argv) { return runTool("sdg_tracer_agreement", [&] { return runMain(argc, argv); }); }
