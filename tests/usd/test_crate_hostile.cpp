// Hostile crate files: truncated at every length, every bit flipped, and
// headers crafted to lie (huge counts, offsets past the end, overlapping
// sections, LZ4 chunk sizes that lie, looping or deep path trees, values
// that contain themselves). Each must fail with a UsdError naming the file
// and the section, never crash or allocate without bound.
#include <catch2/catch.hpp>

#include <memory>

#include "usd/crate_builder.h"
#include "usd/layer_io.h"

using namespace sdg::usd;
using namespace sdg::usd::test;
using T = CrateType;

namespace {

// A small file with a bit of everything: a dictionary, list ops, a
// compressed int array, a float array coded as ints, time samples, strings.
std::vector<uint8_t> richCrateFile() {
  CrateBuilder b;
  std::vector<int32_t> ints;
  for (int i = 0; i < 40; ++i) ints.push_back(i * 7 % 13);
  uint64_t intArray = b.put<uint64_t>(ints.size());
  b.putCompressed(ints);
  uint64_t floatArray = b.put<uint64_t>(20);
  b.put('i');
  b.putCompressed(std::vector<int32_t>(20, 3));
  uint64_t dict = b.put<uint64_t>(1);
  b.put(b.string("key")), b.put<int64_t>(8), b.put(rep(T::String, b.string("value")));
  uint64_t times = b.put<uint64_t>(2);
  b.putAll(std::vector<double>{0, 10});
  uint64_t samples = b.put<int64_t>(8);
  b.put(rep(T::DoubleVector, times)), b.put<int64_t>(8), b.put<uint64_t>(2);
  b.put(inlined(T::Vec3f, 0x010203)), b.put(inlined(T::Vec3f, 0));
  uint64_t apis = b.put<uint8_t>(1 << 5);
  b.put<uint64_t>(1), b.put(b.token("MaterialBindingAPI"));
  uint64_t children = b.put<uint64_t>(1);
  b.put(b.token("Mesh"));
  uint64_t props = b.put<uint64_t>(2);
  b.put(b.token("faceVertexIndices")), b.put(b.token("widths"));
  b.spec("/", SpecType::PseudoRoot,
         {b.field("primChildren", rep(T::TokenVector, children)), b.field("customLayerData", rep(T::Dictionary, dict))});
  b.spec("/Mesh", SpecType::Prim,
         {b.field("specifier", rep(T::Specifier, 0)), b.field("typeName", rep(T::Token, b.token("Mesh"))),
          b.field("apiSchemas", rep(T::TokenListOp, apis)), b.field("properties", rep(T::TokenVector, props))});
  b.spec("/Mesh.faceVertexIndices", SpecType::Attribute,
         {b.field("default", rep(T::Int, intArray, true, false, true)),
          b.field("timeSamples", rep(T::TimeSamples, samples))});
  b.spec("/Mesh.widths", SpecType::Attribute, {b.field("default", rep(T::Float, floatArray, true, false, true))});
  return b.finish();
}

// Reads `bytes`: true when it parses, false when it fails with a UsdError
// naming the file; anything else (another exception) fails the test.
bool readsOrFailsCleanly(const std::vector<uint8_t>& bytes, const ReadLimits& limits = {}) {
  try {
    readCrateLayer(bytes, "hostile.usdc", limits);
    return true;
  } catch (const UsdError& e) {
    INFO(e.what());
    CHECK(std::string(e.what()).rfind("hostile.usdc: crate ", 0) == 0);
    CHECK(e.loc().file.str() == "hostile.usdc");
    return false;
  }
}

std::string errorOf(const std::vector<uint8_t>& bytes, const ReadLimits& limits = {}) {
  try {
    readCrateLayer(bytes, "hostile.usdc", limits);
  } catch (const UsdError& e) {
    return e.what();
  }
  return "(no error)";
}

const Spec& specAt(const Layer& layer, const std::string& path) {
  const Spec* spec = layer.spec(path);
  INFO(path);
  REQUIRE(spec);
  return *spec;
}

template <class V>
void poke(std::vector<uint8_t>& bytes, uint64_t at, V value) {
  std::memcpy(bytes.data() + at, &value, sizeof(V));
}

}  // namespace

