#pragma once
// A Lidar prim's scan pattern (prim_types.cpp, docs/scene-format.md): the
// rings' elevations, the azimuths of one sweep and when each is fired,
// read from the prim's attributes or a published sensor's preset, and the
// problems that make a prim unusable (for the loader's located errors).
//
// Sensor frame: x forward, y left, z up (the spin axis), as ROS's REP 103
// and KITTI's velodyne frame. A ray's azimuth is measured from +x toward
// +y, its elevation from the x-y plane toward +z. Rays are numbered column
// by column: ray = column * channels + ring, all rings of one azimuth fired
// together; ring 0 is the first elevation (the lowest, for presets and
// verticalFov).
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "stage/math_types.h"
#include "stage/prim.h"

namespace sdg {

struct LidarPreset {
  std::string_view name;
  std::vector<float> elevations;  // degrees, ascending
  std::string_view source;        // the published table it follows
};

std::span<const LidarPreset> lidarPresets();

struct LidarPattern {
  bool solidState = false;
  std::vector<float> elevations;   // degrees, one per ring
  uint32_t azimuths = 0;           // columns per sweep
  float horizontalFov = 360.0f;    // degrees (solidState: the span centred on +x)
  float rotationRate = 10.0f;      // sweeps per second
  float rangeMin = 0.0f, rangeMax = 0.0f;  // metres
  float rangeNoise = 0.0f;         // metres, Gaussian sigma
  float dropout = 0.0f;            // probability
  float beamDivergence = 0.0f;     // milliradians (metadata)

  uint32_t channels() const { return uint32_t(elevations.size()); }
  size_t rayCount() const { return size_t(channels()) * azimuths; }
  // Degrees from +x toward +y: spinning, 360 * column / azimuths; solid
  // state, from +horizontalFov/2 (left) to -horizontalFov/2 (right).
  float azimuth(uint32_t column) const;
  // Seconds from the sweep's start: column / (azimuths * rotationRate).
  float timeOffset(uint32_t column) const;
  // Unit direction of (ring, column) in the sensor frame.
  Vec3f direction(uint32_t ring, uint32_t column) const;
};

struct LidarProblem {
  std::string attribute;
  std::string message;  // what was expected and what was found
};

// Everything wrong with a Lidar prim's attributes (empty: usable).
std::vector<LidarProblem> lidarProblems(const Prim& prim);
// The pattern of a Lidar prim without problems.
LidarPattern lidarPatternOf(const Prim& prim);

// Upper bound on one sweep's rays (channels x azimuths): 16 M, so that a
// typo cannot ask for gigabytes.
inline constexpr size_t kMaxLidarRays = size_t(1) << 24;

}  // namespace sdg
