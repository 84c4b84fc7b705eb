#include "stage/stage_diff.h"

namespace sdg {
namespace {

void diffPrim(const Prim& a, const Prim& b, std::vector<StageChange>& out) {
  for (const auto& [name, attr] : b.attributes()) {
    const Attribute* old = a.findAttribute(name);
    if (!old || !(old->value == attr.value)) out.push_back({b.path(), name, attr.value});
  }
  for (const auto& [name, attr] : a.attributes())
    if (!b.findAttribute(name)) out.push_back({b.path(), name, std::nullopt});
  for (const XformOp& op : b.xformOps()) {
    const XformOp* old = nullptr;
    for (const XformOp& o : a.xformOps())
      if (o.kind == op.kind && o.suffix == op.suffix) old = &o;
    if (!old || !(old->value == op.value)) out.push_back({b.path(), op.attributeName(), op.value});
  }
  for (const XformOp& op : a.xformOps()) {
    bool kept = false;
    for (const XformOp& o : b.xformOps()) kept = kept || (o.kind == op.kind && o.suffix == op.suffix);
    if (!kept) out.push_back({b.path(), op.attributeName(), std::nullopt});
  }
  if (a.material() != b.material())
    out.push_back({b.path(), "material:binding",
                   b.material() ? std::optional<Value>(Value::makeString(b.material()->path)) : std::nullopt});
}

}  // namespace

std::vector<StageChange> diffStages(const Stage& before, const Stage& after) {
  std::vector<StageChange> out;
  after.traverse([&](const Prim& p) {
    const Prim* old = before.find(p.path());
    if (!old || old->type() != p.type()) {
      out.push_back({p.path(), "prim", Value::makeToken(std::string(p.typeInfo().name))});
      if (old) return;
      Prim blank(p.path(), p.type(), nullptr);
      diffPrim(blank, p, out);
      return;
    }
    diffPrim(*old, p, out);
  });
  before.traverse([&](const Prim& p) {
    if (!after.find(p.path())) out.push_back({p.path(), "prim", std::nullopt});
  });
  return out;
}

}  // namespace sdg
