#pragma once
// `sdgbehave describe [NAME]`: the behaviors and their exposed variables,
// from the same specs that create the attributes and feed the JSON Schema.
#include <string>

#include "behavior/registry.h"

namespace sdg {

std::string describeBehaviors(const BehaviorRegistry& registry);
// One behavior in full; "" when there is no behavior of that name.
std::string describeBehavior(const BehaviorRegistry& registry, std::string_view name);
// `describe --format json`: every behavior (or only `name`, when given and
// known) with its variables' type, default, doc and bounds, for tools and
// editors. Empty when `name` is given and unknown.
std::string describeBehaviorsJson(const BehaviorRegistry& registry, std::string_view name = {});

}  // namespace sdg
