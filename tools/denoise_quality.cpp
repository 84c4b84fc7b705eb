// The denoiser's error against a reference of the same tracer: one frame of
// a scene file's first camera at W x H, traced with REFERENCE samples (the
// reference) and with SAMPLES samples, the latter with and without the
// denoiser. Prints one JSON object per figure:
// - bias: the error of 16 x 16-pixel block means, summed over blocks and
//   channels, over the reference's sum (noise averages out in a block, what
//   a filter moves across edges does not);
// - MAE: the per-pixel absolute error, summed, over the reference's sum.
//   sdg_denoise_quality SCENE WIDTH HEIGHT SAMPLES REFERENCE THREADS [SEEDS] [spatial]
// SEEDS (default 3) noisy frames give the median, min and max; `spatial`
// withholds the tracer's per-pixel variance (the neighbourhood estimate).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "assets/asset_resolver.h"
#include "builtin_behaviors/builtin_behaviors.h"
#include "render/pathtrace/denoiser.h"
#include "render/pathtrace/path_tracer.h"
#include "scene_io/scene_loader.h"

using namespace sdg;

namespace {

struct Errors {
  double bias = 0, mae = 0;
};

Errors errorsOf(const std::vector<float>& image, const std::vector<float>& reference, int width, int height) {
  constexpr int kBlock = 16;
  double blockError = 0, pixelError = 0, total = 0;
  for (int by = 0; by + kBlock <= height; by += kBlock)
    for (int bx = 0; bx + kBlock <= width; bx += kBlock)
      for (int c = 0; c < 3; ++c) {
        double a = 0, b = 0;
        for (int y = by; y < by + kBlock; ++y)
          for (int x = bx; x < bx + kBlock; ++x) {
            const size_t i = 3 * (size_t(y) * size_t(width) + size_t(x)) + size_t(c);
            a += image[i];
            b += reference[i];
            pixelError += std::abs(double(image[i]) - reference[i]);
          }
        blockError += std::abs(a - b);
        total += b;
      }
  return {blockError / total, pixelError / total};
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 7) {
    std::fprintf(stderr, "usage: sdg_denoise_quality SCENE WIDTH HEIGHT SAMPLES REFERENCE THREADS [SEEDS] [spatial]\n");
    return 2;
  }
  const std::string file = argv[1];
  const int width = std::atoi(argv[2]), height = std::atoi(argv[3]), samples = std::atoi(argv[4]);
  const int referenceSamples = std::atoi(argv[5]), threads = std::atoi(argv[6]);
  const int seeds = argc > 7 ? std::max(1, std::atoi(argv[7])) : 3;
  const bool spatial = argc > 8 && std::string(argv[8]) == "spatial";
  Scene scene = loadScene(file, builtinRegistry().catalog());
  const RenderList list = buildRenderList(scene.stage);
  const AssetResolver assets = makeSceneResolver(scene.sourceDir, scene.assetRoots, {});
  const int bounces = int(scene.render.getUInt("max_bounces"));
  PathTracedFrame reference;
  PathTracer(assets, PathTraceSettings{referenceSamples, bounces, threads}).render(list, 0, width, height, 1000, reference);
  PathTracer tracer(assets, PathTraceSettings{samples, bounces, threads});
  DenoiseSettings ds;
  ds.threads = unsigned(threads);
  Denoiser denoiser(ds);
  std::vector<double> figures[4];  // bias and MAE without, then with the denoiser, one per seed
  PathTracedFrame frame;
  for (int seed = 0; seed < seeds; ++seed) {
    tracer.render(list, 0, width, height, uint64_t(seed), frame);
    const Errors n = errorsOf(frame.radiance, reference.radiance, width, height);
    denoiser.run({frame.width, frame.height, frame.radiance.data(), frame.albedo.data(), frame.normal.data(),
                  frame.depth.data(), frame.instance.data(), spatial ? nullptr : frame.variance.data()},
                 frame.radiance.data());
    const Errors d = errorsOf(frame.radiance, reference.radiance, width, height);
    for (auto [k, v] : {std::pair{0, n.bias}, std::pair{1, n.mae}, std::pair{2, d.bias}, std::pair{3, d.mae}})
      figures[k].push_back(100 * v);
  }
  const std::string what = file.substr(file.find_last_of('/') + 1) + " " + std::to_string(width) + "x" +
                           std::to_string(height) + ", " + std::to_string(samples) + " spp against " +
                           std::to_string(referenceSamples) + " spp" + (spatial ? ", spatial noise estimate" : "");
  const char* names[4] = {"without the denoiser, block bias", "without the denoiser, MAE", "denoised, block bias",
                          "denoised, MAE"};
  for (int k = 0; k < 4; ++k) {
    std::vector<double>& v = figures[k];
    std::sort(v.begin(), v.end());
    std::printf("{\"name\": \"denoiser: %s, %s\", \"unit\": \"%%\", \"median\": %.2f, \"min\": %.2f, \"max\": %.2f}\n",
                what.c_str(), names[k], v[v.size() / 2], v.front(), v.back());
  }
  return 0;
}
