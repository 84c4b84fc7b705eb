// The usda parser on hand-written layers: every grammar feature lands in
// the layer model under USD's field names.
#include <catch2/catch.hpp>
#include <cmath>

#include "usd/layer_io.h"

using namespace sdg::usd;

namespace {

Layer parse(const std::string& text) { return readUsdaLayer(text, "test.usda"); }

const Spec& specAt(const Layer& layer, const std::string& path) {
  const Spec* spec = layer.spec(path);
  INFO("spec " << path);
  REQUIRE(spec != nullptr);
  return *spec;
}

const Value& fieldOf(const Layer& layer, const std::string& path, const std::string& name) {
  const Spec& spec = specAt(layer, path);
  const Value* v = spec.field(name);
  INFO("field " << name << " of " << path);
  REQUIRE(v != nullptr);
  return *v;
}

std::vector<std::string> strings(std::initializer_list<const char*> items) { return {items.begin(), items.end()}; }

}  // namespace

TEST_CASE("usda: layer metadata, sublayers with offsets, comment and doc", "[usda]") {
  Layer layer = parse(R"(#usda 1.0
(
    "A layer comment"
    doc = """Multi-line
documentation"""
    defaultPrim = "World"
    metersPerUnit = 0.01
    upAxis = "Y"
    startTimeCode = 1
    endTimeCode = 24
    timeCodesPerSecond = 24
    customLayerData = {
        string creator = "hand"
        dictionary nested = { int n = 3 }
    }
    subLayers = [
        @./a.usda@ (offset = 10; scale = 2),
        @b.usda@
    ]
)
)");
  CHECK(layer.format == "usda");
  const Spec& root = layer.pseudoRoot();
  CHECK(root.type == SpecType::PseudoRoot);
  CHECK(fieldOf(layer, "/", "comment").asString() == "A layer comment");
  CHECK(fieldOf(layer, "/", "documentation").asString() == "Multi-line\ndocumentation");
  CHECK(fieldOf(layer, "/", "defaultPrim").kind == Kind::Token);
  CHECK(fieldOf(layer, "/", "defaultPrim").asString() == "World");
  CHECK(fieldOf(layer, "/", "metersPerUnit").asDouble() == 0.01);
  CHECK(fieldOf(layer, "/", "upAxis").asString() == "Y");
  CHECK(fieldOf(layer, "/", "startTimeCode").asDouble() == 1);
  CHECK(fieldOf(layer, "/", "timeCodesPerSecond").asDouble() == 24);
  const Value& data = fieldOf(layer, "/", "customLayerData");
  REQUIRE(data.kind == Kind::Dictionary);
  CHECK(data.dictionary->at("creator").asString() == "hand");
  CHECK(data.dictionary->at("nested").dictionary->at("n").asDouble() == 3);
  CHECK(data.dictionary->at("nested").dictionary->at("n").kind == Kind::Int);
  CHECK(fieldOf(layer, "/", "subLayers").asStrings() == strings({"./a.usda", "b.usda"}));
  const Value& offsets = fieldOf(layer, "/", "subLayerOffsets");
  REQUIRE(offsets.layerOffsets->size() == 2);
  CHECK((*offsets.layerOffsets)[0] == LayerOffset{10, 2});
  CHECK((*offsets.layerOffsets)[1] == LayerOffset{0, 1});
}

