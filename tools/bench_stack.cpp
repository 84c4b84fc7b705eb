// Stacking benchmark: 4 pallets (1.2 m x 1.0 m) with 15, 100 or 1,000
// cartons each (sizes vary, so the stacks are irregular), dropped and
// settled by the volume stack schedule. Prints one JSON object per figure:
// the median, min and max wall time of the simulation over several runs,
// the cost per asset, and the settle quality of the last run.
//   sdg_bench_stack [runs] [counts...]      e.g. sdg_bench_stack 5 15 100
// SDG_STACK_TRACE=1 prints the fastest asset speed after every step.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "physics/stack_simulation.h"

using namespace sdg;

namespace {

StackPlan makePlan(int perSurface) {
  StackPlan plan;
  // Carton sizes shrink with the count so the same pallet holds them.
  const double scale = perSurface <= 15 ? 1.0 : perSurface <= 100 ? 0.5 : 0.22;
  uint64_t state = 12345;
  auto next = [&] {  // a fixed LCG: the plan is the same on every machine
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    return double(state >> 11) / double(1ull << 53);
  };
  for (int s = 0; s < 4; ++s) {
    StackSurface surface;
    surface.path = "/Pallets/Pallet_" + std::to_string(s);
    surface.origin = Vec3d(2.0 * s, 0, 0.07);
    surface.size = Vec3d(1.2, 1.0, 0.14);
    surface.dropHeight = 2.0;
    plan.surfaces.push_back(surface);
    plan.assets.emplace_back();
    for (int i = 0; i < perSurface; ++i) {
      Vec3d half = Vec3d(0.15 + 0.1 * next(), 0.12 + 0.08 * next(), 0.1 + 0.1 * next()) * scale;
      MeshKey key;
      key.shape = PrimType::Cube;
      key.a = 2.0;
      MeshData cube;
      for (int c = 0; c < 8; ++c)
        cube.positions.push_back(Vec3f(float(c & 1 ? half.x() : -half.x()), float(c & 2 ? half.y() : -half.y()),
                                       float(c & 4 ? half.z() : -half.z())));
      StackAsset a;
      a.path = surface.path + "/Asset_" + std::to_string(i);
      a.url = "carton";
      a.collider = std::make_shared<const Collider>(makeCollider(key, cube));
      double margin = half.maxCoeff();
      double range = 0.5 - margin;
      Vec3d local = surface.topCentre() + Vec3d((2 * next() - 1) * range, (2 * next() - 1) * range,
                                                surface.dropHeight - half.z() - 0.001);
      a.drop.position = surface.toWorld(local);
      plan.assets.back().push_back(a);
    }
  }
  return plan;
}

}  // namespace

int main(int argc, char** argv) {
  int runs = argc > 1 ? std::atoi(argv[1]) : 5;
  std::vector<int> counts;
  for (int i = 2; i < argc; ++i) counts.push_back(std::atoi(argv[i]));
  if (counts.empty()) counts = {15, 100, 1000};
  const bool trace = std::getenv("SDG_STACK_TRACE") != nullptr;
  for (int count : counts) {
    StackPlan plan = makePlan(count);
    StackOptions options;
    if (trace)
      options.onStep = [](uint64_t step, const std::vector<std::vector<BodyPose>>&) {
        std::fprintf(stderr, "step %llu\n", static_cast<unsigned long long>(step));
      };
    std::vector<double> seconds;
    StackResult last;
    for (int r = 0; r < (count >= 1000 ? 1 : std::max(1, runs)); ++r) {
      auto start = std::chrono::steady_clock::now();
      last = simulateStack(plan, options);
      seconds.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    }
    std::sort(seconds.begin(), seconds.end());
    double median = seconds[seconds.size() / 2];
    bool settled = true;
    double lin = 0, ang = 0, penSurface = 0, penAssets = 0;
    size_t left = 0, extra = 0;
    for (const SurfaceSettleReport& r : last.reports) {
      settled = settled && r.settled;
      lin = std::max(lin, r.maxLinearSpeed), ang = std::max(ang, r.maxAngularSpeed);
      penSurface = std::max(penSurface, r.maxPenetrationSurface);
      penAssets = std::max(penAssets, r.maxPenetrationAssets);
      left += r.leftArea.size();
      extra = r.extraSettleSteps;
    }
    std::printf(
        "{\"name\": \"stack simulation, 4 surfaces x %d cartons\", \"unit\": \"s\", \"median\": %.4f, "
        "\"min\": %.4f, \"max\": %.4f, \"runs\": %zu, \"ms_per_asset\": %.4f, \"steps\": %llu, "
        "\"extra_settle_steps\": %zu, \"settled\": %s, \"max_linear_speed\": %.5f, \"max_angular_speed\": %.5f, "
        "\"max_penetration_surface\": %.5f, \"max_penetration_assets\": %.5f, \"left_area\": %zu}\n",
        count, median, seconds.front(), seconds.back(), seconds.size(), 1000 * median / (4.0 * count),
        static_cast<unsigned long long>(last.steps), extra, settled ? "true" : "false", lin, ang, penSurface, penAssets, left);
    std::fflush(stdout);
  }
}
