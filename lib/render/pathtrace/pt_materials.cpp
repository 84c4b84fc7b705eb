#include "render/pathtrace/pt_materials.h"

#include <algorithm>
#include <cmath>

namespace sdg {
namespace {

Vec2f transformUv(const SurfaceMaterial& m, const Vec2f& uv) {
  const Vec2f s = uv.cwiseProduct(m.textureScale);
  return {m.cosRotate * s.x() - m.sinRotate * s.y(), m.sinRotate * s.x() + m.cosRotate * s.y()};
}

// A map at the point: through the uvs, or three world-plane projections
// blended by the normal's components (the rasterizer's sampleMap()).
Eigen::Vector4f sampleMap(const SurfaceMaterial& m, const PtTexture& map, const SurfaceGeometry& g, const Vec3f& n) {
  if (!m.triplanar) return map.sample(transformUv(m, g.uv));
  Vec3f w = n.cwiseAbs();
  w /= (w.x() + w.y() + w.z());
  const Vec3f& p = g.position;
  return map.sample(transformUv(m, {p.y(), p.z()})) * w.x() + map.sample(transformUv(m, {p.x(), p.z()})) * w.y() +
         map.sample(transformUv(m, {p.x(), p.y()})) * w.z();
}

// The tangent-space normal map applied around n. The frame is Schueler's
// (2013): T and B proportional to the surface gradients of the
// (transformed) u and v, computed from the triangle's edges instead of
// screen derivatives (the formula is the same up to a factor that the
// shared normalisation removes; its sign is the triangle's winding seen
// from n), both divided by the longer of the two.
Vec3f mappedNormal(const SurfaceMaterial& m, const SurfaceGeometry& g, const Vec3f& n) {
  const Vec2f duv1 = transformUv(m, g.uvEdge1), duv2 = transformUv(m, g.uvEdge2);
  const Vec3f perp2 = g.edge2.cross(n), perp1 = n.cross(g.edge1);
  Vec3f t = perp2 * duv1.x() + perp1 * duv2.x();
  Vec3f b = perp2 * duv1.y() + perp1 * duv2.y();
  if (n.dot(g.edge1.cross(g.edge2)) < 0.0f) {
    t = -t;
    b = -b;
  }
  const float longest2 = std::max(t.squaredNorm(), b.squaredNorm());
  const float scale = 1.0f / std::sqrt(std::max(longest2, 1e-20f));
  const Eigen::Vector4f texel = m.normalMap->sample(transformUv(m, g.uv));
  const Vec3f tilt(m.normalScale * (2.0f * texel.x() - 1.0f), m.normalScale * (2.0f * texel.y() - 1.0f),
                   2.0f * texel.z() - 1.0f);
  // +Y is the image's top, where v decreases.
  const Vec3f mapped = t * (scale * tilt.x()) - b * (scale * tilt.y()) + n * tilt.z();
  const float length2 = mapped.squaredNorm();
  return length2 > 1e-12f && std::isfinite(length2) ? Vec3f(mapped / std::sqrt(length2)) : n;
}

}  // namespace

SurfaceMaterial resolveSurfaceMaterial(const RenderItem& item, const MeshPart& part, PtTextureCache& textures) {
  const RenderMaterial& prim = item.material;
  SurfaceMaterial m;
  m.partMaterial = !prim.fromPrim && part.hasMaterial;
  const MaterialMaps& maps = m.partMaterial ? part.maps : prim.maps;
  const std::string& path = item.primPath;
  if (m.partMaterial) {
    m.baseColor = part.baseColor;
    m.roughness = part.roughness;
    m.metallic = part.metallic;
    m.roughnessInfluence = m.metallicInfluence = 1.0f;
    m.opacity = part.opacity;
    m.opacityConstant = part.opacityConstant;
    m.opacityCutoff = part.opacityCutoff;
    m.normalScale = part.normalScale;
    m.vertexColors = part.vertexColors;
  } else {
    m.baseColor = prim.baseColor;
    m.roughness = prim.roughness;
    m.metallic = prim.metallic;
    m.roughnessInfluence = prim.roughnessInfluence;
    m.metallicInfluence = prim.metallicInfluence;
    m.opacity = prim.opacity;
    m.opacityConstant = prim.opacityConstant;
    m.opacityCutoff = prim.opacityCutoff;
    m.normalScale = prim.normalScale;
    m.specularLevel = prim.specularLevel;
    m.triplanar = prim.projectUvw;
    m.vertexColors = prim.vertexColors;
  }
  // The texture placement is the prim's in both cases (it travels per instance).
  m.textureScale = prim.textureScale;
  const double radians = double(prim.textureRotate) * M_PI / 180.0;
  m.cosRotate = float(std::cos(radians));
  m.sinRotate = float(std::sin(radians));
  m.baseMap = textures.get(maps.baseColor, TextureData::Color, path);
  // A separate roughness or metallic map wins over the ORM map.
  if (!maps.roughness.empty()) m.roughnessMap = textures.get(maps.roughness, TextureData::Linear, path);
  else if (!maps.orm.empty()) {
    m.roughnessMap = textures.get(maps.orm, TextureData::Linear, path);
    m.roughnessChannel = 1;
  }
  if (!maps.metallic.empty()) m.metallicMap = textures.get(maps.metallic, TextureData::Linear, path);
  else if (!maps.orm.empty()) {
    m.metallicMap = textures.get(maps.orm, TextureData::Linear, path);
    m.metallicChannel = 2;
  }
  if (!m.triplanar) m.normalMap = textures.get(maps.normal, TextureData::Linear, path);  // none under project_uvw
  if (m.opacity == OpacitySource::OpacityMap) m.opacityMap = textures.get(maps.opacity, TextureData::Linear, path);
  // The rasterizer's fallbacks (ShadingVariant::of): a named source
  // without its map is the constant alone.
  if (m.opacity == OpacitySource::BaseColorAlpha && !m.baseMap) m.opacity = OpacitySource::Constant;
  if (m.opacity == OpacitySource::OpacityMap && !m.opacityMap) m.opacity = OpacitySource::Constant;
  return m;
}

bool surfaceOpaque(const SurfaceMaterial& m, const SurfaceGeometry& g) {
  float opacity = m.opacityConstant;
  switch (m.opacity) {
    case OpacitySource::None: return true;
    case OpacitySource::Constant: break;
    case OpacitySource::OpacityMap: opacity *= sampleMap(m, *m.opacityMap, g, g.shadingNormal).x(); break;
    case OpacitySource::BaseColorAlpha: opacity *= sampleMap(m, *m.baseMap, g, g.shadingNormal).w(); break;
  }
  if (m.vertexColors) opacity *= g.color.w();
  return opacity >= m.opacityCutoff;
}

ShadedSurface shadeSurface(const SurfaceMaterial& m, const SurfaceGeometry& g, const Vec3f& towardViewer) {
  // Every face is seen from either side, as in the rasterizer (which culls
  // nothing): the interpolated normal turns toward the viewer.
  Vec3f n = g.shadingNormal.dot(towardViewer) < 0.0f ? Vec3f(-g.shadingNormal) : g.shadingNormal;
  float roughness = m.roughness, metallic = m.metallic;
  if (m.roughnessMap) {
    const float map = sampleMap(m, *m.roughnessMap, g, n)[m.roughnessChannel];
    roughness = m.partMaterial ? roughness * map : roughness + (map - roughness) * m.roughnessInfluence;
  }
  if (m.metallicMap) {
    const float map = sampleMap(m, *m.metallicMap, g, n)[m.metallicChannel];
    metallic = m.partMaterial ? metallic * map : metallic + (map - metallic) * m.metallicInfluence;
  }
  ShadedSurface s;
  s.albedo = m.baseMap ? Vec3f(sampleMap(m, *m.baseMap, g, n).head<3>()) : m.baseColor;
  if (m.vertexColors) s.albedo = s.albedo.cwiseProduct(g.color.head<3>());
  s.material.baseColor = s.albedo;
  s.material.roughness = std::clamp(roughness, 0.0f, 1.0f);
  s.material.metallic = std::clamp(metallic, 0.0f, 1.0f);
  s.material.specularLevel = m.specularLevel;
  if (m.normalMap) n = mappedNormal(m, g, n);
  // A mapped (or strongly interpolated) normal can turn away from the
  // viewer, where the BSDF is black: tip it back until the viewer is just
  // above its horizon.
  constexpr float kMinCosine = 0.01f;
  const float c = n.dot(towardViewer);
  if (c < kMinCosine) n = (n + (kMinCosine - c) * towardViewer).normalized();
  s.normal = n;
  return s;
}

}  // namespace sdg
