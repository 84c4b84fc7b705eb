#include "usd/crate_builder.h"

#include <stdexcept>

#include "usd/integer_coding.h"
#include "usd/lz4_chunks.h"

namespace sdg::usd::test {

uint64_t rep(CrateType type, uint64_t payload, bool isArray, bool isInlined, bool isCompressed) {
  return (isArray ? uint64_t(1) << 63 : 0) | (isInlined ? uint64_t(1) << 62 : 0) |
         (isCompressed ? uint64_t(1) << 61 : 0) | uint64_t(type) << 48 | (payload & ((uint64_t(1) << 48) - 1));
}

CrateBuilder::CrateBuilder(uint8_t minor, uint8_t patch) : minor_(minor), patch_(patch) {
  bytes_.assign(88, 0);
  std::memcpy(bytes_.data(), "PXR-USDC", 8);
  bytes_[9] = minor_;
  bytes_[10] = patch_;
  path("/");  // the root: path index 0, the empty element token 0
}

uint32_t CrateBuilder::token(const std::string& s) {
  auto [it, added] = tokenIndex_.emplace(s, uint32_t(tokens_.size()));
  if (added) tokens_.push_back(s);
  return it->second;
}

uint32_t CrateBuilder::string(const std::string& s) {
  strings_.push_back(token(s));
  return uint32_t(strings_.size() - 1);
}

uint32_t CrateBuilder::emptyPath() { return pathCount_++; }

uint32_t CrateBuilder::path(const std::string& p) { return nodes_[node(p)].index; }

// Splits a test path into parent and last element, the way Sdf composes
// them: "/A/B", "/A.prop" (a prim property: its name token, negated),
// "/A{set=sel}", "/A{set=sel}B", "/A.rel[/T]", "/A.rel[/T].attr".
size_t CrateBuilder::node(const std::string& p) {
  if (auto it = nodeOf_.find(p); it != nodeOf_.end()) return it->second;
  PathNode n;
  std::string parent;
  if (p == "/") {
    n.element = "";
  } else if (p.back() == ']') {
    size_t open = p.rfind('[');
    parent = p.substr(0, open), n.element = p.substr(open);
  } else if (p.back() == '}') {
    size_t open = p.rfind('{');
    parent = p.substr(0, open), n.element = p.substr(open);
  } else {
    size_t cut = p.find_last_of("/.}]");
    if (p[cut] == '/') {
      parent = cut == 0 ? "/" : p.substr(0, cut), n.element = p.substr(cut + 1);
    } else if (p[cut] == '}') {
      parent = p.substr(0, cut + 1), n.element = p.substr(cut + 1);
    } else if (p[cut] == '.') {
      parent = p.substr(0, cut);
      n.isProperty = parent.find_first_of(".[") == std::string::npos;
      n.element = n.isProperty ? p.substr(cut + 1) : p.substr(cut);
    } else {
      throw std::invalid_argument("test path " + p);
    }
  }
  size_t parentNode = parent.empty() ? SIZE_MAX : node(parent);
  n.index = pathCount_++;
  token(n.element);
  nodes_.push_back(n);
  size_t id = nodes_.size() - 1;
  if (parentNode != SIZE_MAX) nodes_[parentNode].children.push_back(id);
  nodeOf_[p] = id;
  return id;
}

template <class Int>
uint64_t CrateBuilder::putCompressed(const std::vector<Int>& values) {
  auto framed = compressLz4Chunks(encodeIntegers<Int>(values));
  uint64_t at = put<uint64_t>(framed.size());
  putBytes(framed);
  return at;
}
template uint64_t CrateBuilder::putCompressed(const std::vector<int32_t>&);
template uint64_t CrateBuilder::putCompressed(const std::vector<uint32_t>&);
template uint64_t CrateBuilder::putCompressed(const std::vector<int64_t>&);
template uint64_t CrateBuilder::putCompressed(const std::vector<uint64_t>&);

uint32_t CrateBuilder::field(const std::string& name, uint64_t valueRep) {
  fieldTokens_.push_back(token(name));
  fieldReps_.push_back(valueRep);
  return uint32_t(fieldTokens_.size() - 1);
}

void CrateBuilder::spec(const std::string& p, SpecType type, const std::vector<uint32_t>& fields) {
  specPaths_.push_back(path(p));
  specFieldSets_.push_back(uint32_t(fieldSets_.size()));
  specTypes_.push_back(uint32_t(type));
  fieldSets_.insert(fieldSets_.end(), fields.begin(), fields.end());
  fieldSets_.push_back(kFieldSetEnd);
}

// Depth first: a node, then its subtree, then its next sibling; the jump of
// a node with both a child and a sibling is the distance to the sibling.
void CrateBuilder::encodeTree(size_t n, std::vector<uint32_t>& indexes, std::vector<int32_t>& tokens,
                              std::vector<int32_t>& jumps) {
  const auto& kids = nodes_[n].children;
  for (size_t k = 0; k < kids.size(); ++k) {
    const PathNode& child = nodes_[kids[k]];
    size_t at = indexes.size();
    indexes.push_back(child.index);
    int32_t t = int32_t(tokenIndex_.at(child.element));
    tokens.push_back(child.isProperty ? -t : t);
    jumps.push_back(0);
    bool hasChild = !child.children.empty(), hasSibling = k + 1 < kids.size();
    if (hasChild) encodeTree(kids[k], indexes, tokens, jumps);
    jumps[at] = hasChild && hasSibling ? int32_t(indexes.size() - at) : hasChild ? -1 : hasSibling ? 0 : -2;
  }
}

std::vector<uint8_t> CrateBuilder::finish() {
  auto section = [this](const char* name, auto write) {
    uint64_t start = tell();
    write();
    sections_[name] = {name, start, tell() - start};
  };
  section("TOKENS", [this] {
    std::vector<uint8_t> chars;
    for (const auto& t : tokens_) chars.insert(chars.end(), t.c_str(), t.c_str() + t.size() + 1);
    auto framed = compressLz4Chunks(chars);
    put<uint64_t>(tokens_.size());
    put<uint64_t>(chars.size());
    put<uint64_t>(framed.size());
    putBytes(framed);
  });
  section("STRINGS", [this] {
    put<uint64_t>(strings_.size());
    putAll(strings_);
  });
  section("FIELDS", [this] {
    put<uint64_t>(fieldTokens_.size());
    putCompressed(fieldTokens_);
    auto framed = compressLz4Chunks(
        std::span(reinterpret_cast<const uint8_t*>(fieldReps_.data()), fieldReps_.size() * 8));
    put<uint64_t>(framed.size());
    putBytes(framed);
  });
  section("FIELDSETS", [this] {
    put<uint64_t>(fieldSets_.size());
    putCompressed(fieldSets_);
  });
  section("PATHS", [this] {
    std::vector<uint32_t> indexes{nodes_[0].index};
    std::vector<int32_t> tokens{0}, jumps{nodes_[0].children.empty() ? -2 : -1};
    encodeTree(0, indexes, tokens, jumps);
    if (editPathTree) editPathTree(indexes, tokens, jumps);
    put<uint64_t>(pathCount_);
    put<uint64_t>(indexes.size());
    putCompressed(indexes);
    putCompressed(tokens);
    putCompressed(jumps);
  });
  section("SPECS", [this] {
    put<uint64_t>(specPaths_.size());
    putCompressed(specPaths_);
    putCompressed(specFieldSets_);
    putCompressed(specTypes_);
  });
  tocOffset_ = tell();
  put<uint64_t>(sections_.size());
  for (const char* name : {"TOKENS", "STRINGS", "FIELDS", "FIELDSETS", "PATHS", "SPECS"}) {
    char padded[16] = {};
    std::strncpy(padded, name, 15);
    put(padded);
    put<int64_t>(int64_t(sections_[name].start));
    put<int64_t>(int64_t(sections_[name].size));
  }
  std::memcpy(bytes_.data() + 16, &tocOffset_, 8);
  return bytes_;
}

}  // namespace sdg::usd::test
