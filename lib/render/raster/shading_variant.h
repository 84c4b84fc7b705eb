#pragma once
// Which scene program draws a mesh part: the arrangement of its material's
// maps, written into the fragment shader as #defines (render/shaders.h) so
// that llvmpipe never pays per pixel for a map the part does not have.
#include <cstdint>
#include <string>

#include "assets/mesh_data.h"

namespace sdg {

struct ShadingVariant {
  uint8_t projection = 1;    // 1 the mesh's uvs, 2 world-space triplanar
  uint8_t baseMap = 0;       // 0 none, 1 sampled
  uint8_t roughnessMap = 0;  // 0 none, 1 its own map's red, 2 the ORM map's green
  uint8_t metallicMap = 0;   // 0 none, 1 its own map's red, 2 the ORM map's blue
  uint8_t normalMap = 0;     // 0 none, 1 sampled (uv projection only)
  uint8_t opacity = 0;       // OpacitySource: 0 opaque, 1 constant, 2 opacity map, 3 base colour's alpha
  uint8_t vertexColors = 0;  // 1: base colour and opacity times the mesh's vertex colour (RenderMaterial::vertexColors)

  static constexpr int kCount = 3 * 2 * 3 * 3 * 2 * 4 * 2;
  // A dense index in [0, kCount), for a per-frame table of programs.
  int index() const {
    return (((((projection * 2 + baseMap) * 3 + roughnessMap) * 3 + metallicMap) * 2 + normalMap) * 4 + opacity) * 2 +
           vertexColors;
  }
  void appendDefines(std::string& out) const {
    auto define = [&](const char* name, int value) {
      out += "#define ";
      out += name;
      out += ' ';
      out += char('0' + value);
      out += '\n';
    };
    define("PROJECTION", projection);
    define("BASE_MAP", baseMap);
    define("ROUGHNESS_MAP", roughnessMap);
    define("METALLIC_MAP", metallicMap);
    define("NORMAL_MAP", normalMap);
    define("OPACITY", opacity);
    define("VERTEX_COLORS", vertexColors);
  }

  // The variant for a part whose maps are `maps`: a separate roughness or
  // metallic map wins over the ORM map, as in OmniPBR when both are set.
  static ShadingVariant of(const MaterialMaps& maps, bool triplanar, OpacitySource opacity) {
    ShadingVariant v;
    v.projection = triplanar ? 2 : 1;
    v.baseMap = maps.baseColor.empty() ? 0 : 1;
    v.roughnessMap = !maps.roughness.empty() ? 1 : !maps.orm.empty() ? 2 : 0;
    v.metallicMap = !maps.metallic.empty() ? 1 : !maps.orm.empty() ? 2 : 0;
    v.normalMap = (!maps.normal.empty() && !triplanar) ? 1 : 0;
    v.opacity = uint8_t(opacity);
    if (opacity == OpacitySource::BaseColorAlpha && maps.baseColor.empty()) v.opacity = uint8_t(OpacitySource::Constant);
    if (opacity == OpacitySource::OpacityMap && maps.opacity.empty()) v.opacity = uint8_t(OpacitySource::Constant);
    return v;
  }
};

}  // namespace sdg
