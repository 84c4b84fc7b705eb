#include "scene_io/raw_node.h"

#include "core/diagnostics.h"
#include "core/text.h"

namespace sdg {

RawNode::RawNode() = default;
RawNode::~RawNode() = default;
RawNode::RawNode(const RawNode&) = default;
RawNode::RawNode(RawNode&&) noexcept = default;
RawNode& RawNode::operator=(const RawNode&) = default;
RawNode& RawNode::operator=(RawNode&&) noexcept = default;

const RawNode* RawNode::find(std::string_view key) const {
  for (const auto& [k, v] : entries)
    if (k.isScalar() && k.scalar == key) return &v;
  return nullptr;
}

std::string RawNode::describe() const {
  switch (kind) {
    case Kind::Null: return "nothing (null)";
    case Kind::Map: return "a mapping";
    case Kind::Sequence:
      return "a list of " + std::to_string(items.size()) + (items.size() == 1 ? " item" : " items");
    case Kind::Scalar: return (quoted ? "the string " : "") + text::quote(scalar);
  }
  return {};
}

}  // namespace sdg
