#include "usd/usda_writer.h"

#include <charconv>
#include <cmath>
#include <optional>
#include <set>

#include "usd/sdf_path.h"

namespace sdg::usd {

namespace {

// ---- text of single values ---------------------------------------------------------

std::string quoted(std::string_view s) {
  std::string out = "\"";
  for (char c : s) {
    auto u = static_cast<unsigned char>(c);
    switch (c) {
      case '"': out += "\\\""; break;
      case '\\': out += "\\\\"; break;
      case '\n': out += "\\n"; break;
      case '\r': out += "\\r"; break;
      case '\t': out += "\\t"; break;
      default:
        if (u < 0x20 || u == 0x7f) {
          const char* hex = "0123456789abcdef";
          out += "\\x";
          out += hex[u >> 4];
          out += hex[u & 15];
        } else {
          out += c;
        }
    }
  }
  return out + "\"";
}

// The shortest text that reads back to `v` as the usda reader reads a
// number of `scalar`'s type (floats and halves as floats, integers whole).
void appendNumber(std::string& out, double v, Kind scalar) {
  if (std::isnan(v)) {
    out += "nan";
    return;
  }
  if (std::isinf(v)) {
    out += v < 0 ? "-inf" : "inf";
    return;
  }
  char buf[64];
  char* end = buf;
  switch (scalar) {
    case Kind::Bool:
      out += v != 0 ? "true" : "false";
      return;
    case Kind::UChar: case Kind::Int: case Kind::UInt: case Kind::Int64: case Kind::UInt64:
      end = std::to_chars(buf, buf + sizeof buf, v, std::chars_format::fixed).ptr;
      break;
    case Kind::Half:
    case Kind::Float: {
      // The float's shortest form, unless reading it as a double and
      // narrowing (as the reader does) would land on another float.
      end = std::to_chars(buf, buf + sizeof buf, static_cast<float>(v)).ptr;
      double back = 0;
      std::from_chars(buf, end, back);
      if (static_cast<float>(back) != static_cast<float>(v)) end = std::to_chars(buf, buf + sizeof buf, v).ptr;
      break;
    }
    default: end = std::to_chars(buf, buf + sizeof buf, v).ptr; break;
  }
  out.append(buf, end);
}

// One element of a numeric value: "1.5", "(1, 2, 3)", "((1, 0), (0, 1))".
void appendElement(std::string& out, Kind kind, const double* numbers) {
  const int components = componentCount(kind);
  const Kind scalar = componentKind(kind);
  if (components == 1) {
    appendNumber(out, numbers[0], scalar);
    return;
  }
  const int rows = matrixDimension(kind);
  auto tuple = [&](const double* p, int n) {
    out += '(';
    for (int i = 0; i < n; ++i) {
      if (i) out += ", ";
      appendNumber(out, p[i], scalar);
    }
    out += ')';
  };
  if (!rows) {
    tuple(numbers, components);
    return;
  }
  out += '(';
  for (int r = 0; r < rows; ++r) {
    if (r) out += ", ";
    tuple(numbers + r * rows, rows);
  }
  out += ')';
}

std::string pathText(const std::string& p) { return "<" + p + ">"; }

std::string pathListText(const std::vector<std::string>& paths) {
  std::string out = "[";
  for (size_t i = 0; i < paths.size(); ++i) out += (i ? ", " : "") + pathText(paths[i]);
  return out + "]";
}

std::string nameListText(const std::vector<std::string>& names) {
  std::string out = "[";
  for (size_t i = 0; i < names.size(); ++i) out += (i ? ", " : "") + quoted(names[i]);
  return out + "]";
}

std::string indentText(int indent) { return std::string(size_t(indent) * 4, ' '); }

// "custom " for a custom property, and `word` when its variability is
// `stated` (the one that is not the property kind's fallback).
std::string qualifiers(const Spec& spec, Variability stated, const char* word) {
  std::string out;
  if (const Value* custom = spec.field(field::kCustom); custom && custom->kind == Kind::Bool && custom->numbers.at(0) != 0)
    out += "custom ";
  if (const Value* v = spec.field(field::kVariability); v && v->kind == Kind::Variability && v->enumValue == int(stated))
    out += word;
  return out;
}

// ---- the writer ---------------------------------------------------------------------

class UsdaWriter {
 public:
  UsdaWriter(const Layer& layer, uint64_t maxBytes) : layer_(layer), maxBytes_(maxBytes) { indexSpecs(); }
  std::string write();

