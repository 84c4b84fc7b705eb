// readCrateLayer (declared in layer_io.h): a crate file's specs and their
// fields as a Layer. Each spec's fields are its field set's run of field
// indexes; each field is a name token and a value (crate_values.h).
#include <string>

#include "usd/crate_file.h"
#include "usd/crate_values.h"
#include "usd/layer_io.h"

namespace sdg::usd {

namespace {

// Fields that shape the layer's namespace must hold the type Sdf gives them;
// any other field may hold whatever the file says (kept as Unsupported when
// this reader does not know the type).
const char* structuralMismatch(const std::string& name, const Value& v) {
  auto expect = [&v](Kind kind, const char* what) -> const char* { return v.kind == kind ? nullptr : what; };
  if (name == field::kSpecifier) return expect(Kind::Specifier, "a specifier");
  if (name == field::kTypeName) return expect(Kind::Token, "a token");
  if (name == field::kVariability) return expect(Kind::Variability, "a variability");
  if (name == field::kPrimChildren || name == field::kProperties || name == field::kVariantSetChildren ||
      name == field::kVariantChildren)
    return expect(Kind::TokenVector, "a token vector");
  return nullptr;
}

const char* valueKindName(const Value& v, ValueRep rep) {
  return v.kind == Kind::Unsupported ? "an unsupported type" : crateTypeName(rep.type());
}

}  // namespace

Layer readCrateLayer(std::span<const uint8_t> bytes, const std::string& identifier, const ReadLimits& limits) {
  CrateFile crate(bytes, identifier, limits);
  CrateValueReader values(crate);
  Layer layer;
  layer.identifier = identifier;
  layer.realPath = identifier;
  layer.format = "usdc";
  const FileName file(identifier);
  const auto& fieldSets = crate.fieldSets();
  const auto& specs = crate.specs();
  for (size_t i = 0; i < specs.size(); ++i) {
    const CrateSpec& cs = specs[i];
    const std::string& path = crate.paths()[cs.path];
    Spec spec;
    spec.type = SpecType(cs.type);
    spec.loc = SourceLoc(file, 0, 0);
    for (size_t f = cs.fieldSet; f < fieldSets.size() && fieldSets[f] != kFieldSetEnd; ++f) {
      const CrateField& cf = crate.fields()[fieldSets[f]];
      const std::string& name = crate.tokens()[cf.token];
      auto where = [&] {  // built only for an error: most fields have none
        return "spec " + std::to_string(i) + " <" + path + "> field '" + name + "' (" + crateTypeName(cf.rep.type()) +
               (cf.rep.isArray() ? "[]" : "") + ")";
      };
      Value value;
      try {
        value = values.read(cf.rep);
      } catch (const CodingError& e) {
        throwCrateError(identifier, where(), e.what());
      } catch (const std::bad_alloc&) {
        throwCrateError(identifier, where(), "out of memory");
      }
      if (const char* expected = structuralMismatch(name, value))
        throwCrateError(identifier, where(), std::string("holds ") + valueKindName(value, cf.rep) + ", expected " +
                                               expected);
      // Crate files list fields and specs mostly in sorted order: hinting
      // the end makes each insertion constant time then.
      const size_t fieldsBefore = spec.fields.size();
      spec.fields.emplace_hint(spec.fields.end(), name, std::move(value));
      if (spec.fields.size() == fieldsBefore)
        throwCrateError(identifier, where(), "the field appears twice in the spec");
    }
    const size_t specsBefore = layer.specs.size();
    layer.specs.emplace_hint(layer.specs.end(), path, std::move(spec));
    if (layer.specs.size() == specsBefore)
      throwCrateError(identifier, "spec " + std::to_string(i), "a second spec for <" + path + ">");
  }
  auto root = layer.specs.find("/");
  if (root == layer.specs.end() || root->second.type != SpecType::PseudoRoot)
    throwCrateError(identifier, "SPECS section", "there is no pseudo-root spec at </>");
  return layer;
}

}  // namespace sdg::usd
