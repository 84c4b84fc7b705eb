#pragma once
// Typed reading of YAML nodes against an AttributeSpec, with located messages
// that say what was expected and what was found.
#include <optional>
#include <string>
#include <string_view>

#include "core/diagnostics.h"
#include "scene_io/raw_node.h"
#include "stage/value.h"

namespace sdg {

// Reads `node` as a value of `spec.type`, checking shape, length, finiteness,
// range, the spec's minimum and allowed tokens. `what` names the thing being
// read in messages (e.g. "/Root/Camera.focalLength"). On failure it reports
// to `diag` and returns nullopt.
std::optional<Value> readValue(const RawNode& node, const AttributeSpec& spec, std::string_view what,
                               Diagnostics& diag);
std::optional<Value> readValue(const RawNode& node, ValueType type, std::string_view what, Diagnostics& diag);

// Scalars for structural keys.
std::optional<std::string> readString(const RawNode& node, std::string_view what, Diagnostics& diag);
std::optional<double> readNumber(const RawNode& node, std::string_view what, Diagnostics& diag);

}  // namespace sdg
