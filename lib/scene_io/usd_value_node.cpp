#include "scene_io/usd_value_node.h"

#include <charconv>
#include <filesystem>

#include "scene_io/value_reader.h"
#include "usd/layer_io.h"

namespace sdg {

RawNode scalarNode(std::string text, bool quoted, const SourceLoc& loc) {
  RawNode n;
  n.kind = RawNode::Kind::Scalar;
  n.scalar = std::move(text);
  n.quoted = quoted;
  n.loc = loc;
  return n;
}

namespace {

// A resolved asset path as the stage holds it. Composition resolves against
// layer paths as they were given, relative to the working directory, while
// the stage resolves relative paths against the scene's folder: made
// absolute (the package's path, for a package entry), the path means the
// same file from either, whatever folder the command was started in.
std::string stageAssetPath(const std::string& resolved) {
  if (resolved.empty() || resolved.find("://") != std::string::npos) return resolved;
  auto [file, entry] = usd::splitPackagePath(resolved);
  const std::string absolute = std::filesystem::absolute(file).lexically_normal().generic_string();
  return entry.empty() ? absolute : absolute + "[" + entry + "]";
}

// Shortest text that reads back as the same number (a float's value read
// back as float, a double's as double).
std::string numberText(double v, bool single) {
  char buf[64];
  auto r = single ? std::to_chars(buf, buf + sizeof buf, static_cast<float>(v))
                  : std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}

bool isSinglePrecision(usd::Kind k) {
  switch (k) {
    case usd::Kind::Half: case usd::Kind::Float: case usd::Kind::Vec2h: case usd::Kind::Vec2f:
    case usd::Kind::Vec3h: case usd::Kind::Vec3f: case usd::Kind::Vec4h: case usd::Kind::Vec4f:
    case usd::Kind::Quath: case usd::Kind::Quatf: return true;
    default: return false;
  }
}

RawNode numericElement(const usd::Value& v, size_t element, const SourceLoc& loc) {
  const int n = usd::componentCount(v.kind);
  const bool single = isSinglePrecision(v.kind);
  const size_t base = element * size_t(n);
  if (v.kind == usd::Kind::Bool) return scalarNode(v.numbers[base] != 0 ? "true" : "false", false, loc);
  if (n == 1) return scalarNode(numberText(v.numbers[base], single), false, loc);
  RawNode seq;
  seq.kind = RawNode::Kind::Sequence;
  seq.loc = loc;
  const bool matrix = v.kind == usd::Kind::Matrix2d || v.kind == usd::Kind::Matrix3d || v.kind == usd::Kind::Matrix4d;
  const int rows = matrix ? (n == 4 ? 2 : n == 9 ? 3 : 4) : 1;
  const int cols = n / rows;
  for (int r = 0; r < rows; ++r) {
    RawNode row;
    row.kind = RawNode::Kind::Sequence;
    row.loc = loc;
    for (int c = 0; c < cols; ++c)
      row.items.push_back(scalarNode(numberText(v.numbers[base + size_t(r * cols + c)], single), false, loc));
    if (!matrix) return row;
    seq.items.push_back(std::move(row));
  }
  return seq;
}

}  // namespace

RawNode usdValueAsNode(const usd::ComposedProperty& property) {
  const usd::Value& v = property.value;
  const SourceLoc& loc = property.loc;
  RawNode node;
  node.loc = loc;
  if (v.empty() || v.kind == usd::Kind::ValueBlock) return node;
  if (usd::isText(v.kind)) {
    const bool asset = v.kind == usd::Kind::AssetPath;
    std::vector<std::string> items = v.strings;
    if (asset && property.resolvedAssets.size() == v.strings.size())
      for (size_t i = 0; i < items.size(); ++i) items[i] = stageAssetPath(property.resolvedAssets[i]);
    if (!v.isArray) return scalarNode(items.empty() ? std::string() : items.front(), true, loc);
    node.kind = RawNode::Kind::Sequence;
    for (const std::string& s : items) node.items.push_back(scalarNode(s, true, loc));
    return node;
  }
  if (usd::isNumeric(v.kind)) {
    if (!v.isArray) return numericElement(v, 0, loc);
    node.kind = RawNode::Kind::Sequence;
    for (size_t i = 0; i < v.elementCount(); ++i) node.items.push_back(numericElement(v, i, loc));
    return node;
  }
  // Metadata kinds never hold an attribute's value; say what it is.
  return scalarNode(std::string("<") + usd::kindName(v.kind) + ">", true, loc);
}

std::optional<Value> readUsdValue(const usd::ComposedProperty& property, const AttributeSpec& spec,
                                  std::string_view what, Diagnostics& diag) {
  return readValue(usdValueAsNode(property), spec, what, diag);
}

std::optional<Value> readUsdValue(const usd::ComposedProperty& property, ValueType type, std::string_view what,
                                  Diagnostics& diag) {
  return readValue(usdValueAsNode(property), type, what, diag);
}

}  // namespace sdg
