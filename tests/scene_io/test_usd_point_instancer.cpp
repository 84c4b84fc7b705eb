// USD PointInstancers onto the stage (scene_io/usd_point_instancer.h): the
// instance transform against answers worked by hand, quath and quatf
// orientations, ids, invisibleIds and inactiveIds, prototypes hidden where
// they stand, one semantic entity per instance, and located errors.
#include <catch2/catch.hpp>

#include <cmath>

#include "render/render_list.h"
#include "scene_io/usd_fixtures.h"
#include "scene_io/usd_import.h"
#include "scene_io/usd_point_instancer.h"
#include "writers/semantics.h"

using namespace sdg;
using sdg::test::composeText;

namespace {

using Imported = test::ImportedStage;
using test::importText;

Vec3d world(const Stage& stage, const std::string& path, const Vec3d& local) {
  const Prim* prim = stage.find(path);
  REQUIRE(prim);
  return (stage.worldMatrix(*prim) * local.homogeneous()).head<3>();
}

bool near(const Vec3d& a, const Vec3d& b, double tolerance = 1e-6) { return (a - b).norm() < tolerance; }

std::string errors(const Diagnostics& diag) {
  std::string out;
  for (const Diagnostic& d : diag.all()) out += d.loc.str() + ": " + d.message + "\n";
  return out;
}

// In Z-up metres, the stage's units, so that world positions are the
// hand-computed ones (USD's fallbacks, Y-up centimetres, add a correction).
// One instancer, translated by (10, 0, 0), one Cube prototype whose root is
// itself translated by (0, 0, 1).
std::string oneInstancer(const std::string& arrays, const std::string& metadata = "") {
  return R"(#usda 1.0
(
    metersPerUnit = 1
    upAxis = "Z"
)
def Xform "W"
{
    def PointInstancer "P" ()" + metadata + R"()
    {
        double3 xformOp:translate = (10, 0, 0)
        uniform token[] xformOpOrder = ["xformOp:translate"]
        rel prototypes = [</W/P/Protos/C>]
)" + arrays + R"(
        def Scope "Protos"
        {
            def Cube "C"
            {
                double size = 1
                double3 xformOp:translate = (0, 0, 1)
                uniform token[] xformOpOrder = ["xformOp:translate"]
            }
        }
    }
}
)";
}

}  // namespace

TEST_CASE("point instancer: T * R * S of one instance, worked by hand", "[scene_io][usd][instancer]") {
  PointInstancerData d;
  d.protoIndices = {0};
  d.positions = {Vec3d(1, 2, 3)};
  d.orientations = {Quatd(std::sqrt(0.5), 0, 0, std::sqrt(0.5))};  // 90 degrees about Z
  d.scales = {Vec3d(2, 1, 1)};
  // (1, 0, 0): scaled to (2, 0, 0), turned to (0, 2, 0), moved to (1, 4, 3).
  CHECK(near((d.instanceMatrix(0) * Vec3d(1, 0, 0).homogeneous()).head<3>(), Vec3d(1, 4, 3)));
  // (0, 1, 0): scaled to (0, 1, 0), turned to (-1, 0, 0), moved to (0, 2, 3).
  CHECK(near((d.instanceMatrix(0) * Vec3d(0, 1, 0).homogeneous()).head<3>(), Vec3d(0, 2, 3)));
  d.orientations.clear();
  d.scales.clear();
  CHECK(near((d.instanceMatrix(0) * Vec3d(1, 0, 0).homogeneous()).head<3>(), Vec3d(2, 2, 3)));
}

