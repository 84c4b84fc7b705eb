#include "stage/prim.h"

#include <stdexcept>

#include "stage/path.h"

namespace sdg {

Prim::Prim(std::string path, PrimType type, Prim* parent)
    : path_(std::move(path)), type_(type), parent_(parent) {}

std::string_view Prim::name() const { return path::name(path_); }

const Attribute* Prim::findAttribute(std::string_view name) const {
  auto it = attributes_.find(name);
  return it == attributes_.end() ? nullptr : &it->second;
}

Attribute* Prim::findAttribute(std::string_view name) {
  auto it = attributes_.find(name);
  return it == attributes_.end() ? nullptr : &it->second;
}

Attribute& Prim::setAttribute(const std::string& name, Value value, bool custom) {
  Attribute& a = attributes_[name];
  a.value = std::move(value);
  a.custom = custom;
  return a;
}

bool Prim::removeAttribute(std::string_view name) {
  auto it = attributes_.find(name);
  if (it == attributes_.end()) return false;
  attributes_.erase(it);
  return true;
}

const Value* Prim::value(std::string_view name) const {
  if (const Attribute* a = findAttribute(name)) return &a->value;
  if (const AttributeSpec* spec = findSchemaAttribute(type_, name)) return &spec->defaultValue;
  return nullptr;
}

namespace {
const Value& required(const Prim& prim, std::string_view name) {
  const Value* v = prim.value(name);
  if (!v) throw std::logic_error(prim.path() + " has no attribute " + std::string(name));
  return *v;
}
}  // namespace

double Prim::getDouble(std::string_view name) const { return required(*this, name).get<double>(); }
float Prim::getFloat(std::string_view name) const { return required(*this, name).get<float>(); }
bool Prim::getBool(std::string_view name) const { return required(*this, name).get<bool>(); }
const std::string& Prim::getString(std::string_view name) const { return required(*this, name).get<std::string>(); }

XformOp* Prim::findXformOp(std::string_view attributeName) {
  for (XformOp& op : xformOps_)
    if (op.attributeName() == attributeName) return &op;
  return nullptr;
}

bool Prim::sameContent(const Prim& o) const {
  return path_ == o.path_ && type_ == o.type_ && attributes_ == o.attributes_ && xformOps_ == o.xformOps_ &&
         semantics_ == o.semantics_ && material_ == o.material_ && behaviors_ == o.behaviors_ &&
         metadata_ == o.metadata_;
}

}  // namespace sdg