 private:
  struct Children {
    std::map<std::string, std::string> prims, properties, variantSets, variants;  // name -> spec path
  };

  void indexSpecs();
  [[noreturn]] void fail(const Spec& spec, const std::string& path, const std::string& what) const;
  void line(int indent, const std::string& text) {
    out_ += indentText(indent) + text + "\n";
    checkSize(out_.size());
  }
  void checkSize(uint64_t size) const {
    if (size > maxBytes_)
      throw usdErrorAt(SourceLoc(layer_.identifier, 0, 0),
                       "the usda text would pass " + std::to_string(maxBytes_) + " bytes");
  }
  void comment(int indent, const std::string& key, const Value& v) {
    line(indent, "# '" + key + "' (" + (v.kind == Kind::Unsupported && !v.strings.empty() ? v.strings[0]
                                                                                          : kindName(v.kind)) +
                     ") is not written: usda has no form for it here");
  }
  std::vector<std::string> ordered(const Spec& spec, const char* listField,
                                   const std::map<std::string, std::string>& byName) const;

  void writeMetadataBlock(const std::string& head, const std::string& path, const Spec& spec,
                          const std::set<std::string>& skip, int indent, const char* open);
  void metadataEntries(const std::string& path, const Spec& spec, const std::set<std::string>& skip, int indent);
  void prim(const std::string& path, const Spec& spec, int indent);
  void contents(const std::string& path, const Spec& spec, int indent);
  void variantSet(const std::string& path, const std::string& name, int indent);
  void attribute(const std::string& path, const std::string& name, const Spec& spec, int indent);
  void relationship(const std::string& path, const std::string& name, const Spec& spec, int indent);

  std::string typedValue(const Value& v, int indent, const std::string& path, const Spec& spec) const;
  std::optional<std::string> typeNameOf(const Value& v) const;
  std::optional<std::string> untypedValue(const Value& v, int indent, const std::string& path,
                                          const Spec& spec) const;
  std::string dictionaryText(const Dictionary& d, int indent, const std::string& path, const Spec& spec) const;
  std::string assetText(const std::string& s, const std::string& path, const Spec& spec) const;
  std::string referenceText(const Reference& r, int indent, const std::string& path, const Spec& spec) const;
  template <class T, class Text>
  void listOpLines(int indent, const std::string& declaration, const ListOp<T>& op, Text itemsText);

