#pragma once
// JSON text exactly as Python's json.dumps writes it with default options:
// ", " and ": " separators, no indentation, non-ASCII escaped as \uXXXX,
// floats as Python's repr (shortest round-trip, "1.0", "NaN", "Infinity").
#include <string>

#include <nlohmann/json.hpp>

namespace sdg {

std::string pythonJsonDumps(const nlohmann::ordered_json& value);

}  // namespace sdg