TEST_CASE("point instancer: quath orientations, scales, the prototype root's and the instancer's transforms",
          "[scene_io][usd][instancer]") {
  Imported in;
  // 90 degrees about X as (real, i, j, k); scale 2.
  importText(oneInstancer(R"(
        int[] protoIndices = [0, 0]
        point3f[] positions = [(1, 0, 0), (0, 5, 0)]
        quath[] orientations = [(0.7071068, 0.7071068, 0, 0), (1, 0, 0, 0)]
        float3[] scales = [(2, 2, 2), (1, 1, 1)]
)"),
         in);
  INFO(errors(in.diag));
  REQUIRE_FALSE(in.diag.hasErrors());
  // Origin of the cube: prototype root (0, 0, 1), scaled (0, 0, 2), turned
  // about X to (0, -2, 0), moved by (1, 0, 0), then the instancer's (10, 0, 0).
  CHECK(near(world(in.stage, "/W/P/instance_0", Vec3d::Zero()), Vec3d(11, -2, 0), 1e-3));
  // A corner (0.5, 0.5, 0.5) of the cube: (0.5, 0.5, 1.5) -> (1, 1, 3) -> (1, -3, 1) -> (12, -3, 1).
  CHECK(near(world(in.stage, "/W/P/instance_0", Vec3d(0.5, 0.5, 0.5)), Vec3d(12, -3, 1), 1e-3));
  CHECK(near(world(in.stage, "/W/P/instance_1", Vec3d::Zero()), Vec3d(10, 5, 1)));
  // The clone is the prototype's type with its attributes.
  CHECK(in.stage.find("/W/P/instance_0")->type() == PrimType::Cube);
  CHECK(in.stage.find("/W/P/instance_0")->getDouble("size") == 1.0);
  // Nothing of the instancer's arrays is reported as unmapped.
  CHECK(in.report.warnings.empty());
}

TEST_CASE("point instancer: quatf orientationsf win over quath orientations", "[scene_io][usd][instancer]") {
  Imported in;
  importText(oneInstancer(R"(
        int[] protoIndices = [0]
        point3f[] positions = [(0, 0, 0)]
        quath[] orientations = [(1, 0, 0, 0)]
        quatf[] orientationsf = [(0, 0, 0, 1)]
)"),
         in);
  INFO(errors(in.diag));
  REQUIRE_FALSE(in.diag.hasErrors());
  // 180 degrees about Z: the prototype's (0, 0, 1) stays, (1, 0, 1) goes to (-1, 0, 1).
  CHECK(near(world(in.stage, "/W/P/instance_0", Vec3d(1, 0, 0)), Vec3d(9, 0, 1), 1e-6));
  // Unnormalised quaternions are normalised: (2, 0, 0, 0) is no rotation.
  Imported unnormalised;
  importText(oneInstancer(R"(
        int[] protoIndices = [0]
        point3f[] positions = [(0, 0, 0)]
        quatf[] orientationsf = [(2, 0, 0, 0)]
)"),
         unnormalised);
  CHECK(near(world(unnormalised.stage, "/W/P/instance_0", Vec3d(1, 0, 0)), Vec3d(11, 0, 1)));
}

TEST_CASE("point instancer: ids name the instances, invisibleIds hide, inactiveIds drop", "[scene_io][usd][instancer]") {
  Imported in;
  importText(oneInstancer(R"(
        int[] protoIndices = [0, 0, 0, 0]
        int64[] ids = [5, 6, 7, -3]
        point3f[] positions = [(0, 0, 0), (1, 0, 0), (2, 0, 0), (3, 0, 0)]
        int64[] invisibleIds = [6]
)",
                      "inactiveIds = [7]"),
         in);
  INFO(errors(in.diag));
  REQUIRE_FALSE(in.diag.hasErrors());
  REQUIRE(in.stage.find("/W/P/instance_5"));
  CHECK(in.stage.find("/W/P/instance_5")->getString("visibility") == "inherited");
  REQUIRE(in.stage.find("/W/P/instance_6"));
  CHECK(in.stage.find("/W/P/instance_6")->getString("visibility") == "invisible");
  CHECK_FALSE(in.stage.find("/W/P/instance_7"));
  CHECK(in.stage.find("/W/P/instance_n3"));
  CHECK(near(world(in.stage, "/W/P/instance_n3", Vec3d::Zero()), Vec3d(13, 0, 1)));

  // Without ids the index is the id.
  Imported byIndex;
  importText(oneInstancer(R"(
        int[] protoIndices = [0, 0, 0]
        point3f[] positions = [(0, 0, 0), (1, 0, 0), (2, 0, 0)]
        int64[] invisibleIds = [0]
)",
                      "inactiveIds = [2]"),
         byIndex);
  REQUIRE_FALSE(byIndex.diag.hasErrors());
  CHECK(byIndex.stage.find("/W/P/instance_0")->getString("visibility") == "invisible");
  CHECK(byIndex.stage.find("/W/P/instance_1")->getString("visibility") == "inherited");
  CHECK_FALSE(byIndex.stage.find("/W/P/instance_2"));
}