TEST_CASE("usda: prims with specifiers, types, children order and metadata", "[usda]") {
  Layer layer = parse(R"(#usda 1.0
def Xform "World" (
    kind = "assembly"
    active = true
    instanceable = false
    hidden = true
    displayName = "The world"
    prepend apiSchemas = ["GeomModelAPI", "MaterialBindingAPI"]
    customData = { bool flag = 1 }
    assetInfo = { asset identifier = @world.usd@ }
)
{
    over "Patch" {}
    class Scope "_Class" {
    }
    def "Untyped" {
    }
    reorder nameChildren = ["Untyped", "Patch"]
}
over "Top" { }
)");
  CHECK(fieldOf(layer, "/", "primChildren").asStrings() == strings({"World", "Top"}));
  const Spec& world = specAt(layer, "/World");
  CHECK(world.type == SpecType::Prim);
  CHECK(world.loc.str() == "test.usda:2:1");
  CHECK(fieldOf(layer, "/World", "specifier").enumValue == int(Specifier::Def));
  CHECK(fieldOf(layer, "/World", "typeName").asString() == "Xform");
  CHECK(fieldOf(layer, "/World", "kind").asString() == "assembly");
  CHECK(fieldOf(layer, "/World", "active").asBool());
  CHECK_FALSE(fieldOf(layer, "/World", "instanceable").asBool());
  CHECK(fieldOf(layer, "/World", "hidden").asBool());
  CHECK(fieldOf(layer, "/World", "displayName").kind == Kind::String);
  const Value& api = fieldOf(layer, "/World", "apiSchemas");
  REQUIRE(api.kind == Kind::TokenListOp);
  CHECK(api.textListOp->prependedItems == strings({"GeomModelAPI", "MaterialBindingAPI"}));
  CHECK(fieldOf(layer, "/World", "customData").dictionary->at("flag").asBool());
  CHECK(fieldOf(layer, "/World", "assetInfo").dictionary->at("identifier").kind == Kind::AssetPath);
  CHECK(fieldOf(layer, "/World", "primChildren").asStrings() == strings({"Patch", "_Class", "Untyped"}));
  CHECK(fieldOf(layer, "/World", "primOrder").asStrings() == strings({"Untyped", "Patch"}));
  CHECK(fieldOf(layer, "/World/Patch", "specifier").enumValue == int(Specifier::Over));
  CHECK(specAt(layer, "/World/Patch").field("typeName") == nullptr);
  CHECK(fieldOf(layer, "/World/_Class", "specifier").enumValue == int(Specifier::Class));
  CHECK(fieldOf(layer, "/World/_Class", "typeName").asString() == "Scope");
  CHECK(fieldOf(layer, "/Top", "specifier").enumValue == int(Specifier::Over));
}

