#pragma once
// NVIDIA's omni_lens_distortion API schemas and the `omni:lensdistortion:model`
// token each stands for: a stage that applies the schema without authoring the
// token gets the schema's model (its fallback in NVIDIA's schema), and
// export-usd applies the schema of the model it writes.
#include <array>
#include <string_view>

namespace sdg {

struct UsdLensSchema {
  std::string_view schema;
  std::string_view model;
};

inline constexpr std::array<UsdLensSchema, 4> kUsdLensSchemas = {{
    {"OmniLensDistortionOpenCvPinholeAPI", "opencvPinhole"},
    {"OmniLensDistortionOpenCvFisheyeAPI", "opencvFisheye"},
    {"OmniLensDistortionFthetaAPI", "ftheta"},
    {"OmniLensDistortionKannalaBrandtK3API", "kannalaBrandtK3"},
}};

// The model of the family's schema that nothing here reads
// (OmniLensDistortionRadTanThinPrismAPI: NVIDIA's reference gives no
// formula): a stage using it keeps the ideal pinhole and the import counts
// the loss. The family's LUT and omni-directional stereo schemas are counted
// by their applied schema (usd_losses.cpp).
inline constexpr std::string_view kUnreadLensModel = "radTanThinPrism";

}  // namespace sdg