TEST_CASE("crate: the rich test file reads", "[usd][crate][hostile]") {
  auto bytes = richCrateFile();
  Layer layer = readCrateLayer(bytes, "rich.usdc");
  CHECK(layer.specs.size() == 4);
  CHECK(specAt(layer, "/Mesh.widths").fields.at("default").numbers == std::vector<double>(20, 3.0));
}

TEST_CASE("crate: every truncation fails cleanly", "[usd][crate][hostile]") {
  auto bytes = richCrateFile();
  for (size_t n = 0; n < bytes.size(); ++n) {
    std::vector<uint8_t> prefix(bytes.begin(), bytes.begin() + ptrdiff_t(n));
    INFO("prefix of " << n << " bytes");
    CHECK_FALSE(readsOrFailsCleanly(prefix));
  }
  CHECK(errorOf(std::vector<uint8_t>(bytes.begin(), bytes.begin() + 50)) ==
        "hostile.usdc: crate bootstrap: the file has 50 bytes, fewer than the 88 of the bootstrap (truncated)");
  CHECK_THAT(errorOf(std::vector<uint8_t>(bytes.begin(), bytes.end() - 40)),
             Catch::Contains("hostile.usdc: crate table of contents:"));
}

TEST_CASE("crate: every flipped bit reads or fails cleanly", "[usd][crate][hostile]") {
  auto bytes = richCrateFile();
  int parsed = 0, failed = 0;
  for (size_t i = 0; i < bytes.size(); ++i) {
    for (int bit = 0; bit < 8; ++bit) {
      auto flipped = bytes;
      flipped[i] = uint8_t(flipped[i] ^ (1 << bit));
      INFO("byte " << i << " bit " << bit);
      (readsOrFailsCleanly(flipped) ? parsed : failed)++;
    }
  }
  // Flips inside values or reserved bytes still parse; flips in the
  // structure fail. Both happen.
  CHECK(parsed > 0);
  CHECK(failed > 0);
}

