// Composition errors name the file and the arc with the referencing
// location: cycles, missing files, missing prims, missing defaultPrim; wide
// or deep hostile compositions stop at the limits.
#include <catch2/catch.hpp>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "usd/compose_test_util.h"

using namespace sdg::usd;
using sdg::usd::test::composeError;
using sdg::usd::test::MemoryLayers;

TEST_CASE("compose errors: cycles of references, internal arcs and sublayers", "[compose]") {
  MemoryLayers layers;
  layers.texts["a.usda"] = "#usda 1.0\ndef \"A\" (references = @b.usda@</B>) {}\n";
  layers.texts["b.usda"] = "#usda 1.0\ndef \"B\" (references = @a.usda@</A>) {}\n";
  CHECK(composeError(layers, "a.usda") ==
        "b.usda:2:23: reference @a.usda@</A> makes a composition cycle: </A> in a.usda leads back to </A>");

  layers.texts["self.usda"] = "#usda 1.0\ndef \"A\" {\n  def \"B\" (references = </A>) {}\n}\n";
  CHECK(composeError(layers, "self.usda") ==
        "self.usda:3:25: reference </A> makes a composition cycle: </A> in self.usda leads back to </A/B>");

  layers.texts["inherit.usda"] = "#usda 1.0\ndef \"A\" (inherits = </A>) {}\n";
  CHECK(composeError(layers, "inherit.usda") ==
        "inherit.usda:2:1: inherits </A> makes a composition cycle: </A> in inherit.usda leads back to </A>");

  layers.texts["s1.usda"] = "#usda 1.0\n(\n subLayers = [@s2.usda@]\n)\n";
  layers.texts["s2.usda"] = "#usda 1.0\n(\n subLayers = [@./s1.usda@]\n)\n";
  CHECK(composeError(layers, "s1.usda") == "s2.usda:3:15: sublayer cycle: s1.usda -> s2.usda -> s1.usda");
}

TEST_CASE("compose errors: missing files, prims and defaultPrim", "[compose]") {
  MemoryLayers layers;
  layers.texts["root.usda"] = "#usda 1.0\ndef \"A\" {\n}\ndef \"B\" (\n  references = @missing.usda@\n) {}\n";
  CHECK(composeError(layers, "root.usda") ==
        "root.usda:5:16: reference @missing.usda@ (missing.usda): no such layer");

  layers.texts["asset.usda"] = "#usda 1.0\ndef \"Asset\" {}\n";
  layers.texts["nodefault.usda"] = "#usda 1.0\ndef \"B\" (payload = @asset.usda@) {}\n";
  CHECK(composeError(layers, "nodefault.usda") ==
        "nodefault.usda:2:20: payload @asset.usda@: asset.usda has no defaultPrim; name the prim to load "
        "(@asset.usda@</Prim>)");

  layers.texts["noprim.usda"] = "#usda 1.0\ndef \"B\" (references = @asset.usda@</Nope>) {}\n";
  CHECK(composeError(layers, "noprim.usda") ==
        "noprim.usda:2:23: reference @asset.usda@</Nope>: no prim </Nope> in asset.usda");

  layers.texts["internal.usda"] = "#usda 1.0\ndef \"B\" (references = </Nope>) {}\n";
  CHECK(composeError(layers, "internal.usda") == "internal.usda:2:23: reference </Nope>: no prim </Nope> in internal.usda");

  layers.texts["badsub.usda"] = "#usda 1.0\n(\n subLayers = [@gone.usda@]\n)\n";
  CHECK(composeError(layers, "badsub.usda") == "badsub.usda:3:15: sublayer @gone.usda@ (gone.usda): no such layer");

  layers.texts["syntax.usda"] = "#usda 1.0\ndef \"A\" {\n  double x = \n}\n";
  layers.texts["refsyntax.usda"] = "#usda 1.0\ndef \"A\" (references = @syntax.usda@</A>) {}\n";
  CHECK(composeError(layers, "refsyntax.usda") ==
        "refsyntax.usda:2:23: reference @syntax.usda@</A> (syntax.usda): syntax.usda:4:1: expected a double number, found '}'");

  CHECK(composeError(layers, "nothing.usda") == "the root layer (nothing.usda): no such layer");
}

TEST_CASE("compose errors: wide and deep hostile compositions are bounded", "[compose]") {
  MemoryLayers layers;
  // A chain of references 100 deep, each layer referencing the next.
  for (int i = 0; i < 100; ++i)
    layers.texts["l" + std::to_string(i) + ".usda"] =
        "#usda 1.0\ndef \"P\" (references = @l" + std::to_string(i + 1) + ".usda@</P>) {}\n";
  layers.texts["l100.usda"] = "#usda 1.0\ndef \"P\" {}\n";
  CHECK_THAT(composeError(layers, "l0.usda"), Catch::Contains("composition arcs nested deeper than 64, the limit"));

  // One prim with thousands of internal references.
  std::string wide = "#usda 1.0\ndef \"T\" {}\ndef \"W\" (references = [";
  for (int i = 0; i < 5000; ++i) wide += "</T>, ";
  wide += "]) {}\n";
  layers.texts["wide.usda"] = wide;
  ComposeOptions options;
  options.limits.maxArcsPerPrim = 100;
  // Repeated items of a list op collapse to one arc, as in USD.
  CHECK(composeError(layers, "wide.usda", options).empty());
  std::string distinct = "#usda 1.0\ndef \"W\" (references = [";
  std::string prims;
  for (int i = 0; i < 200; ++i) {
    distinct += "</T" + std::to_string(i) + ">, ";
    prims += "def \"T" + std::to_string(i) + "\" {}\n";
  }
  layers.texts["distinct.usda"] = distinct + "]) {}\n" + prims;
  CHECK_THAT(composeError(layers, "distinct.usda", options),
             Catch::Contains("more than 100 composition arcs for one prim, the limit"));

  // A prim count beyond the limit.
  ComposeOptions fewPrims;
  fewPrims.limits.maxPrims = 50;
  CHECK_THAT(composeError(layers, "distinct.usda", fewPrims), Catch::Contains("more than 50 composed prims, the limit"));
}

TEST_CASE("compose errors: a missing file on disk names the referencing location", "[compose]") {
  std::filesystem::path dir = std::filesystem::temp_directory_path() / ("sdg_usd_missing_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  std::string root = (dir / "root.usda").string();
  {
    std::ofstream out(root);
    out << "#usda 1.0\ndef \"A\" (\n    references = @./missing.usda@\n) {}\n";
  }
  std::string error;
  try {
    composeStage(root, textLayerFileReader());
  } catch (const UsdError& e) {
    error = e.what();
  }
  std::filesystem::remove_all(dir);
  std::string missing = (dir / "missing.usda").string();
  CHECK(error == root + ":3:18: reference @./missing.usda@ (" + missing +
                     "): cannot open the layer: No such file or directory");
}
