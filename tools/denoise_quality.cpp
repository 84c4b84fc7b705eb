// The denoiser's bias and error: one frame of a scene file's first camera at
// W x H, traced SEEDS times with SAMPLES samples (seeds 0, 1, ...), each
// frame with and without the denoiser, and once with REFERENCE samples
// (seed 1000) as the reference. Prints one JSON object per figure, all in
// percent of the reference's sum (of the noisy frames' mean without one):
// - block error of one frame: the error of 16 x 16-pixel block means,
//   summed over blocks and channels (median, min and max over the seeds).
//   At 4 samples noise does not average out in a block (the noisy frame's
//   own figure is its noise), so this mixes the denoiser's bias with noise;
// - MAE: the per-pixel absolute error, summed (median over the seeds);
// - the block error of the mean of the SEEDS frames, noisy (the
//   measurement's noise floor: the seeds' and the reference's noise) and
//   denoised (the denoiser's bias, on top of that floor);
// - paired bias: the block error of the mean of (denoised - noisy) over the
//   seeds. The noisy frame is unbiased, so its expectation is the
//   denoiser's bias; pairing cancels the noise the filter leaves in place,
//   so it resolves far below the floor above and needs no reference;
// - the denoiser's time per frame on THREADS threads (ms; median, min, max).
//   sdg_denoise_quality SCENE WIDTH HEIGHT SAMPLES REFERENCE THREADS [SEEDS] [spatial] [KEY=VALUE...]
// SEEDS defaults to 3; REFERENCE 0 skips the reference (paired figures
// only); `spatial` withholds the tracer's per-pixel variance (the
// neighbourhood estimate); iterations=, sigmaColor=, sigmaColorDecay=,
// sigmaNormal= and sigmaDepth= set the denoiser's parameters (DenoiseSettings) to try others.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "render/pathtrace/denoiser.h"
#include "render/pathtrace/path_tracer.h"
#include "tool_scene.h"

using namespace sdg;

namespace {

constexpr int kBlock = 16;

// Block and per-pixel absolute errors of `image` against `truth`, over the
// sum of `scale` (both in the blocks that fit the image).
struct Errors {
  double block = 0, pixel = 0;
};

template <class A, class B, class C>
Errors errorsOf(const A& image, const B& truth, const C& scale, int width, int height) {
  double blockError = 0, pixelError = 0, total = 0;
  for (int by = 0; by + kBlock <= height; by += kBlock)
    for (int bx = 0; bx + kBlock <= width; bx += kBlock)
      for (int c = 0; c < 3; ++c) {
        double a = 0, b = 0;
        for (int y = by; y < by + kBlock; ++y)
          for (int x = bx; x < bx + kBlock; ++x) {
            const size_t i = 3 * (size_t(y) * size_t(width) + size_t(x)) + size_t(c);
            a += image[i];
            b += truth[i];
            pixelError += std::abs(double(image[i]) - double(truth[i]));
            total += scale[i];
          }
        blockError += std::abs(a - b);
      }
  return {blockError / total, pixelError / total};
}

// Fractions, printed in percent; with unit "ms", as they are.
void print(const std::string& what, const std::string& name, std::vector<double> v, const char* unit = "%") {
  std::sort(v.begin(), v.end());
  const double scale = std::string(unit) == "%" ? 100.0 : 1.0;
  std::printf("{\"name\": \"denoiser: %s, %s\", \"unit\": \"%s\", \"median\": %.2f, \"min\": %.2f, \"max\": %.2f}\n",
              what.c_str(), name.c_str(), unit, scale * v[v.size() / 2],
              scale * v.front(), scale * v.back());
}

}  // namespace