TEST_CASE("crate: lying headers", "[usd][crate][hostile]") {
  const auto good = richCrateFile();
  // Section starts, from the table of contents.
  uint64_t toc;
  std::memcpy(&toc, good.data() + 16, 8);
  auto sectionStart = [&](const char* name) -> uint64_t {
    for (uint64_t i = 0; i < 6; ++i) {
      uint64_t entry = toc + 8 + i * 32;
      if (std::strcmp(reinterpret_cast<const char*>(good.data() + entry), name) == 0) {
        uint64_t start;
        std::memcpy(&start, good.data() + entry + 16, 8);
        return start;
      }
    }
    FAIL("no section " << name);
    return 0;
  };

  SECTION("not a crate file, or a table of contents past the end") {
    auto bytes = good;
    bytes[0] = 'X';
    CHECK_THAT(errorOf(bytes), Catch::Contains("does not start with \"PXR-USDC\""));
    bytes = good;
    poke<int64_t>(bytes, 16, int64_t(bytes.size()) + 100);
    CHECK_THAT(errorOf(bytes), Catch::Contains("crate bootstrap: the table of contents is at offset"));
    poke<int64_t>(bytes, 16, -8);
    CHECK_THAT(errorOf(bytes), Catch::Contains("crate bootstrap: the table of contents is at offset -8"));
  }
  SECTION("a huge section count") {
    auto bytes = good;
    poke<uint64_t>(bytes, toc, uint64_t(1) << 60);
    CHECK_THAT(errorOf(bytes), Catch::Contains("crate table of contents: section count claims 1152921504606846976"));
  }
  SECTION("a section past the end, a negative size, overlapping sections, a missing one") {
    auto bytes = good;
    poke<int64_t>(bytes, toc + 8 + 16, int64_t(bytes.size()) - 4);
    CHECK_THAT(errorOf(bytes), Catch::Contains("lies outside the file's"));
    bytes = good;
    poke<int64_t>(bytes, toc + 8 + 24, -1);
    CHECK_THAT(errorOf(bytes), Catch::Contains("lies outside the file's"));
    bytes = good;
    poke<int64_t>(bytes, toc + 8 + 32 + 16, int64_t(sectionStart("TOKENS")) + 1);  // STRINGS inside TOKENS
    CHECK_THAT(errorOf(bytes), Catch::Contains("crate table of contents: sections TOKENS and STRINGS overlap"));
    bytes = good;
    std::memcpy(bytes.data() + toc + 8 + 5 * 32, "SPECZ", 5);
    CHECK_THAT(errorOf(bytes), Catch::Contains("crate table of contents: the SPECS section is missing"));
  }
  SECTION("token counts and sizes that lie") {
    const uint64_t tokens = sectionStart("TOKENS");
    auto bytes = good;
    poke<uint64_t>(bytes, tokens, uint64_t(1) << 40);
    CHECK_THAT(errorOf(bytes), Catch::Contains("crate TOKENS section: claims 1099511627776 tokens in"));
    bytes = good;
    poke<uint64_t>(bytes, tokens + 8, uint64_t(1) << 50);
    CHECK_THAT(errorOf(bytes), Catch::Contains("crate TOKENS section: claims 1125899906842624 bytes of tokens"));
    bytes = good;
    poke<uint64_t>(bytes, tokens + 16, uint64_t(1) << 62);
    CHECK_THAT(errorOf(bytes), Catch::Contains("crate TOKENS section: compressed tokens needs"));
    bytes = good;
    poke<uint64_t>(bytes, tokens + 8, 3);  // fewer bytes than the tokens decompress to
    CHECK_THAT(errorOf(bytes), Catch::Contains("crate TOKENS section: "));
  }
  SECTION("an LZ4 chunk size that lies") {
    const uint64_t framed = sectionStart("TOKENS") + 24;
    auto bytes = good;
    bytes[framed] = 1;  // one chunk: the next four bytes are taken as its size
    poke<int32_t>(bytes, framed + 1, 1 << 30);
    CHECK_THAT(errorOf(bytes), Catch::Contains("crate TOKENS section: LZ4 chunk 0 claims 1073741824 bytes"));
    bytes[framed] = 0x90;
    CHECK_THAT(errorOf(bytes), Catch::Contains("crate TOKENS section: LZ4 data claims 144 chunks"));
  }
  SECTION("compressed counts that the data cannot hold") {
    auto bytes = good;
    poke<uint64_t>(bytes, sectionStart("FIELDS"), uint64_t(1) << 27);
    CHECK_THAT(errorOf(bytes), Catch::Contains("crate FIELDS section: field names: 134217728 entries cannot be coded in"));
    bytes = good;
    poke<uint64_t>(bytes, sectionStart("SPECS"), uint64_t(1) << 40);
    CHECK_THAT(errorOf(bytes), Catch::Contains("crate SPECS section: 1099511627776 specs exceed the limit"));
    bytes = good;
    poke<uint64_t>(bytes, sectionStart("PATHS"), uint64_t(1) << 40);
    CHECK_THAT(errorOf(bytes), Catch::Contains("crate PATHS section: claims 1099511627776 paths of which"));
  }
}

