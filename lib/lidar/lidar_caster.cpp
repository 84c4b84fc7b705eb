#include "lidar/lidar_caster.h"

#include <algorithm>
#include <atomic>
#include <climits>
#include <cstdint>
#include <cmath>
#include <exception>
#include <mutex>
#include <numbers>
#include <thread>
#include <vector>

#include "behavior/rng.h"
#include "render/pathtrace/pt_surfaces.h"
#include "stage/xform.h"

namespace sdg {
namespace {

// What one block of rays needs, on the stack of the thread casting it.
struct BlockRays {
  PtRay rays[LidarCaster::kBlock];
  Vec3f local[LidarCaster::kBlock];  // each ray's direction in the sensor frame
  SurfaceHit hits[LidarCaster::kBlock];
  uint8_t found[LidarCaster::kBlock];
};

float luminance(const Vec3f& c) { return 0.2126f * c.x() + 0.7152f * c.y() + 0.0722f * c.z(); }

// A standard normal draw from two uniforms (Box-Muller, the cosine branch).
double gaussian(Rng& rng) {
  const double u1 = 1.0 - rng.uniform01();  // (0, 1]: log stays finite
  const double u2 = rng.uniform01();
  return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * std::numbers::pi * u2);
}

}  // namespace

LidarCaster::LidarCaster(const AssetResolver& assets, unsigned threads)
    : assets_(assets), threads_(std::max(1u, threads)), cache_(std::make_unique<PtGeometryCache>(assets)),
      surfaces_(std::make_unique<PtSurfaces>()) {}

LidarCaster::~LidarCaster() = default;

void LidarCaster::setScene(const RenderList& list) {
  *surfaces_ = PtSurfaces{};
  preparePtSurfaces(list, assets_, *cache_, *surfaces_);
}

void LidarCaster::cast(const LidarPattern& pattern, const Matrix4d& worldFromSensor, double metersPerUnit,
                       uint64_t seed, LidarSweep& out) const {
  const Decomposed pose = decompose(worldFromSensor);
  out.pattern = pattern;
  out.worldFromSensor = compose(pose.translation, pose.rotation, Vec3d::Ones());
  out.metersPerUnit = metersPerUnit;
  const size_t total = pattern.rayCount();
  out.returns.assign(total, LidarReturn{});
  if (total == 0) return;

  const Eigen::Matrix3f rotation = pose.rotation.cast<float>();
  const Vec3f origin = pose.translation.cast<float>();
  const float unitsPerMeter = float(1.0 / metersPerUnit);
  const uint32_t channels = pattern.channels();
  // Per ring and per column, computed once: a ray's direction is their product.
  std::vector<float> cosElevation(channels), sinElevation(channels);
  for (uint32_t r = 0; r < channels; ++r) {
    const double e = pattern.elevations[r] * std::numbers::pi / 180.0;
    cosElevation[r] = float(std::cos(e));
    sinElevation[r] = float(std::sin(e));
  }
  const PtSurfaces& surfaces = *surfaces_;
  const bool random = pattern.rangeNoise > 0.0f || pattern.dropout > 0.0f;
  const size_t blocks = (total + kBlock - 1) / kBlock;
  std::atomic<size_t> next{0};
  std::exception_ptr failure;
  std::mutex failureMutex;

  auto castBlocks = [&] {
    try {
      auto scratch = std::make_unique<BlockRays>();
      for (size_t block = next++; block < blocks; block = next++) {
        const size_t first = block * kBlock, n = std::min(kBlock, total - first);
        // A column's azimuth, time and sines, computed once for its rings.
        uint32_t column = UINT32_MAX;
        float azimuth = 0, time = 0, cosAzimuth = 1, sinAzimuth = 0;
        for (size_t i = 0; i < n; ++i) {
          const size_t ray = first + i;
          const uint32_t ring = uint32_t(ray % channels);
          if (uint32_t(ray / channels) != column) {
            column = uint32_t(ray / channels);
            azimuth = pattern.azimuth(column);
            time = pattern.timeOffset(column);
            const double a = double(azimuth) * std::numbers::pi / 180.0;
            cosAzimuth = float(std::cos(a));
            sinAzimuth = float(std::sin(a));
          }
          LidarReturn& ret = out.returns[ray];
          ret.ring = ring;
          ret.azimuth = azimuth;
          ret.time = time;
          const Vec3f local(cosElevation[ring] * cosAzimuth, cosElevation[ring] * sinAzimuth, sinElevation[ring]);
          scratch->local[i] = local;
          PtRay& r = scratch->rays[i];
          r.origin = origin;
          r.direction = (rotation * local).normalized();
          r.tMin = pattern.rangeMin * unitsPerMeter;
          r.tMax = pattern.rangeMax * unitsPerMeter;
        }
        surfaces.scene->intersectMany(scratch->rays, n, true, surfaces.cutOuts(), scratch->hits, scratch->found);
        for (size_t i = 0; i < n; ++i) {
          if (!scratch->found[i]) continue;
          const size_t ray = first + i;
          LidarReturn& ret = out.returns[ray];
          double range = double(scratch->hits[i].t) * metersPerUnit;
          if (random) {
            Rng rng(seed, ray);
            if (rng.uniform01() < pattern.dropout) continue;
            if (pattern.rangeNoise > 0.0f) range = std::max(0.0, range + pattern.rangeNoise * gaussian(rng));
          }
          if (!(range > 0.0)) continue;
          const PtRay& r = scratch->rays[i];
          const SurfaceHit& hit = scratch->hits[i];
          const SurfaceGeometry g = surfaces.scene->geometry(hit);
          const Vec3f toward = -r.direction;
          const ShadedSurface shaded = shadeSurface(surfaces.material(hit.instance, g.part), g, toward);
          const float cosine = std::clamp(shaded.normal.dot(toward), 0.0f, 1.0f);
          ret.intensity = std::clamp(luminance(shaded.albedo) * cosine, 0.0f, 1.0f);
          ret.range = float(range);
          // The point along the sensor-frame direction, at the (noisy) range.
          const Vec3f& local = scratch->local[i];
          ret.x = local.x() * ret.range;
          ret.y = local.y() * ret.range;
          ret.z = local.z() * ret.range;
          ret.renderId = surfaces.instanceIds[hit.instance];
        }
      }
    } catch (...) {
      std::lock_guard lock(failureMutex);
      if (!failure) failure = std::current_exception();
      next = blocks;
    }
  };
  const unsigned workers = unsigned(std::min<size_t>(threads_, blocks));
  std::vector<std::thread> helpers;
  for (unsigned t = 1; t < workers; ++t) helpers.emplace_back(castBlocks);
  castBlocks();
  for (std::thread& t : helpers) t.join();
  if (failure) std::rethrow_exception(failure);
}

uint64_t lidarSeed(int64_t runSeed, std::string_view primPath, uint64_t frame) {
  return mix64(stableHash(primPath, uint64_t(runSeed)) ^ mix64(frame + 0x6c69646172ull));  // "lidar"
}

}  // namespace sdg
