#include "core/payload.h"

#include "core/text.h"

namespace sdg {

Payload::Payload(std::initializer_list<std::pair<std::string, PayloadValue>> entries) {
  for (const auto& [k, v] : entries) set(k, v);
}

void Payload::set(std::string key, PayloadValue value) {
  for (auto& [k, v] : entries_)
    if (k == key) {
      v = std::move(value);
      return;
    }
  entries_.emplace_back(std::move(key), std::move(value));
}

const PayloadValue* Payload::find(std::string_view key) const {
  for (const auto& [k, v] : entries_)
    if (k == key) return &v;
  return nullptr;
}

std::string_view Payload::getString(std::string_view key) const {
  const PayloadValue* v = find(key);
  if (!v) return {};
  const std::string* s = std::get_if<std::string>(v);
  return s ? std::string_view(*s) : std::string_view{};
}

bool Payload::contains(const Payload& expected) const {
  for (const auto& [k, v] : expected.entries_) {
    const PayloadValue* mine = find(k);
    if (!mine || *mine != v) return false;
  }
  return true;
}

std::string Payload::toString() const {
  std::string out = "{";
  for (size_t i = 0; i < entries_.size(); ++i) {
    const auto& [k, v] = entries_[i];
    if (i) out += ", ";
    out += k + ": ";
    if (const auto* s = std::get_if<std::string>(&v)) out += *s;
    else if (const auto* d = std::get_if<double>(&v)) out += text::formatDouble(*d);
    else out += std::get<bool>(v) ? "true" : "false";
  }
  return out + "}";
}

}  // namespace sdg
