#include "behavior/behavior.h"

#include <stdexcept>

#include "core/log.h"

namespace sdg {

void Behavior::bind(Prim& prim, const BehaviorSpec& spec, BehaviorContext& context) {
  primPath_ = prim.path();
  spec_ = &spec;
  context_ = &context;
}

Prim& Behavior::prim() const {
  Prim* p = context_->stage->find(primPath_);
  if (!p) throw std::logic_error(spec_->name + ": its prim " + primPath_ + " was removed");
  return *p;
}

std::string Behavior::attributeName(std::string_view name) const { return exposedAttributeName(spec_->name, name); }

const Value& Behavior::variable(std::string_view name) const {
  const Value* v = prim().value(attributeName(name));
  if (!v) throw std::logic_error(primPath_ + ": exposed variable " + attributeName(name) + " is missing");
  return *v;
}

Rng Behavior::makeRng(int32_t fixedSeed) const {
  return makeBehaviorRng(context_->runSeed, primPath_, spec_->name, context_->iteration, fixedSeed);
}

std::vector<Prim*> Behavior::selectPrims(bool includeChildren, const std::function<bool(const Prim&)>& accept) const {
  std::vector<Prim*> candidates = includeChildren ? stage().subtree(prim()) : std::vector<Prim*>{&prim()};
  std::vector<Prim*> selected;
  for (Prim* p : candidates)
    if (accept(*p)) selected.push_back(p);
  return selected;
}

std::string Behavior::xformableTarget(std::string_view name, std::string_view fallbackNote) const {
  const std::string& target = var<std::string>(name);
  if (target.empty()) return {};
  const Prim* t = stage().find(target);
  if (t && t->typeInfo().xformable) return target;
  log::warn(primPath_ + ": " + spec_->name + ": invalid target prim path " + target + "; " + std::string(fallbackNote));
  return {};
}

bool Behavior::addressedToMe(const Payload& payload) const {
  std::string_view target = payload.getString("prim_path");
  return target.empty() || target == primPath_;
}

}  // namespace sdg
