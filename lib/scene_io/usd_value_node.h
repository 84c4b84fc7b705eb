#pragma once
// USD attribute values read against sdgbehave's AttributeSpecs with the
// YAML loader's checks (shape, finiteness, range, minimum, allowed tokens):
// the composed value is turned into the plain node the YAML reader would
// have built, located at the USD opinion, and read by value_reader. One set
// of checks, so a value is accepted from a .usda exactly when it would be
// accepted from a scene YAML.
#include <optional>
#include <string>
#include <string_view>

#include "core/diagnostics.h"
#include "scene_io/raw_node.h"
#include "stage/value.h"
#include "usd/compose.h"

namespace sdg {

// A scalar node at `loc` (quoted: a string, never a number or bool).
RawNode scalarNode(std::string text, bool quoted, const SourceLoc& loc);

// The value of `property` as a node at property.loc: numbers as plain
// scalars, text as quoted scalars, vectors and arrays as sequences. Asset
// values are the paths resolved against the layer that wrote them
// (resolvedAssets), made absolute so that they name the same file from the
// scene's folder as from the working directory. An empty (unauthored or blocked) value is a null node.
RawNode usdValueAsNode(const usd::ComposedProperty& property);

// The property's value read as `spec` says; problems go to `diag` at the
// property's file:line:col, naming `what`.
std::optional<Value> readUsdValue(const usd::ComposedProperty& property, const AttributeSpec& spec,
                                  std::string_view what, Diagnostics& diag);
std::optional<Value> readUsdValue(const usd::ComposedProperty& property, ValueType type, std::string_view what,
                                  Diagnostics& diag);

}  // namespace sdg