TEST_CASE("point instancer: prototypes beneath are drawn only as instances, sharing one mesh",
          "[scene_io][usd][instancer]") {
  Imported in;
  importText(R"(#usda 1.0
(
    metersPerUnit = 1
    upAxis = "Z"
)
def Xform "W"
{
    def PointInstancer "P"
    {
        rel prototypes = [</W/P/Protos/Rock>, </W/Outside>]
        int[] protoIndices = [0, 1, 0]
        point3f[] positions = [(0, 0, 0), (1, 0, 0), (2, 0, 0)]
        vector3f[] velocities = [(1, 0, 0), (0, 2, 0), (0, 0, 3)]
        def Scope "Protos"
        {
            def Xform "Rock" (
                prepend apiSchemas = ["SemanticsAPI:Semantics_a1"]
            )
            {
                string semantic:Semantics_a1:params:semanticType = "class"
                string semantic:Semantics_a1:params:semanticData = "rock"
                def Mesh "Shape"
                {
                    point3f[] points = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0)]
                    int[] faceVertexCounts = [4]
                    int[] faceVertexIndices = [0, 1, 2, 3]
                }
            }
        }
    }
    def Sphere "Outside"
    {
        double radius = 0.5
    }
}
)",
         in);
  INFO(errors(in.diag));
  REQUIRE_FALSE(in.diag.hasErrors());
  // The prototype under the instancer is hidden where it stands; the one
  // outside stays drawn there, as in USD.
  CHECK(in.stage.find("/W/P/Protos/Rock")->getString("visibility") == "invisible");
  CHECK(in.stage.find("/W/Outside")->getString("visibility") == "inherited");
  // Clones keep the prototype's own visibility, not the hiding.
  CHECK(in.stage.find("/W/P/instance_0")->getString("visibility") == "inherited");
  CHECK(in.stage.find("/W/P/instance_0/Shape")->type() == PrimType::Mesh);

  const RenderList list = buildRenderList(in.stage);
  std::vector<std::string> drawn;
  for (const RenderItem& item : list.items) drawn.push_back(item.primPath);
  CHECK(drawn == std::vector<std::string>{"/W/P/instance_0/Shape", "/W/P/instance_1", "/W/P/instance_2/Shape",
                                          "/W/Outside"});
  // Both rocks draw the same mesh: one instanced draw.
  CHECK(list.items[0].meshId == list.items[2].meshId);

  // One entity per instance, with its prototype's label.
  const FrameSemantics semantics = computeSemantics(in.stage, list, {"class"});
  REQUIRE(semantics.entities.size() == 2);
  CHECK(semantics.entities[0].primPath == "/W/P/instance_0");
  CHECK(semantics.entities[1].primPath == "/W/P/instance_2");
  CHECK(semantics.entities[0].labels.at("class") == "rock");
  CHECK(semantics.entities[0].instanceId != semantics.entities[1].instanceId);

  // Velocities ride on each instance.
  REQUIRE(instanceVelocity(*in.stage.find("/W/P/instance_2")));
  CHECK(near(*instanceVelocity(*in.stage.find("/W/P/instance_2")), Vec3d(0, 0, 3)));
  CHECK_FALSE(instanceVelocity(*in.stage.find("/W/P/Protos/Rock")));
}