TEST_CASE("crate: path trees that loop, climb too deep or collide", "[usd][crate][hostile]") {
  auto fourPaths = [] {
    auto b = std::make_unique<CrateBuilder>();
    b->spec("/", SpecType::PseudoRoot, {});
    b->spec("/A", SpecType::Prim, {});
    b->spec("/A/B", SpecType::Prim, {});
    b->spec("/C", SpecType::Prim, {});
    return b;
  };
  SECTION("the untouched tree reads") {
    auto b = fourPaths();
    auto bytes = b->finish();
    CHECK(readCrateLayer(bytes, "tree.usdc").spec("/A/B"));
  }
  SECTION("a node reached both in sequence and by a sibling jump") {
    auto b = fourPaths();  // nodes: / A B C; B claims C as its next sibling, A jumps to C too
    b->editPathTree = [](auto&, auto&, std::vector<int32_t>& jumps) { jumps[2] = 0; };
    auto bytes = b->finish();
    CHECK_THAT(errorOf(bytes), Catch::Contains("crate PATHS section: path index 3 appears twice in the tree"));
  }
  SECTION("a sibling jump past the last node") {
    auto b = fourPaths();
    b->editPathTree = [](auto&, auto&, std::vector<int32_t>& jumps) { jumps[1] = 100; };
    auto bytes = b->finish();
    CHECK_THAT(errorOf(bytes), Catch::Contains("crate PATHS section: the path tree jumps to node 4 of 4"));
  }
  SECTION("a tree cut short leaves specs without paths") {
    auto b = fourPaths();
    b->editPathTree = [](auto&, auto&, std::vector<int32_t>& jumps) { jumps[1] = -2; };
    auto bytes = b->finish();
    CHECK_THAT(errorOf(bytes), Catch::Contains("crate SPECS section: spec 2 has no path"));
  }
  SECTION("two nodes with one path index") {
    CrateBuilder b;
    b.spec("/", SpecType::PseudoRoot, {});
    b.spec("/A", SpecType::Prim, {});
    b.spec("/B", SpecType::Prim, {});
    b.editPathTree = [](std::vector<uint32_t>& indexes, auto&, auto&) { indexes[2] = indexes[1]; };
    auto bytes = b.finish();
    CHECK_THAT(errorOf(bytes), Catch::Contains("crate PATHS section: path index 1 appears twice in the tree"));
  }
  SECTION("an element token past the table") {
    CrateBuilder b;
    b.spec("/", SpecType::PseudoRoot, {});
    b.spec("/A", SpecType::Prim, {});
    b.editPathTree = [](auto&, std::vector<int32_t>& tokens, auto&) { tokens[1] = -2000000000; };
    auto bytes = b.finish();
    CHECK_THAT(errorOf(bytes), Catch::Contains("crate PATHS section: token index 2000000000 is past the"));
  }
  SECTION("a tree deeper than the nesting limit") {
    CrateBuilder b;
    b.spec("/", SpecType::PseudoRoot, {});
    std::string path;
    for (int i = 0; i < 600; ++i) path += "/N";
    b.spec(path, SpecType::Prim, {});
    auto bytes = b.finish();
    CHECK_THAT(errorOf(bytes), Catch::Contains("crate PATHS section: the path tree is deeper than 512 elements"));
    ReadLimits loose;
    loose.maxNesting = 1000;
    CHECK(readCrateLayer(bytes, "deep.usdc", loose).spec(path));
  }
}

