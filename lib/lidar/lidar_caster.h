#pragma once
// Casts a Lidar prim's sweep through the CPU path tracer's Embree scene of
// the frame (render/pathtrace/pt_surfaces.h: the same meshes, instances,
// materials and cut-outs the path tracer traces), so no second BVH exists.
//
// Rays leave the sensor's origin along LidarPattern::direction, turned by
// the sensor's world rotation, and hit in [range min, range max]. Per hit:
// the range (metres), the point along the ray at that range in the sensor
// frame, the intensity (below), the render id of the surface.
//
// Intensity: a Lambertian return, rho * cos(theta), where rho is the
// Rec. 709 luminance of the surface's base colour at the hit (the diffuse
// reflectance the path tracer shades with: material constant, texture and
// vertex colours) and theta the angle between the ray and the shading
// normal; in [0, 1], no fall-off with range (a calibrated reflectivity, as
// KITTI's remission).
//
// Noise and dropout: each ray r draws from its own PCG32 stream, Rng(seed,
// r) (behavior/rng.h), where `seed` is the sensor's (the run's seed, the
// prim path and the frame: lidarSeed()); a hit is dropped with probability
// `dropout`, and its range gets Gaussian noise of sigma `rangeNoise`
// (Box-Muller on two draws; a range below 0 becomes 0, a miss).
//
// Determinism: rays are cast in fixed blocks of kBlock rays, one Embree
// stream each, taken by threads from an atomic counter; a ray's result
// depends only on its block and its own stream, so a sweep is
// byte-identical whatever the thread count.
#include <cstdint>
#include <memory>
#include <string_view>

#include "assets/asset_resolver.h"
#include "render/lidar_sweep.h"
#include "render/render_list.h"

namespace sdg {

struct PtGeometryCache;
struct PtSurfaces;

class LidarCaster {
 public:
  static constexpr size_t kBlock = 256;

  LidarCaster(const AssetResolver& assets, unsigned threads);
  ~LidarCaster();
  LidarCaster(const LidarCaster&) = delete;
  LidarCaster& operator=(const LidarCaster&) = delete;

  // The frame's geometry: every sweep cast until the next call sees it.
  // Meshes are loaded once per caster. Throws RunError for a mesh or
  // texture that cannot be read.
  void setScene(const RenderList& list);
  // One sweep of `pattern` from `worldFromSensor` (scale ignored); `out`'s
  // returns are resized to the pattern's rays, its other fields filled.
  void cast(const LidarPattern& pattern, const Matrix4d& worldFromSensor, double metersPerUnit, uint64_t seed,
            LidarSweep& out) const;

 private:
  const AssetResolver& assets_;
  unsigned threads_;
  std::unique_ptr<PtGeometryCache> cache_;
  std::unique_ptr<PtSurfaces> surfaces_;
};

// The sensor's random stream key for one frame: the run's seed, the prim's
// path and the frame number (so shards and thread counts agree).
uint64_t lidarSeed(int64_t runSeed, std::string_view primPath, uint64_t frame);

}  // namespace sdg
