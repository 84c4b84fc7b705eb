#pragma once
// What the rasterizer's source files share and nothing else needs: the
// program helpers, uniform locations, the GPU mesh record and texture units.
#include <initializer_list>
#include <string>
#include <vector>

#include "render/frame_passes.h"
#include "render/raster/gl_api.h"
#include "render/raster/renderer.h"

namespace sdg::raster_detail {

// A shader from several source strings; throws RunError with GL's log.
unsigned compile(const GlApi& gl, GLenum type, std::initializer_list<const char*> sources);
// Vertex shaders are one string; fragment shaders get the shared header,
// `defines` and the common functions first.
unsigned link(const GlApi& gl, const char* vertex, const char* fragmentBody, bool common = true, const char* defines = "");
Eigen::Matrix4f toFloat(const Matrix4d& m);
void setMatrix(const GlApi& gl, int location, const Matrix4d& m);

// Whether a frame reads back colour attachment `attachment` (0 colour,
// 1 normals and distance, 2 image-plane distance, 3 instance ids).
inline bool wanted(int attachment, const PassSelection& passes) {
  return attachment == 0 || (attachment == 1 && passes.normals) || (attachment == 2 && passes.imagePlane) ||
         (attachment == 3 && passes.ids);
}

// Texture units of the scene and sky programs.
enum TextureUnit : int {
  kBaseUnit = 0, kDomeSpecularUnit = 1, kShadowUnit = 2, kRoughnessUnit = 3, kMetallicUnit = 4, kOrmUnit = 5,
  kNormalUnit = 6, kOpacityUnit = 7, kDomeIrradianceUnit = 8, kBrdfLutUnit = 9, kDomeBackgroundUnit = 10,
};

// Domes whose pre-filtered textures stay on the GPU; a randomizer cycling
// through more maps than this reloads the oldest.
constexpr size_t kMaxCachedDomes = 8;

}  // namespace sdg::raster_detail

namespace sdg {

#define SDG_SCENE_UNIFORMS(X) X(uAmbient) X(uAmbientSpecular) X(uBrdfLut) X(uCameraForward) X(uCameraPosition) X(uDome) X(uDomeBackground) X(uDomeFromWorld) X(uDomeIrradiance) X(uDomeLod) X(uDomeResponse) X(uDomeScale) X(uExposureScale) X(uLightDirection) X(uLightParams) X(uLightPosition) X(uLightRadiance) X(uLightResponse) X(uMetallicMap) X(uMetersPerUnit) X(uNormalMap) X(uNormalScale) X(uOpacityConstant) X(uOpacityCutoff) X(uOpacityMap) X(uOrmMap) X(uPartBaseColor) X(uPartSurface) X(uRoughnessMap) X(uShadowAtlas) X(uShadowMatrix) X(uShadowTexel) X(uSpecularLevel) X(uTexture) X(uUsePartMaterial) X(uViewProjection) X(uWorldFromClip)

// Uniform locations, looked up once per program instead of per draw (the
// sky program uses a few of the same names; the rest stay -1 for it).
struct Renderer::Uniforms {
#define SDG_UNIFORM_FIELD(name) int name = -1;
  SDG_SCENE_UNIFORMS(SDG_UNIFORM_FIELD)
#undef SDG_UNIFORM_FIELD
};

struct Renderer::GpuMesh {
  uint32_t slot = 0;  // index in meshBySlot_
  unsigned vao = 0;
  unsigned buffers[4] = {0, 0, 0, 0};
  unsigned colorBuffer = 0;  // attribute 14, only for a mesh with MeshData::colors
  std::vector<MeshPart> parts;
  Eigen::AlignedBox3f bounds;
};

}  // namespace sdg