TEST_CASE("usda: typed attributes, role types, arrays, uniform, custom, None", "[usda]") {
  Layer layer = parse(R"(#usda 1.0
def Mesh "M"
{
    point3f[] points = [(0, 0, 0), (1, 0, 0), (1, 1, 0.5)]
    normal3f[] normals = [(0, 0, 1)] (
        interpolation = "uniform"
    )
    texCoord2f[] primvars:st = [(0, 0), (1, 1)] (
        interpolation = "faceVarying"
        elementSize = 1
    )
    color3f[] primvars:displayColor = [(0.1, 0.2, 0.3)]
    uniform token subdivisionScheme = "none"
    int[] faceVertexCounts = [3]
    custom double myValue = -2.5e3
    bool flag = true
    half h = 0.1
    float f = 0.1
    double d = 0.1
    int64 big = -9007199254740992
    uchar u = 255
    quatf orient = (1, 0, 0, 0.5)
    matrix4d xformOp:transform = ( (1, 0, 0, 0), (0, 1, 0, 0), (0, 0, 1, 0), (2, 3, 4, 1) )
    asset tex = @./textures/wood.png@
    asset[] texs = [@a.png@, @@@b@c.png@@@]
    string s = "line\nbreak \"quoted\""
    string single = 'single'
    token[] tokens = ["a", "b"]
    float blocked = None
    float declared
    double inf = inf
    double negInf = -inf
    float[] empty = []
    timecode tc = 12
    frame4d frame = ((1,0,0,0),(0,1,0,0),(0,0,1,0),(0,0,0,1))
}
)");
  CHECK(fieldOf(layer, "/M", "properties").asStrings().size() == 27);
  const Value& points = fieldOf(layer, "/M.points", "default");
  CHECK(points.kind == Kind::Vec3f);
  CHECK(points.isArray);
  CHECK(points.elementCount() == 3);
  CHECK(points.numbers[8] == 0.5);
  CHECK(fieldOf(layer, "/M.points", "typeName").asString() == "point3f[]");
  CHECK(fieldOf(layer, "/M.points", "variability").enumValue == int(Variability::Varying));
  CHECK(fieldOf(layer, "/M.normals", "interpolation").asString() == "uniform");
  CHECK(fieldOf(layer, "/M.primvars:st", "typeName").asString() == "texCoord2f[]");
  CHECK(fieldOf(layer, "/M.primvars:st", "elementSize").asDouble() == 1);
  CHECK(fieldOf(layer, "/M.primvars:st", "default").kind == Kind::Vec2f);
  CHECK(fieldOf(layer, "/M.primvars:displayColor", "typeName").asString() == "color3f[]");
  CHECK(fieldOf(layer, "/M.subdivisionScheme", "variability").enumValue == int(Variability::Uniform));
  CHECK(fieldOf(layer, "/M.subdivisionScheme", "default").asString() == "none");
  CHECK(fieldOf(layer, "/M.myValue", "custom").asBool());
  CHECK_FALSE(fieldOf(layer, "/M.points", "custom").asBool());
  CHECK(fieldOf(layer, "/M.myValue", "default").asDouble() == -2500);
  CHECK(fieldOf(layer, "/M.flag", "default").asBool());
  CHECK(fieldOf(layer, "/M.h", "default").asDouble() == 0.0999755859375);  // the nearest half
  CHECK(fieldOf(layer, "/M.f", "default").asDouble() == double(0.1f));
  CHECK(fieldOf(layer, "/M.d", "default").asDouble() == 0.1);
  CHECK(fieldOf(layer, "/M.big", "default").asDouble() == -9007199254740992.0);
  CHECK(fieldOf(layer, "/M.u", "default").kind == Kind::UChar);
  const Value& orient = fieldOf(layer, "/M.orient", "default");
  CHECK(orient.kind == Kind::Quatf);
  CHECK(orient.numbers == std::vector<double>{1, 0, 0, 0.5});  // (real, i, j, k) as written
  const Value& m = fieldOf(layer, "/M.xformOp:transform", "default");
  CHECK(m.kind == Kind::Matrix4d);
  CHECK(m.numbers.size() == 16);
  CHECK(m.numbers[12] == 2);
  CHECK(m.numbers[14] == 4);
  CHECK(fieldOf(layer, "/M.tex", "default").kind == Kind::AssetPath);
  CHECK(fieldOf(layer, "/M.tex", "default").asString() == "./textures/wood.png");
  CHECK(fieldOf(layer, "/M.texs", "default").asStrings() == strings({"a.png", "b@c.png"}));
  CHECK(fieldOf(layer, "/M.s", "default").asString() == "line\nbreak \"quoted\"");
  CHECK(fieldOf(layer, "/M.single", "default").asString() == "single");
  CHECK(fieldOf(layer, "/M.tokens", "default").kind == Kind::Token);
  CHECK(fieldOf(layer, "/M.tokens", "default").asStrings() == strings({"a", "b"}));
  CHECK(fieldOf(layer, "/M.blocked", "default").kind == Kind::ValueBlock);
  CHECK(specAt(layer, "/M.declared").field("default") == nullptr);
  CHECK(std::isinf(fieldOf(layer, "/M.inf", "default").asDouble()));
  CHECK(fieldOf(layer, "/M.negInf", "default").asDouble() < 0);
  CHECK(fieldOf(layer, "/M.empty", "default").elementCount() == 0);
  CHECK(fieldOf(layer, "/M.tc", "default").kind == Kind::TimeCode);
  CHECK(fieldOf(layer, "/M.frame", "default").kind == Kind::Matrix4d);
  CHECK(fieldOf(layer, "/M.frame", "typeName").asString() == "frame4d");
}

