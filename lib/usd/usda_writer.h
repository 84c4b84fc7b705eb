#pragma once
// Writing a Layer as usda text, the inverse of readUsdaLayer: a crate
// layer (or any other) can be looked at, diffed and edited as text.
// Deterministic: fields in name order, children and properties in the
// order their parent lists them (primChildren, properties,
// variantSetChildren), unlisted ones after in path order; numbers in the
// shortest form that reads back to the same value (float and half
// components as floats, integers in full); strings and asset paths escaped.
//
// What usda cannot say is noted in a `#` comment instead of being written:
// values this module keeps as Kind::Unsupported (path expressions,
// relocates of crate 0.11, unregistered values), and metadata whose kind
// has no untyped usda form (e.g. a quaternion under a key the usda reader
// does not know). Metadata under keys the reader does not know come back
// typed by how they are written (numbers as double, lists of names as
// strings), as in USD, which types metadata by its schema registry.
#include <cstdint>
#include <string>

#include "usd/layer.h"

namespace sdg::usd {

// Throws UsdError (naming the spec) for what no usda text can hold: an
// attribute without a typeName, an asset path with a line break, an
// internal reference with neither asset nor prim path; and (naming the
// layer) when the text would pass `maxBytes` — dictionaries that share
// entries level after level (which a crate file can hold) grow as
// 2^depth when spelled out.
std::string writeUsdaLayer(const Layer& layer, uint64_t maxBytes = uint64_t(1) << 32);

}  // namespace sdg::usd
