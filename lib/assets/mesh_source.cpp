#include "assets/mesh_source.h"

#include "assets/mesh_loader.h"
#include "assets/primitives.h"
#include "core/diagnostics.h"
#include "core/text.h"

namespace sdg {
namespace {

char axisOf(const Prim& prim) { return prim.getString("axis")[0]; }

}  // namespace

MeshKey meshKeyOf(const Prim& prim, int subdivisionLevel) {
  MeshKey key;
  key.shape = prim.type();
  switch (prim.type()) {
    case PrimType::Mesh:
      key.asset = prim.getString("asset");
      key.submesh = prim.getString("submesh");
      if (key.asset.empty()) key.inlineMesh = inlineMeshOf(prim, subdivisionLevel);
      break;
    case PrimType::Cube: key.a = prim.getDouble("size"); break;
    case PrimType::Sphere: key.a = prim.getDouble("radius"); break;
    case PrimType::Cylinder:
    case PrimType::Cone:
    case PrimType::Capsule:
      key.a = prim.getDouble("radius");
      key.b = prim.getDouble("height");
      key.axis = axisOf(prim);
      break;
    case PrimType::Plane:
      key.b = prim.getDouble("width");
      key.c = prim.getDouble("length");
      key.axis = axisOf(prim);
      break;
    default: break;
  }
  return key;
}

std::string MeshKey::id() const {
  std::string key(primTypeInfo(shape).name);
  if (inlineMesh) return key + ":" + inlineMesh->id();
  if (shape == PrimType::Mesh) return key + ":" + asset + "#" + submesh;
  return key + ":" + text::formatDouble(a) + ":" + text::formatDouble(b) + ":" + text::formatDouble(c) + ":" + axis;
}

MeshData meshDataFor(const MeshKey& key, const AssetResolver& assets, const std::string& primPath) {
  switch (key.shape) {
    case PrimType::Cube: return makeCube(key.a);
    case PrimType::Sphere: return makeSphere(key.a);
    case PrimType::Cylinder: return makeCylinder(key.a, key.b, key.axis);
    case PrimType::Cone: return makeCone(key.a, key.b, key.axis);
    case PrimType::Capsule: return makeCapsule(key.a, key.b, key.axis);
    case PrimType::Plane: return makePlane(key.b, key.c, key.axis);
    default: break;
  }
  if (key.inlineMesh) return triangulateInlineMesh(*key.inlineMesh, primPath);
  std::optional<std::string> path = assets.resolve(key.asset);
  if (!path) throw RunError(primPath + ": mesh '" + key.asset + "' not found; " + assets.describeSearch(key.asset));
  try {
    return loadMeshFile(*path, key.submesh);
  } catch (const RunError& e) {
    throw RunError(primPath + ": " + e.what());
  }
}

}  // namespace sdg