TEST_CASE("usda: time samples, connections, relationships", "[usda]") {
  Layer layer = parse(R"(#usda 1.0
def Xform "A"
{
    double3 xformOp:translate.timeSamples = {
        10: (0, 0, 10),
        0: (0, 0, 0),
        5: None,
    }
    double3 xformOp:translate = (1, 1, 1)
    float inputs:x.connect = </A/Shader.outputs:out>
    float inputs:x = 2
    prepend float inputs:y.connect = [<Shader.outputs:a>, <../A/Shader.outputs:b>]
    rel material:binding = </Looks/Mat> (
        bindMaterialAs = "weakerThanDescendants"
    )
    custom rel proxyPrim
    append rel targets = [</X>, </Y>]
    delete rel targets = </Z>
    rel empty = None
    varying rel v = </V>
}
)");
  const Value& ts = fieldOf(layer, "/A.xformOp:translate", "timeSamples");
  REQUIRE(ts.kind == Kind::TimeSamples);
  CHECK(ts.timeSamples->times == std::vector<double>{0, 5, 10});
  CHECK(ts.timeSamples->values[1].kind == Kind::ValueBlock);
  CHECK(ts.timeSamples->values[2].numbers == std::vector<double>{0, 0, 10});
  CHECK(fieldOf(layer, "/A.xformOp:translate", "default").numbers == std::vector<double>{1, 1, 1});
  const Value& connect = fieldOf(layer, "/A.inputs:x", "connectionPaths");
  REQUIRE(connect.kind == Kind::PathListOp);
  CHECK(connect.textListOp->isExplicit);
  CHECK(connect.textListOp->explicitItems == strings({"/A/Shader.outputs:out"}));
  CHECK(fieldOf(layer, "/A.inputs:x", "default").asDouble() == 2);
  CHECK(fieldOf(layer, "/A.inputs:y", "connectionPaths").textListOp->prependedItems ==
        strings({"/A/Shader.outputs:a", "/A/Shader.outputs:b"}));
  const Spec& binding = specAt(layer, "/A.material:binding");
  CHECK(binding.type == SpecType::Relationship);
  CHECK(fieldOf(layer, "/A.material:binding", "targetPaths").textListOp->explicitItems == strings({"/Looks/Mat"}));
  CHECK(fieldOf(layer, "/A.material:binding", "bindMaterialAs").asString() == "weakerThanDescendants");
  CHECK(fieldOf(layer, "/A.proxyPrim", "custom").asBool());
  CHECK(specAt(layer, "/A.proxyPrim").field("targetPaths") == nullptr);
  const Value& targets = fieldOf(layer, "/A.targets", "targetPaths");
  CHECK(targets.textListOp->appendedItems == strings({"/X", "/Y"}));
  CHECK(targets.textListOp->deletedItems == strings({"/Z"}));
  CHECK_FALSE(targets.textListOp->isExplicit);
  const Value& empty = fieldOf(layer, "/A.empty", "targetPaths");
  CHECK(empty.textListOp->isExplicit);
  CHECK(empty.textListOp->explicitItems.empty());
  CHECK(fieldOf(layer, "/A.v", "variability").enumValue == int(Variability::Varying));
  CHECK(fieldOf(layer, "/A.material:binding", "variability").enumValue == int(Variability::Uniform));
}