int runMain(int argc, char** argv) {
  if (argc < 7) {
    std::fprintf(stderr, "usage: sdg_denoise_quality SCENE WIDTH HEIGHT SAMPLES REFERENCE THREADS [SEEDS] [spatial] "
                         "[iterations=N] [sigmaColor=X] [sigmaColorDecay=X] [sigmaNormal=X] [sigmaDepth=X]\n");
    return 2;
  }
  const std::string file = argv[1];
  const int width = toolInt("WIDTH", argv[2], kBlock), height = toolInt("HEIGHT", argv[3], kBlock);
  const int samples = toolInt("SAMPLES", argv[4], 1), referenceSamples = toolInt("REFERENCE", argv[5], 0);
  const int threads = toolInt("THREADS", argv[6], 1);
  const int seeds = argc > 7 ? toolInt("SEEDS", argv[7], 1) : 3;
  bool spatial = false;
  DenoiseSettings ds;
  for (int a = 8; a < argc; ++a) {
    const std::string arg = argv[a];
    const size_t eq = arg.find('=');
    const std::string key = arg.substr(0, eq);
    const char* value = eq == std::string::npos ? nullptr : argv[a] + eq + 1;
    if (arg == "spatial") spatial = true;
    else if (value && key == "iterations") ds.iterations = toolInt("iterations", value, 0);
    else if (value && key == "sigmaColor") ds.sigmaColor = toolFloat("sigmaColor", value);
    else if (value && key == "sigmaNormal") ds.sigmaNormal = toolFloat("sigmaNormal", value);
    else if (value && key == "sigmaDepth") ds.sigmaDepth = toolFloat("sigmaDepth", value);
    else if (value && key == "sigmaColorDecay") ds.sigmaColorDecay = toolFloat("sigmaColorDecay", value);
    else
      throw ToolUsageError("unknown argument '" + arg + "' (expected spatial or iterations=, sigmaColor=, "
                           "sigmaColorDecay=, sigmaNormal=, sigmaDepth=)");
  }
  if (ds.iterations > 16) throw ToolUsageError("iterations must be 0 to 16, got " + std::to_string(ds.iterations));
  const ToolScene loaded = loadToolScene(file);
  const RenderList& list = loaded.list;
  const AssetResolver& assets = loaded.assets;
  PathTracedFrame reference;
  if (referenceSamples > 0)
    PathTracer(assets, loaded.tracing(referenceSamples, threads))
        .render(list, 0, width, height, 1000, reference);
  PathTracer tracer(assets, loaded.tracing(samples, threads));
  ds.threads = unsigned(threads);
  Denoiser denoiser(ds);
  std::vector<double> noisyBlock, noisyMae, denoisedBlock, denoisedMae;  // one per seed
  PathTracedFrame frame;
  std::vector<float> denoised;
  std::vector<double> noisySum, denoisedSum, differenceSum, milliseconds;
  for (int seed = 0; seed < seeds; ++seed) {
    tracer.render(list, 0, width, height, uint64_t(seed), frame);
    denoised.resize(frame.radiance.size());
    const auto start = std::chrono::steady_clock::now();
    denoiser.run({frame.width, frame.height, frame.radiance.data(), frame.albedo.data(), frame.normal.data(),
                  frame.depth.data(), frame.instance.data(), spatial ? nullptr : frame.variance.data()},
                 denoised.data());
    milliseconds.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
    noisySum.resize(denoised.size()), denoisedSum.resize(denoised.size()), differenceSum.resize(denoised.size());
    for (size_t i = 0; i < denoised.size(); ++i) {
      noisySum[i] += frame.radiance[i];
      denoisedSum[i] += denoised[i];
      differenceSum[i] += double(denoised[i]) - double(frame.radiance[i]);
    }
    if (referenceSamples == 0) continue;
    const Errors n = errorsOf(frame.radiance, reference.radiance, reference.radiance, width, height);
    const Errors d = errorsOf(denoised, reference.radiance, reference.radiance, width, height);
    noisyBlock.push_back(n.block), noisyMae.push_back(n.pixel);
    denoisedBlock.push_back(d.block), denoisedMae.push_back(d.pixel);
  }
  const std::string what = file.substr(file.find_last_of('/') + 1) + " " + std::to_string(width) + "x" +
                           std::to_string(height) + ", " + std::to_string(samples) + " spp" +
                           (referenceSamples > 0 ? " against " + std::to_string(referenceSamples) + " spp" : "") +
                           (spatial ? ", spatial noise estimate" : "") + ", denoiser " +
                           std::to_string(ds.iterations) + " passes, sigmaColor " + std::to_string(ds.sigmaColor) +
                           ", sigmaNormal " + std::to_string(ds.sigmaNormal) + ", sigmaDepth " +
                           std::to_string(ds.sigmaDepth) + ", sigmaColorDecay " + std::to_string(ds.sigmaColorDecay);
  const std::string frames = std::to_string(seeds) + " frames";
  if (referenceSamples > 0) {
    print(what, "without the denoiser, block error of one frame", noisyBlock);
    print(what, "without the denoiser, MAE", noisyMae);
    print(what, "denoised, block error of one frame", denoisedBlock);
    print(what, "denoised, MAE", denoisedMae);
    std::vector<double> noisyMean(noisySum.size()), denoisedMean(noisySum.size());
    for (size_t i = 0; i < noisySum.size(); ++i) noisyMean[i] = noisySum[i] / seeds, denoisedMean[i] = denoisedSum[i] / seeds;
    print(what, "without the denoiser, block error of the mean of " + frames + " (the noise floor)",
          {errorsOf(noisyMean, reference.radiance, reference.radiance, width, height).block});
    print(what, "denoised, block error of the mean of " + frames,
          {errorsOf(denoisedMean, reference.radiance, reference.radiance, width, height).block});
  }
  const std::vector<double> zero(differenceSum.size(), 0.0);
  print(what, "denoised, paired block bias over " + frames,
        {errorsOf(differenceSum, zero, noisySum, width, height).block});
  print(what, "time per frame on " + std::to_string(threads) + " threads", milliseconds, "ms");
  return 0;
}

int main(int argc, char** argv) { return runTool("sdg_denoise_quality", [&] { return runMain(argc, argv); }); }
