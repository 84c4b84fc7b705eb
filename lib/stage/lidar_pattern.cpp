#include "stage/lidar_pattern.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/text.h"

namespace sdg {
namespace {

// Evenly spaced elevations from `low` to `high`, both included.
std::vector<float> evenlySpaced(uint32_t count, float low, float high) {
  std::vector<float> out(count);
  for (uint32_t i = 0; i < count; ++i)
    out[i] = count == 1 ? low : float(double(low) + (double(high) - double(low)) * i / (count - 1));
  return out;
}

std::vector<LidarPreset> buildPresets() {
  return {
      {"VLP-16", evenlySpaced(16, -15.0f, 15.0f),
       "Velodyne VLP-16 User Manual (63-9243), laser ID / vertical angle table: -15 to +15 degrees in 2 degree steps"},
      {"HDL-32E", evenlySpaced(32, -30.67f, 10.67f),
       "Velodyne HDL-32E User's Manual (63-9113), vertical angles -30.67 to +10.67 degrees, 1.33 degrees apart"},
      {"OS1-64", evenlySpaced(64, -16.6f, 16.6f),
       "Ouster OS1 datasheet (first generation): vertical field of view +16.6 to -16.6 degrees (33.2) for 64 "
       "channels, uniform beam spacing"},
      {"OS1-128", evenlySpaced(128, -22.5f, 22.5f),
       "Ouster OS1 datasheet (first generation): vertical field of view +22.5 to -22.5 degrees (45) for 128 "
       "channels, uniform beam spacing"},
  };
}

const LidarPreset* findPreset(std::string_view name) {
  for (const LidarPreset& p : lidarPresets())
    if (p.name == name) return &p;
  return nullptr;
}

int32_t intOf(const Prim& prim, std::string_view name) { return prim.value(name)->get<int32_t>(); }
Vec2f float2Of(const Prim& prim, std::string_view name) { return prim.value(name)->get<Vec2f>(); }
const FloatArray& elevationsOf(const Prim& prim) { return prim.value("elevations")->get<FloatArray>(); }

std::string num(float v) { return text::formatFloat(v); }
std::string pair(Vec2f v) { return "[" + num(v.x()) + ", " + num(v.y()) + "]"; }

}  // namespace

std::span<const LidarPreset> lidarPresets() {
  static const std::vector<LidarPreset> presets = buildPresets();
  return presets;
}

float LidarPattern::azimuth(uint32_t column) const {
  if (!solidState) return float(360.0 * column / azimuths);
  if (azimuths <= 1) return 0.0f;
  return float(horizontalFov * (0.5 - double(column) / (azimuths - 1)));
}

float LidarPattern::timeOffset(uint32_t column) const {
  return float(double(column) / (double(azimuths) * rotationRate));
}

Vec3f LidarPattern::direction(uint32_t ring, uint32_t column) const {
  constexpr double kRadians = std::numbers::pi / 180.0;
  const double a = azimuth(column) * kRadians, e = elevations[ring] * kRadians;
  return Vec3f(float(std::cos(e) * std::cos(a)), float(std::cos(e) * std::sin(a)), float(std::sin(e)));
}

std::vector<LidarProblem> lidarProblems(const Prim& prim) {
  std::vector<LidarProblem> out;
  auto problem = [&](std::string attribute, std::string message) {
    out.push_back({std::move(attribute), std::move(message)});
  };
  const std::string& preset = prim.getString("preset");
  const bool solid = prim.getString("pattern") == "solidState";
  const int32_t channels = intOf(prim, "channels");
  const FloatArray& elevations = elevationsOf(prim);
  const Vec2f vfov = float2Of(prim, "verticalFov");
  if (preset != "none") {
    for (const char* fixed : {"channels", "elevations", "verticalFov"})
      if (prim.findAttribute(fixed))
        problem(fixed, std::string("preset ") + preset + " fixes the channels and their elevations; remove `" + fixed +
                           "` or set preset: none");
    if (solid) problem("pattern", "preset " + preset + " is a spinning sensor, found pattern: solidState");
  } else {
    if (channels < 1 || size_t(channels) > 4096)
      problem("channels", "expected 1 to 4096 beams, found " + std::to_string(channels));
    if (elevations.size() > 0) {
      if (channels >= 1 && elevations.size() != size_t(channels))
        problem("elevations", "expected one elevation per channel (" + std::to_string(channels) + "), found " +
                                  std::to_string(elevations.size()));
      for (size_t i = 0; i < elevations.size(); ++i)
        if (!(std::isfinite(elevations[i]) && std::abs(elevations[i]) <= 90.0f)) {
          problem("elevations", "expected degrees from -90 to 90, found " + num(elevations[i]) + " at index " +
                                    std::to_string(i));
          break;
        }
    } else if (!(std::isfinite(vfov.x()) && std::isfinite(vfov.y()) && vfov.x() >= -90.0f && vfov.y() <= 90.0f &&
                 (vfov.x() < vfov.y() || (channels == 1 && vfov.x() == vfov.y())))) {
      problem("verticalFov", "expected [lowest, highest] degrees with -90 <= lowest < highest <= 90, found " + pair(vfov));
    }
  }
  const int32_t azimuths = intOf(prim, "horizontalResolution");
  if (azimuths < 1) problem("horizontalResolution", "expected at least 1 azimuth, found " + std::to_string(azimuths));
  const size_t rings = preset != "none" ? (findPreset(preset) ? findPreset(preset)->elevations.size() : 0)
                                        : size_t(std::max(channels, 0));
  if (azimuths >= 1 && rings * size_t(azimuths) > kMaxLidarRays)
    problem("horizontalResolution", "a sweep is limited to " + std::to_string(kMaxLidarRays) + " rays, found " +
                                        std::to_string(rings) + " channels x " + std::to_string(azimuths));
  if (solid) {
    const float h = prim.getFloat("horizontalFov");
    if (!(std::isfinite(h) && h > 0.0f && h <= 360.0f))
      problem("horizontalFov", "expected degrees greater than 0 and at most 360, found " + num(h));
  }
  const float rate = prim.getFloat("rotationRate");
  if (!(std::isfinite(rate) && rate > 0.0f)) problem("rotationRate", "expected Hz greater than 0, found " + num(rate));
  const Vec2f range = float2Of(prim, "range");
  if (!(std::isfinite(range.x()) && std::isfinite(range.y()) && range.x() >= 0.0f && range.x() < range.y()))
    problem("range", "expected [min, max] metres with 0 <= min < max, found " + pair(range));
  const float noise = prim.getFloat("rangeNoise");
  if (!(std::isfinite(noise) && noise >= 0.0f)) problem("rangeNoise", "expected metres >= 0, found " + num(noise));
  const float dropout = prim.getFloat("dropout");
  if (!(std::isfinite(dropout) && dropout >= 0.0f && dropout <= 1.0f))
    problem("dropout", "expected a probability from 0 to 1, found " + num(dropout));
  const float divergence = prim.getFloat("beamDivergence");
  if (!(std::isfinite(divergence) && divergence >= 0.0f))
    problem("beamDivergence", "expected milliradians >= 0, found " + num(divergence));
  return out;
}

LidarPattern lidarPatternOf(const Prim& prim) {
  LidarPattern p;
  p.solidState = prim.getString("pattern") == "solidState";
  if (const LidarPreset* preset = findPreset(prim.getString("preset"))) {
    p.elevations = preset->elevations;
  } else if (const FloatArray& e = elevationsOf(prim); e.size() > 0) {
    for (size_t i = 0; i < e.size(); ++i) p.elevations.push_back(e[i]);
  } else {
    const Vec2f vfov = float2Of(prim, "verticalFov");
    p.elevations = evenlySpaced(uint32_t(std::max(intOf(prim, "channels"), 1)), vfov.x(), vfov.y());
  }
  p.azimuths = uint32_t(std::max(intOf(prim, "horizontalResolution"), 1));
  p.horizontalFov = p.solidState ? prim.getFloat("horizontalFov") : 360.0f;
  p.rotationRate = prim.getFloat("rotationRate");
  const Vec2f range = float2Of(prim, "range");
  p.rangeMin = range.x();
  p.rangeMax = range.y();
  p.rangeNoise = prim.getFloat("rangeNoise");
  p.dropout = prim.getFloat("dropout");
  p.beamDivergence = prim.getFloat("beamDivergence");
  return p;
}

}  // namespace sdg
