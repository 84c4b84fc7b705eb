#pragma once
// One LiDAR sweep as plain data, from the caster (lib/lidar) to the
// writers: every ray of the pattern in ray order (column by column, all
// rings of a column together), hit or not.
#include <cstdint>
#include <string>
#include <vector>

#include "stage/lidar_pattern.h"
#include "stage/math_types.h"

namespace sdg {

struct LidarReturn {
  float x = 0, y = 0, z = 0;  // sensor frame, metres; 0 for a miss
  float range = 0;            // metres, noise included; 0 for a miss (no hit in range, or dropped)
  float intensity = 0;        // diffuse reflectance x cos(incidence), 0 to 1
  float azimuth = 0;          // degrees from +x toward +y
  float time = 0;             // seconds from the sweep's start
  uint32_t ring = 0;
  uint32_t renderId = 0;      // RenderItem::instanceId of the surface hit; 0 for a miss

  bool hit() const { return range > 0.0f; }
};

struct LidarSweep {
  std::string path;                     // the Lidar prim
  std::string preset;                   // its preset, or "none"
  LidarPattern pattern;
  Matrix4d worldFromSensor = Matrix4d::Identity();  // rotation and translation (scene units), no scale
  double metersPerUnit = 1.0;
  std::vector<LidarReturn> returns;     // pattern.rayCount(), in ray order
};

}  // namespace sdg
