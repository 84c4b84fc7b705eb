#pragma once
// JSON text as the BOP toolkit's save_json writes its files: one line per
// top-level key (image or object id, ascending), each value as Python's
// json.dumps(value, sort_keys=True) writes it.
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

namespace sdg {

std::string bopJsonFile(const std::vector<std::pair<uint64_t, nlohmann::json>>& entries);
// json.dumps(value, sort_keys=True)
std::string bopJsonValue(const nlohmann::json& value);

}  // namespace sdg
