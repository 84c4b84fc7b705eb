// USD's primvars:displayColor and primvars:displayOpacity onto the stage.
// A constant one (one item, or interpolation "constant") is the gprim's
// primvars:displayColor / primvars:displayOpacity; any other interpolation
// is a Mesh's primvars:displayColor:faceVarying /
// primvars:displayOpacity:faceVarying, expanded per face-vertex by
// usd_geometry.cpp like normals and uvs. Other gprims (Cube, Sphere, ...)
// are generated here, not read: they keep the first item, with a warning.
#include "scene_io/usd_import_internal.h"
#include "scene_io/usd_mesh_topology.h"

namespace sdg::usd_map {
namespace {

size_t widthOf(const std::string& name) { return name == "primvars:displayColor" ? 3 : 1; }

// The elements of the primvar: its indices when indexed, else its items.
size_t elementCount(const usd::ComposedPrim& prim, const usd::ComposedProperty& p) {
  if (const usd::ComposedProperty* ix = prim.property(p.name + ":indices"); ix && !ix->value.empty())
    return ix->value.numbers.size();
  return p.value.numbers.size() / widthOf(p.name);
}

}  // namespace

bool isDisplayPrimvar(const std::string& name) {
  return name == "primvars:displayColor" || name == "primvars:displayOpacity";
}

bool isVaryingDisplayPrimvar(const usd::ComposedPrim& prim, const usd::ComposedProperty& p) {
  if (!isDisplayPrimvar(p.name) || p.value.empty()) return false;
  const std::string interpolation = primvarInterpolation(p);
  if (!interpolation.empty()) return interpolation != "constant";
  return elementCount(prim, p) > 1;
}

std::optional<std::string> displayPrimvarInterpolation(const usd::ComposedPrim& mesh, const usd::ComposedProperty& p,
                                                       size_t faces, size_t points, size_t corners, Diagnostics& diag) {
  if (std::string authored = primvarInterpolation(p); !authored.empty()) return authored;
  // Unauthored means constant in USD, but files written without it by
  // other tools hold one item per point, face-vertex or face: the count
  // says which (points first, as USD's own fallback for geometry).
  const size_t n = elementCount(mesh, p);
  if (n == points) return "vertex";
  if (n == corners) return "faceVarying";
  if (n == faces) return "uniform";
  diag.error(p.loc, mesh.path + "." + p.name + ": " + std::to_string(n) + " items and no interpolation; expected one per point (" +
                        std::to_string(points) + "), face-vertex (" + std::to_string(corners) + ") or face (" +
                        std::to_string(faces) + "), or an authored interpolation");
  return std::nullopt;
}

bool importDisplayPrimvar(const usd::ComposedPrim& prim, const usd::ComposedProperty& p, PrimType type, Prim& stagePrim,
                          Diagnostics& diag) {
  if (!isDisplayPrimvar(p.name) || !primTypeInfo(type).gprim) return false;
  const size_t width = widthOf(p.name);
  const std::vector<double>& values = p.value.numbers;
  if (!usd::isNumeric(p.value.kind) || size_t(usd::componentCount(p.value.kind)) != width || values.size() < width) {
    diag.error(p.loc, prim.path + "." + p.name + ": expected " +
                          (width == 3 ? "color3f[] (lists of 3 numbers r, g, b)" : "float[] (numbers)") + ", found " +
                          p.typeName);
    return true;
  }
  const bool varying = isVaryingDisplayPrimvar(prim, p);
  if (varying && type == PrimType::Mesh) return true;  // per face-vertex: usd_geometry.cpp
  if (varying)
    diag.warning(p.loc, prim.path + "." + p.name + ": a " + std::string(primTypeInfo(type).name) +
                            " is generated, not read, so its " + primvarInterpolation(p) +
                            " colours cannot follow its faces; drawn with the first item");
  // The first element: through the indices when indexed (an empty index
  // list is no indexing, as in USD).
  size_t item = 0;
  const usd::ComposedProperty* ix = prim.property(p.name + ":indices");
  if (ix && !ix->value.empty() && (!usd::isNumeric(ix->value.kind) || usd::componentCount(ix->value.kind) != 1)) {
    diag.error(ix->loc, prim.path + "." + p.name + ":indices: expected int[], found " + ix->typeName);
    return true;
  }
  if (ix && !ix->value.numbers.empty()) {
    const double first = ix->value.numbers[0];
    if (first < 0 || first * double(width) >= double(values.size())) {
      diag.error(ix->loc, prim.path + "." + p.name + ":indices: " + std::to_string(int64_t(first)) +
                              " is outside the " + std::to_string(values.size() / width) + " values");
      return true;
    }
    item = size_t(first);
  }
  const double* v = &values[item * width];
  Value value = width == 3 ? Value::makeColor3f(Vec3f(float(v[0]), float(v[1]), float(v[2]))) : Value::makeFloat(float(v[0]));
  stagePrim.setAttribute(p.name, std::move(value)).loc = p.loc;
  return true;
}

}  // namespace sdg::usd_map
