#pragma once
// A Value as JSON: numbers, lists, strings; quaternions as [w, x, y, z];
// matrices as four rows in USD's row-vector layout; floats through their
// shortest text so 20.955f stays 20.955.
#include <nlohmann/json.hpp>

#include "stage/value.h"

namespace sdg {

nlohmann::ordered_json valueToJson(const Value& value);

}  // namespace sdg
