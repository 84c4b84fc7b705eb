#pragma once
// The small payload events carry: string keys; string, number or bool values,
// in insertion order.
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <variant>
#include <vector>

namespace sdg {

using PayloadValue = std::variant<std::string, double, bool>;

class Payload {
 public:
  Payload() = default;
  Payload(std::initializer_list<std::pair<std::string, PayloadValue>> entries);

  void set(std::string key, PayloadValue value);
  const PayloadValue* find(std::string_view key) const;
  // The string under `key`, or "" when absent or not a string.
  std::string_view getString(std::string_view key) const;
  // True when every entry of `expected` is present here with an equal value.
  bool contains(const Payload& expected) const;
  const std::vector<std::pair<std::string, PayloadValue>>& entries() const { return entries_; }
  bool empty() const { return entries_.empty(); }
  std::string toString() const;  // {key: value, ...} for messages
  bool operator==(const Payload&) const = default;

 private:
  std::vector<std::pair<std::string, PayloadValue>> entries_;
};

}  // namespace sdg