TEST_CASE("usda: composition arcs and list-op prefixes", "[usda]") {
  Layer layer = parse(R"(#usda 1.0
def "A" (
    prepend references = @./asset.usda@</Asset> (offset = 5; customData = {string note = "x"})
    append references = [</Internal>, @other.usd@]
    delete references = @old.usda@
    payload = @./payload.usda@
    inherits = </_Class>
    add specializes = [</Base>]
    variants = {
        string shadingVariant = "red"
        string lod = "high"
    }
    prepend variantSets = ["shadingVariant", "lod"]
    relocates = { </A/x>: </A/y> }
)
{
}
def "B" (references = None) {}
)");
  const Value& refs = fieldOf(layer, "/A", "references");
  REQUIRE(refs.kind == Kind::ReferenceListOp);
  const ListOp<Reference>& op = *refs.referenceListOp;
  REQUIRE(op.prependedItems.size() == 1);
  CHECK(op.prependedItems[0].assetPath == "./asset.usda");
  CHECK(op.prependedItems[0].primPath == "/Asset");
  CHECK(op.prependedItems[0].offset.offset == 5);
  REQUIRE(op.prependedItems[0].customData);
  CHECK(op.prependedItems[0].customData->at("note").asString() == "x");
  REQUIRE(op.appendedItems.size() == 2);
  CHECK(op.appendedItems[0].assetPath.empty());
  CHECK(op.appendedItems[0].primPath == "/Internal");
  CHECK(op.appendedItems[1].assetPath == "other.usd");
  CHECK(op.appendedItems[1].primPath.empty());
  CHECK(op.deletedItems.size() == 1);
  const Value& payload = fieldOf(layer, "/A", "payload");
  CHECK(payload.kind == Kind::PayloadListOp);
  CHECK(payload.referenceListOp->isExplicit);
  CHECK(payload.referenceListOp->explicitItems[0].assetPath == "./payload.usda");
  CHECK(fieldOf(layer, "/A", "inheritPaths").textListOp->explicitItems == strings({"/_Class"}));
  CHECK(fieldOf(layer, "/A", "specializes").textListOp->addedItems == strings({"/Base"}));
  const Value& variants = fieldOf(layer, "/A", "variantSelection");
  CHECK(variants.kind == Kind::VariantSelectionMap);
  CHECK(variants.dictionary->at("shadingVariant").asString() == "red");
  CHECK(fieldOf(layer, "/A", "variantSetNames").textListOp->prependedItems == strings({"shadingVariant", "lod"}));
  CHECK(fieldOf(layer, "/A", "relocates").dictionary->at("/A/x").asString() == "/A/y");
  const Value& none = fieldOf(layer, "/B", "references");
  CHECK(none.referenceListOp->isExplicit);
  CHECK(none.referenceListOp->explicitItems.empty());
}

TEST_CASE("usda: variant sets, nested, with prims and properties inside", "[usda]") {
  Layer layer = parse(R"(#usda 1.0
def Xform "Asset" (
    variants = { string shading = "red" }
    prepend variantSets = "shading"
)
{
    variantSet "shading" = {
        "red" (
            kind = "component"
        ) {
            color3f color = (1, 0, 0)
            def Sphere "Ball" { double radius = 2 }
            variantSet "lod" = {
                "high" { int level = 2 }
            }
        }
        "blue" {
            color3f color = (0, 0, 1)
        }
    }
    double size = 1
}
)");
  CHECK(fieldOf(layer, "/Asset", "variantSetChildren").asStrings() == strings({"shading"}));
  const Spec& set = specAt(layer, "/Asset{shading=}");
  CHECK(set.type == SpecType::VariantSet);
  CHECK(fieldOf(layer, "/Asset{shading=}", "variantChildren").asStrings() == strings({"red", "blue"}));
  CHECK(specAt(layer, "/Asset{shading=red}").type == SpecType::Variant);
  CHECK(fieldOf(layer, "/Asset{shading=red}", "kind").asString() == "component");
  CHECK(fieldOf(layer, "/Asset{shading=red}", "properties").asStrings() == strings({"color"}));
  CHECK(fieldOf(layer, "/Asset{shading=red}", "primChildren").asStrings() == strings({"Ball"}));
  CHECK(fieldOf(layer, "/Asset{shading=red}Ball.radius", "default").asDouble() == 2);
  CHECK(fieldOf(layer, "/Asset{shading=red}", "variantSetChildren").asStrings() == strings({"lod"}));
  CHECK(fieldOf(layer, "/Asset{shading=red}{lod=high}.level", "default").asDouble() == 2);
  CHECK(fieldOf(layer, "/Asset{shading=blue}.color", "default").numbers == std::vector<double>{0, 0, 1});
  CHECK(fieldOf(layer, "/Asset", "properties").asStrings() == strings({"size"}));
}

