#pragma once
// Surface inputs for the path tracer, combined exactly as the rasterizer's
// scene shader combines them (render/shaders.h and docs/rendering.md,
// "Shading and materials"), so both renderers shade one material alike:
// - the prim's bound material wins; else the mesh file's part material;
//   else displayColor (render_list.cpp fills RenderMaterial that way);
// - a base colour map replaces the constant (sRGB, its alpha linear);
// - roughness / metallic: a prim material's value = mix(constant, map,
//   influence) (OmniPBR), a part's = factor * map (glTF); a separate map
//   wins over the ORM map (green roughness, blue metallic);
// - every map is placed by the prim's texture_scale and texture_rotate,
//   through the mesh's uvs or, with project_uvw, world-space triplanar
//   blended by the normal;
// - normal maps (uv-mapped only): tangent space with +X along increasing u
//   and +Y toward the image's top (decreasing v), the tilt scaled by
//   bump_factor, the frame from the uvs' gradients on the surface
//   (Schueler 2013, as the rasterizer's screen-space version computes it);
// - cut-outs: clear where opacity_constant x (the opacity map's red, or
//   the base colour's alpha) < the cut-off;
// - vertex colours (RenderMaterial::vertexColors): the base colour times
//   the interpolated vertex colour, the opacity times its alpha.
#include "render/pathtrace/bsdf.h"
#include "render/pathtrace/embree_scene.h"
#include "render/pathtrace/pt_textures.h"
#include "render/render_list.h"

namespace sdg {

// One render item's material for one mesh part, with its textures found.
struct SurfaceMaterial {
  bool partMaterial = false;  // the mesh file's material (glTF factors) rather than the prim's
  Vec3f baseColor{0.5f, 0.5f, 0.5f};
  float roughness = 0.5f, metallic = 0.0f;
  float roughnessInfluence = 0.0f, metallicInfluence = 0.0f;
  const PtTexture* baseMap = nullptr;
  const PtTexture* roughnessMap = nullptr;
  const PtTexture* metallicMap = nullptr;
  const PtTexture* normalMap = nullptr;
  const PtTexture* opacityMap = nullptr;
  int roughnessChannel = 0, metallicChannel = 0;  // 0 red, 1 green, 2 blue
  OpacitySource opacity = OpacitySource::None;    // after the rasterizer's fallbacks
  float opacityConstant = 1.0f, opacityCutoff = 0.5f;
  float normalScale = 1.0f;
  float specularLevel = 0.5f;  // OmniPBR's; a mesh file's part material keeps the default, as in the rasterizer
  bool triplanar = false;
  bool vertexColors = false;  // base colour and opacity times SurfaceGeometry::color
  Vec2f textureScale{1.0f, 1.0f};
  float cosRotate = 1.0f, sinRotate = 0.0f;

  bool cutOut() const { return opacity != OpacitySource::None; }
};

// Resolves (and loads) what `item` shades `part` with.
SurfaceMaterial resolveSurfaceMaterial(const RenderItem& item, const MeshPart& part, PtTextureCache& textures);

// A shading point: the BSDF's inputs, and the normal they live around.
struct ShadedSurface {
  PbrMaterial material;
  Vec3f normal;  // the shading normal (normal map applied), on the side of `towardViewer`
  Vec3f albedo;  // the base colour, for the denoiser
};

// `towardViewer`: unit, from the point back along the incoming ray.
ShadedSurface shadeSurface(const SurfaceMaterial& m, const SurfaceGeometry& g, const Vec3f& towardViewer);
// False where a cut-out is clear at this point.
bool surfaceOpaque(const SurfaceMaterial& m, const SurfaceGeometry& g);

}  // namespace sdg
