#pragma once
// Replicator's colours for ids in colorized segmentation (spec §5.5.1): a
// 64-bit integer hash drives hue, saturation and value; 0 (BACKGROUND) is
// transparent black and 1 (UNLABELLED) opaque black.
#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace sdg {

std::array<uint8_t, 4> idColor(uint32_t id);
// Python's tuple text of a colour: "(93, 220, 11, 255)".
std::string colorKey(const std::array<uint8_t, 4>& rgba);
// Depth colorization (spec §5.5.3): log-scaled between the nearest and
// farthest finite distances; near bright (254), far and +inf dark (0).
std::vector<uint8_t> colorizeDistance(std::span<const float> distance);

}  // namespace sdg
