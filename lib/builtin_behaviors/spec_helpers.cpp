#include "builtin_behaviors/spec_helpers.h"

#include "core/text.h"

namespace sdg::behaviors {

AttributeSpec variable(std::string name, Value fallback, std::string doc) {
  return makeAttributeSpec(std::move(name), std::move(fallback), std::move(doc));
}

AttributeSpec primPathVariable(std::string name, std::string doc) {
  AttributeSpec spec = variable(std::move(name), Value::makeString(""), std::move(doc));
  spec.primPath = true;
  return spec;
}

AttributeSpec fileVariable(std::string name, Value fallback, FileKind kind, std::string doc) {
  AttributeSpec spec = variable(std::move(name), std::move(fallback), std::move(doc));
  spec.files = kind;
  return spec;
}

AttributeSpec includeChildrenVariable() {
  return variable("includeChildren", Value::makeBool(true),
                  "Also act on every descendant of the right kind (pre-order, the prim itself included).");
}

AttributeSpec intervalVariable() {
  return variable("interval", Value::makeUInt(0), "Apply every N updates; 0 means every update.");
}

AttributeSpec seedVariable() {
  return variable("seed", Value::makeInt(-1), "-1 derives the stream from the run seed; >= 0 fixes it.");
}

namespace {
std::vector<double> components(const Value& v) {
  switch (v.type()) {
    case ValueType::Float2: return {v.get<Vec2f>().x(), v.get<Vec2f>().y()};
    case ValueType::Float3:
    case ValueType::Color3f: return {v.get<Vec3f>().x(), v.get<Vec3f>().y(), v.get<Vec3f>().z()};
    case ValueType::Double3:
    case ValueType::Vector3d: return {v.get<Vec3d>().x(), v.get<Vec3d>().y(), v.get<Vec3d>().z()};
    default: return {};
  }
}
}  // namespace

void checkRange(const Prim& prim, std::string_view behavior, const std::string& minName, const std::string& maxName,
                Diagnostics& diag) {
  std::string minAttr = exposedAttributeName(behavior, minName);
  const Attribute* minA = prim.findAttribute(minAttr);
  if (!minA) return;
  const bool color = minA->value.type() == ValueType::Color3f;
  static const char* kAxes[] = {"x", "y", "z"};
  static const char* kChannels[] = {"red", "green", "blue"};
  if (maxName.empty()) {  // a (min, max) pair in one float2
    std::vector<double> c = components(minA->value);
    if (c.size() == 2 && c[0] > c[1])
      diag.error(minA->loc.known() ? minA->loc : prim.loc(),
                 prim.path() + "." + minAttr + ": the minimum " + text::formatNumber(c[0]) +
                     " is greater than the maximum " + text::formatNumber(c[1]));
    return;
  }
  std::string maxAttr = exposedAttributeName(behavior, maxName);
  const Attribute* maxA = prim.findAttribute(maxAttr);
  if (!maxA) return;
  std::vector<double> lo = components(minA->value), hi = components(maxA->value);
  for (size_t i = 0; i < lo.size() && i < hi.size(); ++i)
    if (lo[i] > hi[i]) {
      const SourceLoc& loc = minA->loc.known() ? minA->loc : maxA->loc.known() ? maxA->loc : prim.loc();
      diag.error(loc, prim.path() + ": " + minAttr + " (" + text::formatNumber(lo[i]) + ") is greater than " +
                          maxAttr + " (" + text::formatNumber(hi[i]) + ") in " + (color ? kChannels[i] : kAxes[i]));
      return;
    }
}

}  // namespace sdg::behaviors