  const Layer& layer_;
  uint64_t maxBytes_;
  std::string out_;
  std::map<std::string, Children> children_;  // by owner path
  std::vector<std::string> skipped_;          // specs of types usda cannot hold
};

void UsdaWriter::fail(const Spec& spec, const std::string& path, const std::string& what) const {
  SourceLoc loc = spec.loc.known() ? spec.loc : SourceLoc(layer_.identifier, 0, 0);
  throw usdErrorAt(loc, "cannot write <" + path + "> as usda: " + what);
}

// Files every spec under its owner: prims under their parent, properties
// under their prim, variant sets under their prim, variants under their set.
void UsdaWriter::indexSpecs() {
  for (const auto& [path, spec] : layer_.specs) {
    switch (spec.type) {
      case SpecType::PseudoRoot: break;
      case SpecType::Prim:
        children_[path::parent(path)].prims[std::string(path::name(path))] = path;
        break;
      case SpecType::Attribute:
      case SpecType::Relationship:
        children_[std::string(path::primPart(path))].properties[std::string(path::propertyName(path))] = path;
        break;
      case SpecType::VariantSet: {  // "/A{set=}"
        size_t open = path.rfind('{');
        children_[path.substr(0, open)].variantSets[path.substr(open + 1, path.size() - open - 3)] = path;
        break;
      }
      case SpecType::Variant: {  // "/A{set=sel}"
        size_t eq = path.rfind('=');
        children_[path.substr(0, eq + 1) + "}"].variants[path.substr(eq + 1, path.size() - eq - 2)] = path;
        break;
      }
      default: skipped_.push_back(path); break;
    }
  }
}

// The names of `byName` in the order the spec's `listField` gives, then
// the unlisted ones in name order.
std::vector<std::string> UsdaWriter::ordered(const Spec& spec, const char* listField,
                                             const std::map<std::string, std::string>& byName) const {
  std::vector<std::string> names;
  std::set<std::string> done;
  if (const Value* list = spec.field(listField))
    for (const auto& n : list->strings)
      if (byName.count(n) && done.insert(n).second) names.push_back(n);
  for (const auto& [n, p] : byName)
    if (done.insert(n).second) names.push_back(n);
  return names;
}

std::string UsdaWriter::write() {
  out_ = "#usda 1.0\n";
  const Spec* root = layer_.spec("/");
  static const Spec kEmpty;
  const Spec& rootSpec = root ? *root : kEmpty;
  const std::set<std::string> skip{field::kPrimChildren, field::kPrimOrder};
  out_ += "(\n";
  metadataEntries("/", rootSpec, skip, 1);
  out_ += ")\n";
  if (const Value* order = rootSpec.field(field::kPrimOrder); order && order->kind == Kind::TokenVector)
    out_ += "\nreorder rootPrims = " + nameListText(order->strings) + "\n";
  const Children& top = children_["/"];
  for (const auto& name : ordered(rootSpec, field::kPrimChildren, top.prims)) {
    out_ += "\n";
    prim(top.prims.at(name), layer_.specs.at(top.prims.at(name)), 0);
  }
  for (const auto& p : skipped_)
    out_ += "\n# spec <" + p + "> (spec type " + std::to_string(int(layer_.specs.at(p).type)) + ") is not written\n";
  return out_;
}

void UsdaWriter::writeMetadataBlock(const std::string& head, const std::string& path, const Spec& spec,
                                    const std::set<std::string>& skip, int indent, const char* open) {
  std::string saved = std::move(out_);
  out_.clear();
  metadataEntries(path, spec, skip, indent + 1);
  std::string entries = std::move(out_);
  out_ = std::move(saved);
  if (entries.empty()) {
    line(indent, head);
  } else {
    line(indent, head + " (");
    out_ += entries;
    line(indent, ")");
  }
  if (open) line(indent, open);
}

// Every field of `spec` not in `skip`, one entry per line (a list op one
// line per list it holds).
void UsdaWriter::metadataEntries(const std::string& path, const Spec& spec, const std::set<std::string>& skip,
                                 int indent) {
  for (const auto& [key, v] : spec.fields) {
    if (skip.count(key)) continue;
    if (key == field::kSubLayers) {
      const Value* offsets = spec.field(field::kSubLayerOffsets);
      line(indent, "subLayers = [");
      for (size_t i = 0; i < v.strings.size(); ++i) {
        std::string item = assetText(v.strings[i], path, spec);
        if (offsets && offsets->layerOffsets && i < offsets->layerOffsets->size()) {
          const LayerOffset& o = (*offsets->layerOffsets)[i];
          std::string parts;
          if (o.offset != 0) appendNumber(parts += "offset = ", o.offset, Kind::Double);
          if (o.scale != 1) appendNumber(parts += std::string(parts.empty() ? "" : "; ") + "scale = ", o.scale, Kind::Double);
          if (!parts.empty()) item += " (" + parts + ")";
        }
        line(indent + 1, item + (i + 1 < v.strings.size() ? "," : ""));
      }
      line(indent, "]");
      continue;
    }
    if (key == field::kSubLayerOffsets && spec.field(field::kSubLayers)) continue;  // with the sublayers
    switch (v.kind) {
      case Kind::TokenListOp:
      case Kind::StringListOp:
      case Kind::PathListOp: {
        // The usda keys of Sdf's list-op fields.
        std::string name = key == field::kInheritPaths ? "inherits" : key == field::kVariantSetNames ? "variantSets" : key;
        bool paths = v.kind == Kind::PathListOp;
        listOpLines(indent, name, *v.textListOp,
                    [paths](const std::vector<std::string>& items) { return paths ? pathListText(items) : nameListText(items); });
        continue;
      }
      case Kind::IntListOp:
      case Kind::Int64ListOp:
      case Kind::UIntListOp:
      case Kind::UInt64ListOp:
        listOpLines(indent, key, *v.intListOp, [](const std::vector<int64_t>& items) {
          std::string s = "[";
          for (size_t i = 0; i < items.size(); ++i) s += (i ? ", " : "") + std::to_string(items[i]);
          return s + "]";
        });
        continue;
      case Kind::ReferenceListOp:
      case Kind::PayloadListOp:
        if (key != field::kReferences && key != field::kPayload) break;
        listOpLines(indent, key, *v.referenceListOp, [&](const std::vector<Reference>& refs) {
          std::string s = "[";
          for (size_t i = 0; i < refs.size(); ++i) s += (i ? ", " : "") + referenceText(refs[i], indent, path, spec);
          return s + "]";
        });
        continue;
      case Kind::Payload:
        if (key != field::kPayload || !v.references || v.references->size() != 1) break;
        line(indent, "payload = " + referenceText(v.references->front(), indent, path, spec));
        continue;
      case Kind::VariantSelectionMap:
        if (key != field::kVariantSelection) break;
        line(indent, "variants = " + dictionaryText(*v.dictionary, indent, path, spec));
        continue;
      case Kind::Permission:
        line(indent, key + " = " + (v.enumValue == int(Permission::Private) ? "private" : "public"));
        continue;
      default: break;
    }
    if (auto text = untypedValue(v, indent, path, spec)) {
      line(indent, key + " = " + *text);
    } else {
      comment(indent, key, v);
    }
  }
}

template <class T, class Text>
void UsdaWriter::listOpLines(int indent, const std::string& declaration, const ListOp<T>& op, Text itemsText) {
  if (op.isExplicit) line(indent, declaration + " = " + itemsText(op.explicitItems));
  const std::pair<const char*, const std::vector<T>*> parts[] = {{"delete", &op.deletedItems},
                                                                 {"add", &op.addedItems},
                                                                 {"prepend", &op.prependedItems},
                                                                 {"append", &op.appendedItems},
                                                                 {"reorder", &op.orderedItems}};
  for (const auto& [word, items] : parts)
    if (!items->empty()) line(indent, std::string(word) + " " + declaration + " = " + itemsText(*items));
}

void UsdaWriter::prim(const std::string& path, const Spec& spec, int indent) {
  const Value* specifier = spec.field(field::kSpecifier);
  int s = specifier && specifier->kind == Kind::Specifier ? specifier->enumValue : int(Specifier::Over);
  std::string head = s == int(Specifier::Def) ? "def" : s == int(Specifier::Class) ? "class" : "over";
  if (const Value* type = spec.field(field::kTypeName); type && type->kind == Kind::Token && !type->strings[0].empty())
    head += " " + type->strings[0];
  head += " " + quoted(path::name(path));
  static const std::set<std::string> skip{field::kSpecifier, field::kTypeName, field::kPrimChildren,
                                          field::kProperties, field::kVariantSetChildren, field::kPrimOrder,
                                          field::kPropertyOrder};
  writeMetadataBlock(head, path, spec, skip, indent, "{");
  contents(path, spec, indent + 1);
  line(indent, "}");
}

// A prim's or a variant's body: reorder statements, properties, child
// prims, variant sets.
void UsdaWriter::contents(const std::string& path, const Spec& spec, int indent) {
  if (const Value* order = spec.field(field::kPrimOrder); order && order->kind == Kind::TokenVector)
    line(indent, "reorder nameChildren = " + nameListText(order->strings));
  if (const Value* order = spec.field(field::kPropertyOrder); order && order->kind == Kind::TokenVector)
    line(indent, "reorder properties = " + nameListText(order->strings));
  Children& c = children_[path];
  bool first = true;
  auto separate = [&] {
    if (!first) out_ += "\n";
    first = false;
  };
  for (const auto& name : ordered(spec, field::kProperties, c.properties)) {
    separate();
    const std::string& p = c.properties.at(name);
    const Spec& s = layer_.specs.at(p);
    s.type == SpecType::Relationship ? relationship(p, name, s, indent) : attribute(p, name, s, indent);
  }
  for (const auto& name : ordered(spec, field::kPrimChildren, c.prims)) {
    separate();
    prim(c.prims.at(name), layer_.specs.at(c.prims.at(name)), indent);
  }
  for (const auto& name : ordered(spec, field::kVariantSetChildren, c.variantSets)) {
    separate();
    variantSet(c.variantSets.at(name), name, indent);
  }
}

void UsdaWriter::variantSet(const std::string& setPath, const std::string& name, int indent) {
  const Spec& set = layer_.specs.at(setPath);
  for (const auto& [key, v] : set.fields)
    if (key != field::kVariantChildren) comment(indent, key, v);
  line(indent, "variantSet " + quoted(name) + " = {");
  Children& c = children_[setPath];
  static const std::set<std::string> skip{field::kSpecifier, field::kTypeName, field::kPrimChildren,
                                          field::kProperties, field::kVariantSetChildren, field::kPrimOrder,
                                          field::kPropertyOrder};
  for (const auto& variant : ordered(set, field::kVariantChildren, c.variants)) {
    const std::string& p = c.variants.at(variant);
    const Spec& spec = layer_.specs.at(p);
    writeMetadataBlock(quoted(variant), p, spec, skip, indent + 1, "{");
    contents(p, spec, indent + 2);
    line(indent + 1, "}");
  }
  line(indent, "}");
}

void UsdaWriter::attribute(const std::string& path, const std::string& name, const Spec& spec, int indent) {
  const Value* typeName = spec.field(field::kTypeName);
  if (!typeName || typeName->kind != Kind::Token || typeName->strings.empty() || typeName->strings[0].empty())
    fail(spec, path, "the attribute has no typeName");
  std::string declaration = qualifiers(spec, Variability::Uniform, "uniform ") + typeName->strings[0] + " " + name;

  std::string head = declaration;
  if (const Value* v = spec.field(field::kDefault)) {
    if (v->kind == Kind::Unsupported) {
      comment(indent, field::kDefault, *v);
    } else {
      head += " = " + (v->kind == Kind::ValueBlock ? std::string("None") : typedValue(*v, indent, path, spec));
    }
  }
  static const std::set<std::string> skip{field::kTypeName, field::kCustom, field::kVariability, field::kDefault,
                                          field::kTimeSamples, field::kConnectionPaths};
  writeMetadataBlock(head, path, spec, skip, indent, nullptr);
  if (const Value* v = spec.field(field::kTimeSamples); v && v->kind == Kind::TimeSamples) {
    line(indent, declaration + ".timeSamples = {");
    const TimeSamples& ts = *v->timeSamples;
    for (size_t i = 0; i < ts.times.size() && i < ts.values.size(); ++i) {
      std::string sample;
      appendNumber(sample, ts.times[i], Kind::Double);
      const Value& value = ts.values[i];
      sample += ": " + (value.kind == Kind::ValueBlock ? std::string("None") : typedValue(value, indent + 1, path, spec));
      line(indent + 1, sample + ",");
    }
    line(indent, "}");
  }
  if (const Value* v = spec.field(field::kConnectionPaths); v && v->kind == Kind::PathListOp)
    listOpLines(indent, declaration + ".connect", *v->textListOp, pathListText);
}

void UsdaWriter::relationship(const std::string& path, const std::string& name, const Spec& spec, int indent) {
  std::string declaration = qualifiers(spec, Variability::Varying, "varying ") + "rel " + name;
  const Value* targets = spec.field(field::kTargetPaths);
  const ListOp<std::string>* op = targets && targets->kind == Kind::PathListOp ? targets->textListOp.get() : nullptr;
  std::string head = declaration;
  if (op && op->isExplicit) head += " = " + pathListText(op->explicitItems);
  static const std::set<std::string> skip{field::kCustom, field::kVariability, field::kTargetPaths, field::kDefault};
  writeMetadataBlock(head, path, spec, skip, indent, nullptr);
  if (op) {
    ListOp<std::string> rest = *op;
    rest.isExplicit = false;  // written above
    listOpLines(indent, declaration, rest, pathListText);
  }
  if (const Value* v = spec.field(field::kDefault)) {
    if (v->kind == Kind::PathVector && v->strings.size() == 1) {
      line(indent, declaration + ".default = " + pathText(v->strings[0]));
    } else {
      comment(indent, field::kDefault, *v);
    }
  }
}

std::string UsdaWriter::assetText(const std::string& s, const std::string& path, const Spec& spec) const {
  if (s.find_first_of("\n\r") != std::string::npos) fail(spec, path, "an asset path holds a line break");
  if (s.find('@') == std::string::npos) return "@" + s + "@";
  std::string escaped;
  for (size_t i = 0; i < s.size(); ++i) {
    if (s.compare(i, 3, "@@@") == 0) {
      escaped += "\\@@@";
      i += 2;
    } else {
      escaped += s[i];
    }
  }
  return "@@@" + escaped + "@@@";
}

std::string UsdaWriter::referenceText(const Reference& r, int indent, const std::string& path, const Spec& spec) const {
  std::string s;
  if (!r.assetPath.empty()) s += assetText(r.assetPath, path, spec);
  if (!r.primPath.empty()) s += pathText(r.primPath);
  if (s.empty()) fail(spec, path, "a reference or payload with neither an asset path nor a prim path");
  std::vector<std::string> parts;
  if (r.offset.offset != 0) appendNumber(parts.emplace_back("offset = "), r.offset.offset, Kind::Double);
  if (r.offset.scale != 1) appendNumber(parts.emplace_back("scale = "), r.offset.scale, Kind::Double);
  if (r.customData && !r.customData->empty())
    parts.push_back("customData = " + dictionaryText(*r.customData, indent, path, spec));
  if (!parts.empty()) {
    s += " (";
    for (size_t i = 0; i < parts.size(); ++i) s += (i ? "; " : "") + parts[i];
    s += ")";
  }
  return s;
}

// An attribute value or a dictionary entry, its type already written.
std::string UsdaWriter::typedValue(const Value& v, int indent, const std::string& path, const Spec& spec) const {
  if (v.kind == Kind::Dictionary) return dictionaryText(*v.dictionary, indent, path, spec);
  std::string out;
  auto element = [&](size_t i) {
    if (isNumeric(v.kind)) {
      appendElement(out, v.kind, v.numbers.data() + i * size_t(componentCount(v.kind)));
    } else if (v.kind == Kind::AssetPath) {
      out += assetText(v.strings[i], path, spec);
    } else {
      out += quoted(v.strings[i]);
    }
  };
  if (v.kind == Kind::DoubleVector) {  // a double[] in usda
    Value d = v;
    d.kind = Kind::Double;
    d.isArray = true;
    return typedValue(d, indent, path, spec);
  }
  bool list = v.isArray || v.kind == Kind::TokenVector || v.kind == Kind::StringVector;
  size_t count = isNumeric(v.kind) ? v.numbers.size() / size_t(std::max(1, componentCount(v.kind))) : v.strings.size();
  if (!list) {
    if (count == 0) fail(spec, path, std::string("a ") + kindName(v.kind) + " value holds nothing");
    element(0);
    return out;
  }
  out += '[';
  for (size_t i = 0; i < count; ++i) {
    if (i) out += ", ";
    element(i);
  }
  return out + ']';
}

// The usda type name of a dictionary entry's value; none for kinds usda's
// typed dictionaries cannot hold.
std::optional<std::string> UsdaWriter::typeNameOf(const Value& v) const {
  if (v.kind == Kind::Dictionary) return "dictionary";
  if (isNumeric(v.kind) || isText(v.kind)) return std::string(kindName(v.kind)) + (v.isArray ? "[]" : "");
  if (v.kind == Kind::TokenVector) return "token[]";
  if (v.kind == Kind::StringVector) return "string[]";
  if (v.kind == Kind::DoubleVector) return "double[]";
  return std::nullopt;
}

std::string UsdaWriter::dictionaryText(const Dictionary& d, int indent, const std::string& path,
                                       const Spec& spec) const {
  if (d.empty()) return "{}";
  std::string out = "{\n";
  for (const auto& [key, v] : d) {
    std::string pad = indentText(indent + 1);
    if (auto type = typeNameOf(v)) {
      out += pad + *type + " " + quoted(key) + " = " + typedValue(v, indent + 1, path, spec) + "\n";
      checkSize(out.size());
    } else {
      out += pad + "# '" + key + "' (" + kindName(v.kind) + ") is not written: usda dictionaries cannot hold it\n";
    }
  }
  return out + indentText(indent) + "}";
}

// A metadata value as written without a type: the reader types it by its
// form (or by its key, for the keys it knows).
std::optional<std::string> UsdaWriter::untypedValue(const Value& v, int indent, const std::string& path,
                                                    const Spec& spec) const {
  switch (v.kind) {
    case Kind::ValueBlock: return "None";
    case Kind::Dictionary: return dictionaryText(*v.dictionary, indent, path, spec);
    case Kind::TokenVector:
    case Kind::StringVector: return nameListText(v.strings);
    case Kind::PathVector: return pathListText(v.strings);
    case Kind::DoubleVector: return typedValue(v, indent, path, spec);
    default: break;
  }
  if (isText(v.kind)) return typedValue(v, indent, path, spec);
  if (!isNumeric(v.kind)) return std::nullopt;
  int components = componentCount(v.kind);
  if (v.isArray) {  // untyped lists hold plain numbers only
    if (components != 1 || v.numbers.empty()) return std::nullopt;
    return typedValue(v, indent, path, spec);
  }
  if (components == 1) return typedValue(v, indent, path, spec);
  if (components > 4 && components != 16) return std::nullopt;
  std::string out = "(";  // untyped tuples are flat
  for (int i = 0; i < components; ++i) {
    if (i) out += ", ";
    appendNumber(out, v.numbers[size_t(i)], componentKind(v.kind));
  }
  return out + ")";
}

}  // namespace

std::string writeUsdaLayer(const Layer& layer, uint64_t maxBytes) { return UsdaWriter(layer, maxBytes).write(); }

}  // namespace sdg::usd