TEST_CASE("usda: comments, semicolons, unknown metadata kept under its name", "[usda]") {
  Layer layer = parse(R"(#usda 1.0
# a comment
// another
/* a block
   comment */
def "A" ( myPlugin:flag = true; customThing = 3; tags = ["a", "b"]; vec = (1, 2, 3); ) {
    float a = 1; float b = 2  # trailing comment
    float c = /* inline */ 3
}
)");
  CHECK(fieldOf(layer, "/A", "myPlugin:flag").asBool());
  CHECK(fieldOf(layer, "/A", "customThing").kind == Kind::Double);
  CHECK(fieldOf(layer, "/A", "tags").asStrings() == strings({"a", "b"}));
  CHECK(fieldOf(layer, "/A", "vec").kind == Kind::Vec3d);
  CHECK(fieldOf(layer, "/A.b", "default").asDouble() == 2);
  CHECK(fieldOf(layer, "/A.c", "default").asDouble() == 3);
}

TEST_CASE("usda: numeric arrays read the same by the fast scanner and the token path", "[usda]") {
  // The scanner reads plain arrays; a comment in front of the first element
  // sends the whole array through the token path instead.
  std::string items;
  for (int i = 0; i < 200; ++i)
    items += "(" + std::to_string(i * 0.37 - 20) + ", -" + std::to_string(i) + "e-3, " + std::to_string(i) + ".25),\n  ";
  Layer fast = parse("#usda 1.0\ndef \"A\" {\n  float3[] p = [" + items + "]\n  half2[] h = [(0.1, 7), (65519, -0)]\n}\n");
  Layer slow = parse("#usda 1.0\ndef \"A\" {\n  float3[] p = [ # tokens\n" + items +
                     "]\n  half2[] h = [ /* c */ (0.1, 7), (65519, -0)]\n}\n");
  CHECK(fieldOf(fast, "/A.p", "default") == fieldOf(slow, "/A.p", "default"));
  CHECK(fieldOf(fast, "/A.p", "default").elementCount() == 200);
  CHECK(fieldOf(fast, "/A.h", "default") == fieldOf(slow, "/A.h", "default"));
  CHECK(fieldOf(fast, "/A.h", "default").numbers[2] == 65504);  // 65519 rounds to the largest half

  // Mid-array hand-overs: comments, inf and nan, trailing commas, then the scanner's shapes again.
  Layer mixed = parse(R"(#usda 1.0
def "A" {
    double3[] v = [(1, 2, 3), # one
        (inf, -inf, 4), (1e3, .5, -.5), (1, 2, 3,),
        (7, 8, 9)]
    int[] i = [1, 2,
        3 /* three */, 4]
    float next = 1
}
)");
  const Value& v = fieldOf(mixed, "/A.v", "default");
  REQUIRE(v.numbers.size() == 15);
  CHECK(std::isinf(v.numbers[3]));
  CHECK(v.numbers[4] < 0);
  CHECK(v.numbers[6] == 1000);
  CHECK(v.numbers[7] == 0.5);
  CHECK(v.numbers[14] == 9);
  CHECK(fieldOf(mixed, "/A.i", "default").numbers == std::vector<double>{1, 2, 3, 4});
  CHECK(fieldOf(mixed, "/A.next", "default").asDouble() == 1);
}

TEST_CASE("usda: Windows line endings count lines the same", "[usda]") {
  Layer layer = parse("#usda 1.0\r\n(\r\n    upAxis = \"Z\"\r\n)\r\ndef \"A\"\r\n{\r\n    float3[] p = [\r\n(1, 2, 3),\r\n(4, 5, 6)]\r\n"
                      "    string s = \"\"\"a\r\nb\"\"\"\r\n    float x = 1\r\n}\r\n");
  CHECK(specAt(layer, "/A").loc.str() == "test.usda:5:1");
  CHECK(fieldOf(layer, "/A.p", "default").numbers.size() == 6);
  CHECK(specAt(layer, "/A.x").loc.str() == "test.usda:12:5");
  try {
    parse("#usda 1.0\r\ndef \"A\"\r\n{\r\n    float x = \r\n}\r\n");
    FAIL("expected an error");
  } catch (const UsdError& e) {
    CHECK(std::string(e.what()) == "test.usda:5:1: expected a float number, found '}'");
  }
}
