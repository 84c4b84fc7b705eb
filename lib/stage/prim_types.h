#pragma once
// The closed set of prim types and their schema attributes (USD names and
// USD fallback values). Attributes a prim does not author read as these
// fallbacks, as in USD.
#include <optional>
#include <span>
#include <string_view>
#include <vector>

#include "stage/value.h"

namespace sdg {

enum class PrimType {
  Xform, Scope, Mesh, Cube, Sphere, Cylinder, Cone, Capsule, Plane, Camera,
  DistantLight, SphereLight, RectLight, DiskLight, CylinderLight, DomeLight, Material, Lidar,
};

struct PrimTypeInfo {
  PrimType type;
  std::string_view name;
  bool xformable;  // UsdGeom.Xformable: carries xform ops
  bool gprim;      // renderable geometry (UsdGeom.Gprim)
  bool light;      // has UsdLux.LightAPI
  std::string_view doc;
  std::vector<AttributeSpec> attributes;  // schema attributes with fallbacks
};

std::span<const PrimTypeInfo> allPrimTypes();
const PrimTypeInfo& primTypeInfo(PrimType type);
std::optional<PrimType> primTypeFromName(std::string_view name);
// The schema attribute `name` of `type`, or nullptr.
const AttributeSpec* findSchemaAttribute(PrimType type, std::string_view name);

}  // namespace sdg
