#include "behavior/behavior_prims.h"

#include <cstdio>

#include "stage/path.h"

namespace sdg {

std::string nextFreePath(const Stage& stage, const std::string& path) {
  if (!stage.find(path)) return path;
  for (int i = 1;; ++i) {
    char suffix[16];
    std::snprintf(suffix, sizeof suffix, "_%02d", i);
    std::string candidate = path + suffix;
    if (!stage.find(candidate)) return candidate;
  }
}

Prim& ensureScope(Stage& stage, const std::string& primPath) {
  if (Prim* existing = stage.find(primPath)) return *existing;
  std::string parent(path::parent(primPath));
  if (parent != "/") ensureScope(stage, parent);
  return stage.definePrim(primPath, PrimType::Scope);
}

void removeEmptyScopes(Stage& stage, const std::string& root) {
  Prim* prim = stage.find(root);
  if (!prim) return;
  std::vector<std::string> children;
  for (const Prim* c : prim->children()) children.push_back(c->path());
  for (const std::string& c : children) removeEmptyScopes(stage, c);
  if (prim->type() == PrimType::Scope && prim->children().empty() && prim->attributes().empty())
    stage.removePrim(root);
}

}  // namespace sdg
