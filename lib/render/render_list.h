#pragma once
// A plain per-frame description of what to draw, built from a read-only
// stage: cameras, geometry with world transforms, materials and instance ids,
// and lights. The GL code consumes only this; it never sees the stage, so
// the list can be inspected in tests without a GL context.
#include <cstdint>
#include <string>
#include <vector>

#include "assets/mesh_data.h"
#include "assets/mesh_source.h"
#include "render/lens_model.h"
#include "stage/stage.h"

namespace sdg {

struct RenderCamera {
  std::string path;
  Matrix4d worldFromCamera = Matrix4d::Identity();  // scale removed
  float focalLength = 50.0f;
  float horizontalAperture = 20.955f;
  float verticalAperture = 15.2908f;
  float horizontalApertureOffset = 0.0f;
  float verticalApertureOffset = 0.0f;
  float nearClip = 1.0f;
  float farClip = 1e6f;
  bool orthographic = false;
  float focusDistance = 0.0f;
  float fStop = 0.0f;
  // A calibrated lens (omni:lensdistortion:*): when set, it replaces
  // focalLength and the apertures for projection.
  LensModel lens;
};


// The OmniPBR-like material both renderers shade with (docs/rendering.md,
// "Materials"). A prim's bound Material fills it; without one, displayColor
// and the mesh file's own materials (MeshPart) apply.
struct RenderMaterial {
  bool fromPrim = false;  // a Material prim is bound; otherwise the mesh file's or displayColor
  Vec3f baseColor{0.5f, 0.5f, 0.5f};
  MaterialMaps maps;      // as written in the scene; "" for none
  Vec2f textureScale{1.0f, 1.0f};
  float textureRotate = 0.0f;  // degrees
  bool projectUvw = false;
  float roughness = 0.5f;
  float metallic = 0.0f;
  // OmniPBR's map influences: value = mix(constant, map, influence).
  float roughnessInfluence = 0.0f;
  float metallicInfluence = 0.0f;
  float normalScale = 1.0f;  // bump_factor
  float specularLevel = 0.5f;  // a dielectric's F0 = 0.08 level, F90 = 2 level
  OpacitySource opacity = OpacitySource::None;
  float opacityConstant = 1.0f;
  float opacityCutoff = 0.5f;  // drawn where opacity >= this
  // No material bound and the mesh has per-vertex colours
  // (MeshData::colors): the base colour and the opacity constant are
  // multiplied by the interpolated vertex colour and opacity (baseColor is
  // then white, so the vertex colour replaces displayColor as in USD).
  bool vertexColors = false;
  bool cutOut() const { return opacity != OpacitySource::None; }
};

struct RenderItem {
  std::string primPath;
  MeshKey mesh;
  std::string meshId;  // mesh.id(), computed once when the list is built
  Matrix4d worldFromLocal = Matrix4d::Identity();
  RenderMaterial material;
  uint32_t instanceId = 0;  // 1-based, in stage order; 0 is background
  bool doubleSided = false;
};

enum class LightKind { Distant, Sphere, Rect, Disk, Cylinder, Dome };

struct RenderLight {
  std::string path;
  LightKind kind = LightKind::Distant;
  // intensity * 2^exposure * color; with inputs:normalize, divided by the
  // emitting area (rect, disk, sphere, cylinder), so resizing keeps the power.
  Vec3f radiance{1, 1, 1};
  Vec3d position = Vec3d::Zero();
  Vec3d direction = -Vec3d::UnitZ();  // the light's local -Z in world space
  // A dome's frame in the world: its texture's pole (+Y in the lat-long
  // convention, render/latlong.h) turned to the stage's up axis, then the
  // prim's rotation.
  Matrix3d worldRotation = Matrix3d::Identity();
  float radius = 0.0f;  // sphere, disk, cylinder
  float width = 0.0f, height = 0.0f, length = 0.0f;
  float angle = 0.0f;   // distant: angular diameter (degrees)
  // inputs:diffuse and inputs:specular: multipliers of the light's diffuse
  // and specular response (applied per lobe by both renderers).
  float diffuse = 1.0f, specular = 1.0f;
  bool treatAsPoint = false;  // sphere: a point of the same power (hard shadows)
  std::string texture;  // dome
};

struct RenderList {
  std::vector<RenderCamera> cameras;
  std::vector<RenderItem> items;
  std::vector<RenderLight> lights;
  double metersPerUnit = 1.0;
};

RenderList buildRenderList(const Stage& stage);
// Whether a camera of the list has a calibrated lens.
bool anyCalibratedLens(const RenderList& list);
// The material bound to a prim: the closest binding above it, unless an
// ancestor binds strongerThanDescendants (then the highest such one wins).
const Prim* boundMaterial(const Stage& stage, const Prim& prim);

}  // namespace sdg
