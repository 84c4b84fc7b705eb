#include "writers/bop_json.h"

#include "writers/py_json.h"

namespace sdg {
namespace {

// nlohmann::json keeps object keys sorted (std::map): copied in that order.
nlohmann::ordered_json sortedCopy(const nlohmann::json& j) {
  if (j.is_object()) {
    nlohmann::ordered_json o = nlohmann::ordered_json::object();
    for (auto it = j.begin(); it != j.end(); ++it) o[it.key()] = sortedCopy(it.value());
    return o;
  }
  if (j.is_array()) {
    nlohmann::ordered_json a = nlohmann::ordered_json::array();
    for (const auto& v : j) a.push_back(sortedCopy(v));
    return a;
  }
  switch (j.type()) {
    case nlohmann::json::value_t::boolean: return j.get<bool>();
    case nlohmann::json::value_t::number_integer: return j.get<int64_t>();
    case nlohmann::json::value_t::number_unsigned: return j.get<uint64_t>();
    case nlohmann::json::value_t::number_float: return j.get<double>();
    case nlohmann::json::value_t::string: return j.get<std::string>();
    default: return nullptr;
  }
}

}  // namespace

std::string bopJsonValue(const nlohmann::json& value) { return pythonJsonDumps(sortedCopy(value)); }

std::string bopJsonFile(const std::vector<std::pair<uint64_t, nlohmann::json>>& entries) {
  std::string out = "{\n";
  for (size_t i = 0; i < entries.size(); ++i) {
    out += "  \"" + std::to_string(entries[i].first) + "\": " + bopJsonValue(entries[i].second);
    if (i + 1 != entries.size()) out += ",";
    out += "\n";
  }
  return out + "}";
}

}  // namespace sdg