TEST_CASE("point instancer: instances move at their velocities on the timeline", "[scene_io][usd][instancer]") {
  // 24 time codes a second: a velocity of (2, 0, 0) units a second moves an
  // instance 1 unit every 12 time codes from the start time code, as USD
  // extrapolates positions from their sample; a zero velocity stays still.
  Imported in;
  importText(oneInstancer(R"(        int[] protoIndices = [0, 0]
        point3f[] positions = [(0, 0, 0), (5, 0, 0)]
        vector3f[] velocities = [(2, 0, 0), (0, 0, 0)]
)"), in);
  INFO(errors(in.diag));
  REQUIRE_FALSE(in.diag.hasErrors());
  const AnimatedValue* moving = in.stage.animation().find("/W/P/instance_0", "xformOp:translate:instance");
  REQUIRE(moving != nullptr);
  CHECK(moving->xformOp);
  CHECK(moving->at(0.0).get<Vec3d>().isApprox(Vec3d(0, 0, 0)));
  CHECK(moving->at(12.0).get<Vec3d>().isApprox(Vec3d(1, 0, 0)));
  CHECK(moving->at(48.0).get<Vec3d>().isApprox(Vec3d(4, 0, 0)));  // past the two samples: still on the line
  CHECK(in.stage.animation().find("/W/P/instance_1", "xformOp:translate:instance") == nullptr);
}

TEST_CASE("point instancer: an instancer inside a prototype is expanded in every copy", "[scene_io][usd][instancer]") {
  Imported in;
  importText(R"(#usda 1.0
(
    metersPerUnit = 1
    upAxis = "Z"
)
def PointInstancer "Outer"
{
    rel prototypes = [</Outer/Protos/Pair>]
    int[] protoIndices = [0, 0]
    point3f[] positions = [(0, 0, 0), (0, 10, 0)]
    def Scope "Protos"
    {
        def PointInstancer "Pair"
        {
            rel prototypes = [</Outer/Protos/Pair/Protos/Dot>]
            int[] protoIndices = [0, 0]
            point3f[] positions = [(1, 0, 0), (2, 0, 0)]
            def Scope "Protos"
            {
                def Sphere "Dot"
                {
                    double radius = 0.1
                }
            }
        }
    }
}
)",
         in);
  INFO(errors(in.diag));
  REQUIRE_FALSE(in.diag.hasErrors());
  const RenderList list = buildRenderList(in.stage);
  std::vector<std::string> drawn;
  for (const RenderItem& item : list.items) drawn.push_back(item.primPath);
  CHECK(drawn == std::vector<std::string>{"/Outer/instance_0/instance_0", "/Outer/instance_0/instance_1",
                                          "/Outer/instance_1/instance_0", "/Outer/instance_1/instance_1"});
  CHECK(near(world(in.stage, "/Outer/instance_1/instance_1", Vec3d::Zero()), Vec3d(2, 10, 0)));
}

TEST_CASE("point instancer: mismatched arrays, indices and quaternions are located errors",
          "[scene_io][usd][instancer]") {
  auto firstError = [](const std::string& arrays) {
    Imported in;
    importText(oneInstancer(arrays), in);
    for (const Diagnostic& d : in.diag.all())
      if (d.severity == Severity::Error) return d.loc.str() + ": " + d.message;
    return std::string();
  };
  std::string e = firstError(R"(
        int[] protoIndices = [0, 0]
        point3f[] positions = [(0, 0, 0)]
)");
  CHECK(e.find("/v/scene.usda:15:") == 0);
  CHECK(e.find("/W/P.positions: 1 items, but protoIndices has 2") != std::string::npos);
  e = firstError(R"(
        int[] protoIndices = [0, 1]
        point3f[] positions = [(0, 0, 0), (1, 0, 0)]
)");
  CHECK(e.find("/W/P.protoIndices: item 1 is 1, outside the 1 prototypes") != std::string::npos);
  e = firstError(R"(
        int[] protoIndices = [0]
        point3f[] positions = [(0, 0, 0)]
        quath[] orientations = [(0, 0, 0, 0)]
)");
  CHECK(e.find("/W/P.orientations: item 0 is a zero quaternion") != std::string::npos);
  e = firstError(R"(
        int[] protoIndices = [0]
)");
  CHECK(e.find("a PointInstancer needs protoIndices (int[]) and positions (point3f[])") != std::string::npos);
  e = firstError(R"(
        int[] protoIndices = [0, 0]
        int64[] ids = [4, 4]
        point3f[] positions = [(0, 0, 0), (1, 0, 0)]
)");
  CHECK(e.find("instance id 4 appears twice") != std::string::npos);
}
