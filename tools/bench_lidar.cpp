// LiDAR casting benchmark: one sweep of CHANNELS x AZIMUTHS rays from the
// scene's first camera's position (level, spinning, range 0.1-100 m,
// evenly spaced over OS1-128's +-22.5 degrees), cast through the
// path tracer's Embree scene on THREADS threads (lib/lidar). Points per
// second = rays cast / seconds per sweep, median of 7 sweeps after one
// that loads the meshes; the fraction of rays that hit goes beside it.
// The returns' FNV-1a hash goes to stderr, to check that a change keeps
// sweeps byte-identical.
//   sdg_bench_lidar SCENE CHANNELS AZIMUTHS THREADS
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <vector>

#include "lidar/lidar_caster.h"
#include "stage/lidar_pattern.h"
#include "tool_scene.h"

using namespace sdg;

int runMain(int argc, char** argv) {
  if (argc != 5) throw ToolUsageError("usage: sdg_bench_lidar SCENE CHANNELS AZIMUTHS THREADS");
  const ToolScene loaded = loadToolScene(argv[1]);
  const int channels = toolInt("CHANNELS", argv[2], 1), azimuths = toolInt("AZIMUTHS", argv[3], 1);
  const int threads = toolInt("THREADS", argv[4], 1);
  if (loaded.list.cameras.empty()) throw ToolUsageError("the scene has no camera to place the sensor at");
  LidarPattern pattern;
  for (int r = 0; r < channels; ++r)
    pattern.elevations.push_back(channels == 1 ? 0.0f : -22.5f + 45.0f * float(r) / float(channels - 1));
  pattern.azimuths = uint32_t(azimuths);
  pattern.rangeMin = 0.1f;
  pattern.rangeMax = 100.0f;
  Matrix4d pose = Matrix4d::Identity();
  pose.block<3, 1>(0, 3) = loaded.list.cameras.front().worldFromCamera.block<3, 1>(0, 3);
  LidarCaster caster(loaded.assets, unsigned(threads));
  caster.setScene(loaded.list);
  LidarSweep sweep;
  std::vector<double> seconds;
  for (int run = 0; run < 8; ++run) {
    const auto start = std::chrono::steady_clock::now();
    caster.cast(pattern, pose, loaded.list.metersPerUnit, 1, sweep);
    if (run > 0) seconds.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  }
  std::sort(seconds.begin(), seconds.end());
  const double rays = double(pattern.rayCount());
  const size_t hits = size_t(std::count_if(sweep.returns.begin(), sweep.returns.end(), [](const LidarReturn& r) { return r.hit(); }));
  uint64_t hash = 1469598103934665603ull;
  const auto* bytes = reinterpret_cast<const uint8_t*>(sweep.returns.data());
  for (size_t i = 0; i < sweep.returns.size() * sizeof(LidarReturn); ++i) hash = (hash ^ bytes[i]) * 1099511628211ull;
  std::fprintf(stderr, "sweep hash %016llx\n", static_cast<unsigned long long>(hash));
  std::printf("{\"name\": \"lidar: %d x %d sweep of %s on %d threads, Embree casting\", \"unit\": \"Mpoints/s\", \"median\": %.3f, "
              "\"min\": %.3f, \"max\": %.3f, \"hit_fraction\": %.3f, \"ms_per_sweep\": %.2f}\n",
              channels, azimuths, argv[1], threads, rays / seconds[3] / 1e6, rays / seconds.back() / 1e6,
              rays / seconds.front() / 1e6, double(hits) / rays, seconds[3] * 1e3);
  return 0;
}

int main(int argc, char** argv) { return runTool("sdg_bench_lidar", [&] { return runMain(argc, argv); }); }