TEST_CASE("crate: specs and fields that do not fit together", "[usd][crate][hostile]") {
  SECTION("no pseudo-root") {
    CrateBuilder b;
    b.spec("/A", SpecType::Prim, {});
    auto bytes = b.finish();
    CHECK(errorOf(bytes) == "hostile.usdc: crate SPECS section: there is no pseudo-root spec at </>");
  }
  SECTION("two specs at one path") {
    CrateBuilder b;
    b.spec("/", SpecType::PseudoRoot, {});
    b.spec("/A", SpecType::Prim, {});
    b.spec("/A", SpecType::Prim, {});
    auto bytes = b.finish();
    CHECK(errorOf(bytes) == "hostile.usdc: crate spec 2: a second spec for </A>");
  }
  SECTION("a spec type out of range, a field twice") {
    CrateBuilder b;
    b.spec("/", SpecType::PseudoRoot, {});
    b.spec("/A", SpecType(42), {});
    auto bytes = b.finish();
    CHECK(errorOf(bytes) == "hostile.usdc: crate SPECS section: spec 1 </A> has spec type 42 (known: 1 to 11)");
    CrateBuilder c;
    uint32_t f = c.field("active", rep(T::Bool, 1));
    c.spec("/", SpecType::PseudoRoot, {f, f});
    bytes = c.finish();
    CHECK(errorOf(bytes) == "hostile.usdc: crate spec 0 </> field 'active' (Bool): the field appears twice in the spec");
  }
  SECTION("a value past the end of the file") {
    CrateBuilder b;
    b.spec("/", SpecType::PseudoRoot, {b.field("far", rep(T::Double, 1 << 30))});
    auto bytes = b.finish();
    CHECK_THAT(errorOf(bytes), Catch::Contains("crate spec 0 </> field 'far' (Double): offset 1073741824 lies outside"));
  }
  SECTION("an array that overruns the file") {
    CrateBuilder b;
    uint64_t at = b.put<uint64_t>(uint64_t(1) << 26);  // 67M floats claimed, none there
    b.spec("/", SpecType::PseudoRoot, {b.field("big", rep(T::Float, at, true))});
    auto bytes = b.finish();
    CHECK_THAT(errorOf(bytes),
               Catch::Contains("crate spec 0 </> field 'big' (Float[]): Float array of 67108864 elements overruns"));
  }
  SECTION("an array above the element limit") {
    CrateBuilder b;
    uint64_t at = b.put<uint64_t>(uint64_t(1) << 40);
    b.spec("/", SpecType::PseudoRoot, {b.field("huge", rep(T::Int, at, true))});
    auto bytes = b.finish();
    CHECK_THAT(errorOf(bytes),
               Catch::Contains("field 'huge' (Int[]): an array of 1099511627776 elements exceeds the limit"));
  }
  SECTION("a compressed array whose data cannot hold its count") {
    CrateBuilder b;
    uint64_t at = b.put<uint64_t>(uint64_t(1) << 27);
    b.putCompressed(std::vector<int32_t>(16, 1));
    b.spec("/", SpecType::PseudoRoot, {b.field("lying", rep(T::Int, at, true, false, true))});
    auto bytes = b.finish();
    CHECK_THAT(errorOf(bytes), Catch::Contains("field 'lying' (Int[]): compressed ints: 134217728 entries cannot be"));
  }
  SECTION("a lookup table index past the table") {
    CrateBuilder b;
    uint64_t at = b.put<uint64_t>(16);
    b.put('t'), b.put<uint32_t>(1), b.put(1.0f);
    b.putCompressed(std::vector<uint32_t>(16, 5));
    b.spec("/", SpecType::PseudoRoot, {b.field("lut", rep(T::Float, at, true, false, true))});
    auto bytes = b.finish();
    CHECK_THAT(errorOf(bytes), Catch::Contains("lookup table index 5 is past the table's 1 values"));
  }
  SECTION("a dictionary that contains itself") {
    CrateBuilder b;
    uint64_t dict = b.put<uint64_t>(1);
    b.put(b.string("self"));
    b.put<int64_t>(8);
    b.put(rep(T::Dictionary, dict));
    b.spec("/", SpecType::PseudoRoot, {b.field("customData", rep(T::Dictionary, dict))});
    auto bytes = b.finish();
    CHECK_THAT(errorOf(bytes), Catch::Contains("field 'customData' (Dictionary): values nest deeper than 256 levels"));
  }
  SECTION("dictionaries sharing entries level after level decode once each") {
    CrateBuilder b;
    uint64_t previous = 0;
    for (int level = 0; level < 200; ++level) {  // 2^200 entries if each were decoded per use
      uint64_t dict = b.put<uint64_t>(level == 0 ? 0 : 2);
      for (const char* key : {"a", "b"}) {
        if (level == 0) break;
        b.put(b.string(key));
        b.put<int64_t>(8);
        b.put(rep(T::Dictionary, previous));
      }
      previous = dict;
    }
    b.spec("/", SpecType::PseudoRoot, {b.field("customData", rep(T::Dictionary, previous))});
    auto bytes = b.finish();
    Layer layer = readCrateLayer(bytes, "dag.usdc");
    CHECK(specAt(layer, "/").fields.at("customData").dictionary->size() == 2);
  }
  SECTION("many fields sharing one large array stop at the decoded-bytes limit") {
    CrateBuilder b;
    uint64_t at = b.put<uint64_t>(1000);
    b.putAll(std::vector<double>(1000, 1.0));
    std::vector<uint32_t> fields;
    for (int i = 0; i < 200; ++i) fields.push_back(b.field("f" + std::to_string(i), rep(T::Double, at, true)));
    b.spec("/", SpecType::PseudoRoot, fields);
    auto bytes = b.finish();
    ReadLimits limits;
    limits.maxDecompressedBytes = 1 << 20;  // 1 MiB: about 130 copies of the 8 KB array
    CHECK_THAT(errorOf(bytes, limits), Catch::Contains("the decoded values exceed the limit of 1048576 bytes"));
    CHECK(specAt(readCrateLayer(bytes, "shared.usdc"), "/").fields.size() == 200);
  }
  SECTION("the file size limit") {
    auto bytes = richCrateFile();
    ReadLimits limits;
    limits.maxFileBytes = 100;
    CHECK_THAT(errorOf(bytes, limits), Catch::Contains("bytes exceed the limit of 100"));
  }
}
