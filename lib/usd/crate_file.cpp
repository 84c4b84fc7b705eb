#include "usd/crate_file.h"

#include <algorithm>
#include <array>
#include <cstring>

#include "usd/crate_bytes.h"
#include "usd/integer_coding.h"
#include "usd/lz4_chunks.h"

namespace sdg::usd {

namespace {

constexpr uint64_t kBootstrapBytes = 88;  // ident, version, toc offset, 8 reserved int64s
constexpr uint64_t kSectionEntryBytes = 32;  // 16-byte name, start, size
constexpr const char* kSectionNames[] = {"TOKENS", "STRINGS", "FIELDS", "FIELDSETS", "PATHS", "SPECS"};
constexpr uint32_t kMaxSpecType = uint32_t(SpecType::VariantSet);

const char* const kTypeNames[] = {
    "Invalid", "Bool", "UChar", "Int", "UInt", "Int64", "UInt64", "Half", "Float", "Double", "String", "Token",
    "AssetPath", "Matrix2d", "Matrix3d", "Matrix4d", "Quatd", "Quatf", "Quath", "Vec2d", "Vec2f", "Vec2h",
    "Vec2i", "Vec3d", "Vec3f", "Vec3h", "Vec3i", "Vec4d", "Vec4f", "Vec4h", "Vec4i", "Dictionary",
    "TokenListOp", "StringListOp", "PathListOp", "ReferenceListOp", "IntListOp", "Int64ListOp", "UIntListOp",
    "UInt64ListOp", "PathVector", "TokenVector", "Specifier", "Permission", "Variability",
    "VariantSelectionMap", "TimeSamples", "Payload", "DoubleVector", "LayerOffsetVector", "StringVector",
    "ValueBlock", "Value", "UnregisteredValue", "UnregisteredValueListOp", "PayloadListOp", "TimeCode",
    "PathExpression", "Relocates"};

// A compressed integer stream of a structural section.
template <class Int>
std::vector<Int> readCompressedInts(ByteCursor& in, uint64_t count, const ReadLimits& limits, const char* what) {
  return readCompressedIntegers<Int>(in, count, limits.maxArrayElements, what);
}

}  // namespace

std::string CrateVersion::str() const {
  return std::to_string(major) + "." + std::to_string(minor) + "." + std::to_string(patch);
}

const char* crateTypeName(uint8_t type) {
  return type < std::size(kTypeNames) ? kTypeNames[type] : "unknown";
}

void throwCrateError(const std::string& identifier, const std::string& where, const std::string& what) {
  throw usdErrorAt(SourceLoc(identifier, 0, 0), "crate " + where + ": " + what);
}

CrateFile::CrateFile(std::span<const uint8_t> bytes, std::string identifier, const ReadLimits& limits)
    : bytes_(bytes), identifier_(std::move(identifier)), limits_(limits) {
  try {
    if (bytes_.size() > limits_.maxFileBytes)
      throw CodingError("the file's " + std::to_string(bytes_.size()) + " bytes exceed the limit of " +
                        std::to_string(limits_.maxFileBytes));
    readBootstrap();
    readTableOfContents();
    readTokens();
    readStrings();
    readFields();
    readFieldSets();
    readPaths();
    readSpecs();
  } catch (const CodingError& e) {
    throwCrateError(identifier_, where_, e.what());
  } catch (const std::bad_alloc&) {
    throwCrateError(identifier_, where_, "out of memory");
  }
}

const std::string& CrateFile::token(uint64_t index) const {
  if (index >= tokens_.size())
    throw CodingError("token index " + std::to_string(index) + " is past the " + std::to_string(tokens_.size()) +
                      " tokens");
  return tokens_[index];
}

const std::string& CrateFile::string(uint64_t index) const {
  if (index >= strings_.size())
    throw CodingError("string index " + std::to_string(index) + " is past the " +
                      std::to_string(strings_.size()) + " strings");
  return tokens_[strings_[index]];
}

const std::string& CrateFile::path(uint64_t index) const {
  if (index >= paths_.size())
    throw CodingError("path index " + std::to_string(index) + " is past the " + std::to_string(paths_.size()) +
                      " paths");
  return paths_[index];
}

void CrateFile::readBootstrap() {
  where_ = "bootstrap";
  if (bytes_.size() < 8 || std::memcmp(bytes_.data(), "PXR-USDC", 8) != 0)
    throw CodingError("the file does not start with \"PXR-USDC\" (not a crate file)");
  if (bytes_.size() < kBootstrapBytes)
    throw CodingError("the file has " + std::to_string(bytes_.size()) + " bytes, fewer than the " +
                      std::to_string(kBootstrapBytes) + " of the bootstrap (truncated)");
  ByteCursor in(bytes_, 8, kBootstrapBytes);
  auto version = in.read<std::array<uint8_t, 8>>("version");
  version_ = {version[0], version[1], version[2]};
  if (!version_.atLeast(kOldestCrateVersion.major, kOldestCrateVersion.minor) || version_.major != 0 ||
      version_.minor > kNewestCrateVersion.minor)
    throw CodingError("version " + version_.str() + " is not supported (this reader reads " +
                      kOldestCrateVersion.str() + " to " + std::to_string(kNewestCrateVersion.major) + "." +
                      std::to_string(kNewestCrateVersion.minor) + ".x)");
  auto tocOffset = in.read<int64_t>("table of contents offset");
  if (tocOffset < int64_t(kBootstrapBytes) || uint64_t(tocOffset) >= bytes_.size())
    throw CodingError("the table of contents is at offset " + std::to_string(tocOffset) +
                      ", outside the file's " + std::to_string(bytes_.size()) + " bytes (truncated?)");
  tocOffset_ = uint64_t(tocOffset);
}

void CrateFile::readTableOfContents() {
  where_ = "table of contents";
  ByteCursor in(bytes_, tocOffset_, bytes_.size());
  auto count = in.readCount("section count", kSectionEntryBytes);
  for (uint64_t i = 0; i < count; ++i) {
    auto rawName = in.read<std::array<char, 16>>("section name");
    if (std::find(rawName.begin(), rawName.end(), '\0') == rawName.end())
      throw CodingError("section " + std::to_string(i) + "'s name is not NUL-terminated");
    CrateSection s{rawName.data(), 0, 0};
    auto start = in.read<int64_t>("section start");
    auto size = in.read<int64_t>("section size");
    if (start < int64_t(kBootstrapBytes) || size < 0 || uint64_t(start) > bytes_.size() ||
        uint64_t(size) > bytes_.size() - uint64_t(start))
      throw CodingError("section " + s.name + " (bytes " + std::to_string(start) + " + " + std::to_string(size) +
                        ") lies outside the file's " + std::to_string(bytes_.size()) + " bytes (truncated?)");
    s.start = uint64_t(start), s.size = uint64_t(size);
    for (const auto& other : sections_) {
      if (other.name == s.name) throw CodingError("section " + s.name + " appears twice");
      if (s.size > 0 && other.size > 0 && s.start < other.start + other.size && other.start < s.start + s.size)
        throw CodingError("sections " + other.name + " and " + s.name + " overlap");
    }
    sections_.push_back(std::move(s));
  }
  for (const char* name : kSectionNames) section(name);
}

const CrateSection& CrateFile::section(const char* name) const {
  for (const auto& s : sections_)
    if (s.name == name) return s;
  throw CodingError(std::string("the ") + name + " section is missing");
}

ByteCursor CrateFile::enterSection(const char* name) {
  where_ = std::string(name) + " section";
  const auto& s = section(name);
  return ByteCursor(bytes_, s.start, s.start + s.size);
}

void CrateFile::readTokens() {
  ByteCursor in = enterSection("TOKENS");
  auto count = in.read<uint64_t>("token count");
  auto size = in.read<uint64_t>("token bytes");
  auto compressedSize = in.read<uint64_t>("compressed token bytes");
  auto framed = in.take(compressedSize, "compressed tokens");
  if (size > maxLz4Expansion(compressedSize) || size > limits_.maxDecompressedBytes)
    throw CodingError("claims " + std::to_string(size) + " bytes of tokens from " +
                      std::to_string(compressedSize) + " compressed bytes");
  if (count > size)
    throw CodingError("claims " + std::to_string(count) + " tokens in " + std::to_string(size) + " bytes");
  std::vector<uint8_t> chars(size);
  if (size > 0) {
    size_t n = decompressLz4Chunks(framed, chars);
    if (n != size)
      throw CodingError("tokens decompress to " + std::to_string(n) + " bytes, not the " + std::to_string(size) +
                        " claimed");
    if (chars.back() != 0) throw CodingError("the last token is not NUL-terminated");
  }
  tokens_.reserve(count);
  const char* p = reinterpret_cast<const char*>(chars.data());
  const char* end = p + chars.size();
  while (p < end && tokens_.size() < count) {
    size_t len = std::strlen(p);
    tokens_.emplace_back(p, len);
    p += len + 1;
  }
  if (tokens_.size() != count)
    throw CodingError("claims " + std::to_string(count) + " tokens, holds " + std::to_string(tokens_.size()));
}

void CrateFile::readStrings() {
  ByteCursor in = enterSection("STRINGS");
  auto count = in.readCount("string count", 4);
  strings_.resize(count);
  for (auto& index : strings_) {
    index = in.read<uint32_t>("string");
    if (index >= tokens_.size())
      throw CodingError("string's token index " + std::to_string(index) + " is past the " +
                        std::to_string(tokens_.size()) + " tokens");
  }
}

void CrateFile::readFields() {
  ByteCursor in = enterSection("FIELDS");
  auto count = in.read<uint64_t>("field count");
  auto tokens = readCompressedInts<uint32_t>(in, count, limits_, "field names");
  auto repsSize = in.read<uint64_t>("value reps size");
  auto framed = in.take(repsSize, "value reps");
  if (count * 8 > maxLz4Expansion(repsSize))
    throw CodingError(std::to_string(count) + " value reps cannot be coded in " + std::to_string(repsSize) +
                      " bytes");
  std::vector<uint64_t> reps(count);
  if (count > 0) {
    size_t n = decompressLz4Chunks(framed, std::span(reinterpret_cast<uint8_t*>(reps.data()), count * 8));
    if (n != count * 8)
      throw CodingError("value reps decompress to " + std::to_string(n) + " bytes, not the " +
                        std::to_string(count * 8) + " of " + std::to_string(count) + " fields");
  }
  fields_.resize(count);
  for (uint64_t i = 0; i < count; ++i) {
    if (tokens[i] >= tokens_.size())
      throw CodingError("field " + std::to_string(i) + "'s name token " + std::to_string(tokens[i]) +
                        " is past the " + std::to_string(tokens_.size()) + " tokens");
    fields_[i] = {tokens[i], ValueRep{reps[i]}};
  }
}

void CrateFile::readFieldSets() {
  ByteCursor in = enterSection("FIELDSETS");
  auto count = in.read<uint64_t>("field set count");
  fieldSets_ = readCompressedInts<uint32_t>(in, count, limits_, "field sets");
  if (!fieldSets_.empty() && fieldSets_.back() != kFieldSetEnd)
    throw CodingError("the last field set is not terminated");
  for (size_t i = 0; i < fieldSets_.size(); ++i)
    if (fieldSets_[i] != kFieldSetEnd && fieldSets_[i] >= fields_.size())
      throw CodingError("entry " + std::to_string(i) + " names field " + std::to_string(fieldSets_[i]) +
                        ", past the " + std::to_string(fields_.size()) + " fields");
}

void CrateFile::readPaths() {
  ByteCursor in = enterSection("PATHS");
  auto total = in.read<uint64_t>("path count");
  auto encoded = in.read<uint64_t>("encoded path count");
  // Only the empty path is left out of the tree, and a file holds it once;
  // a little slack for other writers, but no huge table of empty paths.
  if (encoded > total || total - encoded > 1024)
    throw CodingError("claims " + std::to_string(total) + " paths of which " + std::to_string(encoded) +
                      " are encoded");
  auto pathIndexes = readCompressedInts<uint32_t>(in, encoded, limits_, "path indexes");
  auto elementTokens = readCompressedInts<int32_t>(in, encoded, limits_, "path element tokens");
  auto jumps = readCompressedInts<int32_t>(in, encoded, limits_, "path jumps");
  paths_.assign(total, std::string());
  if (encoded > 0) buildPathTree(pathIndexes, elementTokens, jumps);
}

// Walks the encoded tree depth first: each node either has a child (the
// next node), a sibling (`jump` nodes on), both, or neither (-2). Iterative,
// so that a deep tree cannot exhaust the stack; every node is visited at
// most once (a path index assigned twice is an error), so the walk ends.
void CrateFile::buildPathTree(const std::vector<uint32_t>& pathIndexes, const std::vector<int32_t>& elementTokens,
                              const std::vector<int32_t>& jumps) {
  const size_t n = pathIndexes.size();
  std::vector<uint8_t> assigned(paths_.size(), 0);
  std::vector<uint32_t> depth(paths_.size(), 0);
  struct Pending {
    size_t node;
    int64_t parent;  // path index of the parent, -1 for the root
  };
  std::vector<Pending> siblings;
  size_t node = 0;
  int64_t parent = -1;
  const uint64_t maxDepth = uint64_t(limits_.maxNesting) * 2;  // prim nesting plus variants and properties
  // Every step assigns a path index not assigned before, so the walk ends.
  for (;;) {
    if (node >= n)
      throw CodingError("the path tree jumps to node " + std::to_string(node) + " of " + std::to_string(n));
    uint32_t index = pathIndexes[node];
    if (index >= paths_.size())
      throw CodingError("node " + std::to_string(node) + " has path index " + std::to_string(index) +
                        ", past the " + std::to_string(paths_.size()) + " paths");
    if (assigned[index]) throw CodingError("path index " + std::to_string(index) + " appears twice in the tree");
    assigned[index] = 1;
    std::string& path = paths_[index];
    if (parent < 0) {
      path = "/";
    } else {
      int64_t tokenIndex = elementTokens[node];
      bool isProperty = tokenIndex < 0;
      const std::string& element = token(uint64_t(isProperty ? -tokenIndex : tokenIndex));
      if (element.empty()) throw CodingError("node " + std::to_string(node) + " has an empty name");
      const std::string& parentPath = paths_[size_t(parent)];
      depth[index] = depth[size_t(parent)] + 1;
      if (depth[index] > maxDepth)
        throw CodingError("the path tree is deeper than " + std::to_string(maxDepth) + " elements");
      path.reserve(parentPath.size() + element.size() + 1);
      path = parentPath;
      if (isProperty) {
        path += '.';
      } else if (element[0] != '.' && element[0] != '[' && element[0] != '{' && path != "/" && path.back() != '}') {
        path += '/';  // a prim child (after a variant selection "}" the name follows directly)
      }
      path += element;
    }
    int32_t jump = jumps[node];
    bool hasChild = jump > 0 || jump == -1;
    bool hasSibling = jump >= 0;
    if (hasChild && hasSibling) {
      uint64_t sibling = uint64_t(node) + uint64_t(jump);
      siblings.push_back({size_t(std::min<uint64_t>(sibling, n)), parent});
    }
    if (hasChild) {
      parent = index;
      ++node;
    } else if (hasSibling) {
      ++node;
    } else if (!siblings.empty()) {
      node = siblings.back().node;
      parent = siblings.back().parent;
      siblings.pop_back();
    } else {
      break;
    }
  }
}

void CrateFile::readSpecs() {
  ByteCursor in = enterSection("SPECS");
  auto count = in.read<uint64_t>("spec count");
  if (count > limits_.maxSpecs)
    throw CodingError(std::to_string(count) + " specs exceed the limit of " + std::to_string(limits_.maxSpecs));
  auto pathIndexes = readCompressedInts<uint32_t>(in, count, limits_, "spec paths");
  auto fieldSets = readCompressedInts<uint32_t>(in, count, limits_, "spec field sets");
  auto types = readCompressedInts<uint32_t>(in, count, limits_, "spec types");
  specs_.resize(count);
  for (uint64_t i = 0; i < count; ++i) {
    std::string which = "spec " + std::to_string(i);
    if (pathIndexes[i] >= paths_.size() || paths_[pathIndexes[i]].empty())
      throw CodingError(which + " has no path (path index " + std::to_string(pathIndexes[i]) + ")");
    if (fieldSets[i] >= fieldSets_.size() && !(fieldSets[i] == 0 && fieldSets_.empty()))
      throw CodingError(which + " <" + paths_[pathIndexes[i]] + "> has field set " + std::to_string(fieldSets[i]) +
                        ", past the " + std::to_string(fieldSets_.size()) + " entries");
    if (fieldSets[i] > 0 && fieldSets_[fieldSets[i] - 1] != kFieldSetEnd)
      throw CodingError(which + " <" + paths_[pathIndexes[i]] + ">'s field set " + std::to_string(fieldSets[i]) +
                        " starts inside another one");
    if (types[i] == 0 || types[i] > kMaxSpecType)
      throw CodingError(which + " <" + paths_[pathIndexes[i]] + "> has spec type " + std::to_string(types[i]) +
                        " (known: 1 to " + std::to_string(kMaxSpecType) + ")");
    specs_[i] = {pathIndexes[i], fieldSets[i], types[i]};
  }
}

}  // namespace sdg::usd
