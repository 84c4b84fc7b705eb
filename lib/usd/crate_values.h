#pragma once
// Decoding the field values of a crate file into usd::Value. A field's
// ValueRep either holds the value (ints, floats, halves, enums, token and
// string indexes; small vectors and diagonal matrices as int8s; empty
// dictionaries) or the file offset of its data: arrays (plain, or with
// compressed integers, or floats coded as integers or as a lookup table),
// dictionaries, list ops, references and payloads, path/token/string/
// double/layer-offset vectors, variant selections and time samples. The
// layout of each differs by crate version (array sizes 32-bit before 0.7.0,
// compression from 0.5.0/0.6.0, payload layer offsets from 0.8.0, TimeCode
// from 0.9.0, path expressions from 0.10.0, relocates from 0.11.0).
//
// A type this reader does not interpret (unregistered values, path
// expressions, relocates, a type number past the known ones) becomes
// Kind::Unsupported: strings[0] names the crate type, enumValue holds its
// number, and for path expressions and relocates strings[1..] hold the text.
#include <cstdint>
#include <unordered_map>

#include "usd/crate_bytes.h"
#include "usd/crate_file.h"
#include "usd/value.h"

namespace sdg::usd {

class CrateValueReader {
 public:
  explicit CrateValueReader(const CrateFile& crate);

  // Throws CodingError for data out of range, nesting deeper than
  // limits.maxNesting, arrays over limits.maxArrayElements, or decoded values
  // that add up to more than limits.maxDecompressedBytes (a hostile file
  // can make many fields share one large value).
  Value read(ValueRep rep) { return unpack(rep, 0); }

 private:
  Value unpack(ValueRep rep, uint32_t depth);
  Value unpackOutOfLine(ValueRep rep, uint32_t depth);
  Value unpackNumeric(ValueRep rep, uint8_t type);
  Value unpackNumericArray(ValueRep rep, uint8_t type);
  Value unpackTextArray(ValueRep rep, Kind kind);
  Value readVtValue(ByteCursor& in, uint32_t depth);
  Dictionary readDictionary(ByteCursor& in, uint32_t depth);
  Reference readReference(ByteCursor& in, uint32_t depth, bool isPayload);
  Value readTimeSamples(ByteCursor& in, uint32_t depth);
  uint64_t readArraySize(ByteCursor& in);
  Value textValue(Kind kind, std::string s);
  ByteCursor at(uint64_t offset);
  void charge(uint64_t bytes);

  const CrateFile& crate_;
  uint64_t budget_;
  std::unordered_map<uint64_t, Value> shared_;  // decoded values by rep bits (see unpack)
};

}  // namespace sdg::usd
