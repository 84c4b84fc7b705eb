#pragma once
// The structure of a USD crate (.usdc) file, as Pixar's crate format lays it
// out: an 88-byte bootstrap ("PXR-USDC", version, offset of the table of
// contents), the table of contents (named sections: start and size), and
// six structural sections, all compressed since version 0.4.0:
//   TOKENS     every token, NUL-separated, LZ4-framed
//   STRINGS    string table: token indexes
//   FIELDS     (token index, value rep) per field
//   FIELDSETS  runs of field indexes, each run ended by ~0
//   PATHS      the path tree: path index, element token (negative for a
//              prim property) and a jump to the next sibling per node
//   SPECS      (path index, field set index, spec type) per spec
// CrateFile reads and checks all of it; the values themselves (inlined in a
// rep or stored elsewhere in the file) are crate_values.h's job.
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "usd/crate_bytes.h"
#include "usd/layer.h"

namespace sdg::usd {

struct CrateVersion {
  uint8_t major = 0, minor = 0, patch = 0;
  bool atLeast(uint8_t maj, uint8_t min, uint8_t pat = 0) const {
    return (uint32_t(major) << 16 | uint32_t(minor) << 8 | patch) >=
           (uint32_t(maj) << 16 | uint32_t(min) << 8 | pat);
  }
  std::string str() const;
};

// The value types of crate files, numbered as the format numbers them.
enum class CrateType : uint8_t {
  Invalid = 0,
  Bool = 1, UChar, Int, UInt, Int64, UInt64, Half, Float, Double,
  String = 10, Token, AssetPath, Matrix2d, Matrix3d, Matrix4d, Quatd, Quatf, Quath,
  Vec2d = 19, Vec2f, Vec2h, Vec2i, Vec3d, Vec3f, Vec3h, Vec3i, Vec4d, Vec4f, Vec4h, Vec4i,
  Dictionary = 31, TokenListOp, StringListOp, PathListOp, ReferenceListOp, IntListOp, Int64ListOp,
  UIntListOp, UInt64ListOp, PathVector, TokenVector, Specifier, Permission, Variability,
  VariantSelectionMap = 45, TimeSamples, Payload, DoubleVector, LayerOffsetVector, StringVector,
  ValueBlock = 51, Value, UnregisteredValue, UnregisteredValueListOp, PayloadListOp,
  TimeCode = 56,        // crate 0.9.0
  PathExpression = 57,  // crate 0.10.0
  Relocates = 58,       // crate 0.11.0
};
const char* crateTypeName(uint8_t type);  // "Vec3f", ...; "unknown" past Relocates

// How a field's value is stored: type, flags and a 48-bit payload (the value
// itself when inlined, else the file offset of its data).
struct ValueRep {
  uint64_t bits = 0;
  uint8_t type() const { return uint8_t(bits >> 48); }
  bool isArray() const { return bits >> 63; }
  bool isInlined() const { return (bits >> 62) & 1; }
  bool isCompressed() const { return (bits >> 61) & 1; }
  uint64_t payload() const { return bits & ((uint64_t(1) << 48) - 1); }
  uint32_t payload32() const { return uint32_t(bits); }
};

struct CrateField {
  uint32_t token;
  ValueRep rep;
};

struct CrateSpec {
  uint32_t path;
  uint32_t fieldSet;  // index of the first field index of its run in fieldSets
  uint32_t type;      // SpecType's number
};

struct CrateSection {
  std::string name;
  uint64_t start = 0, size = 0;
};

inline constexpr uint32_t kFieldSetEnd = ~uint32_t(0);

// The oldest and newest crate versions this reader understands.
inline constexpr CrateVersion kOldestCrateVersion{0, 4, 0};
inline constexpr CrateVersion kNewestCrateVersion{0, 11, 0};

// Throws the UsdError of a crate file: "<file>: crate <where>: <what>".
[[noreturn]] void throwCrateError(const std::string& identifier, const std::string& where, const std::string& what);

class CrateFile {
 public:
  // Reads and checks the bootstrap, the table of contents and the
  // structural sections of `bytes` (which must outlive this object).
  // Throws UsdError naming `identifier` and the section for anything
  // truncated, inconsistent or beyond `limits`.
  CrateFile(std::span<const uint8_t> bytes, std::string identifier, const ReadLimits& limits);

  std::span<const uint8_t> bytes() const { return bytes_; }
  const std::string& identifier() const { return identifier_; }
  const ReadLimits& limits() const { return limits_; }
  CrateVersion version() const { return version_; }
  const std::vector<CrateSection>& sections() const { return sections_; }

  const std::vector<std::string>& tokens() const { return tokens_; }
  const std::vector<CrateField>& fields() const { return fields_; }
  const std::vector<uint32_t>& fieldSets() const { return fieldSets_; }
  const std::vector<std::string>& paths() const { return paths_; }  // "" where the file's path is the empty path
  const std::vector<CrateSpec>& specs() const { return specs_; }

  // Table lookups that throw CodingError for an index out of range.
  const std::string& token(uint64_t index) const;
  const std::string& string(uint64_t index) const;
  const std::string& path(uint64_t index) const;

 private:
  void readBootstrap();
  void readTableOfContents();
  const CrateSection& section(const char* name) const;
  ByteCursor enterSection(const char* name);  // a cursor over the section; errors name it
  void readTokens();
  void readStrings();
  void readFields();
  void readFieldSets();
  void readPaths();
  void buildPathTree(const std::vector<uint32_t>& pathIndexes, const std::vector<int32_t>& elementTokens,
                     const std::vector<int32_t>& jumps);
  void readSpecs();

  std::span<const uint8_t> bytes_;
  std::string identifier_;
  ReadLimits limits_;
  std::string where_ = "bootstrap";  // what is being read, for error messages
  CrateVersion version_;
  uint64_t tocOffset_ = 0;
  std::vector<CrateSection> sections_;
  std::vector<std::string> tokens_;
  std::vector<uint32_t> strings_;  // token indexes
  std::vector<CrateField> fields_;
  std::vector<uint32_t> fieldSets_;
  std::vector<std::string> paths_;
  std::vector<CrateSpec> specs_;
};

}  // namespace sdg::usd
