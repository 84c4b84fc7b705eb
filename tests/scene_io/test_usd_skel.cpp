// UsdSkel (scene_io/usd_skel.h): the skinning math against hand-computed
// poses, and a two-joint arm imported from usda (tests/data/usd/skel/arm.usda)
// whose elbow bends over a second: points at the start pose and on the
// stage's animation table at each sample, in the mesh's own space (its
// transform ignored, the Skeleton's applied, as in USD).
#include <catch2/catch.hpp>

#include <cmath>
#include <fstream>
#include <sstream>

#include "scene_io/usd_fixtures.h"
#include "scene_io/usd_skel.h"

namespace sdg {
namespace {

const std::string kArm = std::string(SDG_SOURCE_DIR) + "/tests/data/usd/skel/arm.usda";

std::string readText(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

Vec3d pointOf(const Value& points, size_t i) {
  const FloatArray& p = points.get<FloatArray>();
  return Vec3d(p[3 * i], p[3 * i + 1], p[3 * i + 2]);
}

Matrix4d translation(double x, double y, double z) {
  Matrix4d m = Matrix4d::Identity();
  m.topRightCorner<3, 1>() = Vec3d(x, y, z);
  return m;
}

}  // namespace

TEST_CASE("usd skel: joint parents come from the joint paths, in any order", "[usd_skel]") {
  const SkelTopology t = skelTopology({"Hip/Knee/Ankle", "Hip", "Hip/Knee", "Other", "Hip/Knee2"});
  CHECK(t.parent == std::vector<int>{2, -1, 1, -1, 1});
}

TEST_CASE("usd skel: a local transform is translate * rotate * scale", "[usd_skel]") {
  const Matrix4d m = skelLocalTransform(Vec3d(1, 2, 3), Quatd(Eigen::AngleAxisd(M_PI / 2, Vec3d::UnitZ())), Vec3d(2, 2, 2));
  const Vec3d p = (m * Eigen::Vector4d(1, 0, 0, 1)).head<3>();
  CHECK(p.isApprox(Vec3d(1, 4, 3), 1e-12));  // scaled to 2, turned onto +Y, moved
}

TEST_CASE("usd skel: skinning transforms are identity at the bind pose and follow a bent child", "[usd_skel]") {
  const SkelTopology t = skelTopology({"A", "A/B"});
  const std::vector<Matrix4d> bind = {Matrix4d::Identity(), translation(1, 0, 0)};
  const std::vector<Matrix4d> rest = {Matrix4d::Identity(), translation(1, 0, 0)};
  for (const Matrix4d& s : skinningTransforms(t, rest, bind)) CHECK(s.isApprox(Matrix4d::Identity(), 1e-12));

  // The root moved by (0, 0, 2) moves the child with it; the child turned
  // 90 degrees about Z turns points about (1, 0, 0).
  std::vector<Matrix4d> posed = {translation(0, 0, 2),
                                 skelLocalTransform(Vec3d(1, 0, 0), Quatd(Eigen::AngleAxisd(M_PI / 2, Vec3d::UnitZ())),
                                                    Vec3d::Ones())};
  const std::vector<Matrix4d> skin = skinningTransforms(t, posed, bind);
  CHECK((skin[0] * Eigen::Vector4d(3, 0, 0, 1)).head<3>().isApprox(Vec3d(3, 0, 2), 1e-12));
  CHECK((skin[1] * Eigen::Vector4d(2, 0, 0, 1)).head<3>().isApprox(Vec3d(1, 1, 2), 1e-12));
}

TEST_CASE("usd skel: points blend their joints' transforms by weight, normalised", "[usd_skel]") {
  const std::vector<Matrix4d> skin = {translation(0, 0, 0), translation(0, 0, 4)};
  SkinInfluences in;
  in.perPoint = 2;
  in.joints = {0, 1, 0, 1, 0, 1};
  in.weights = {1, 0, 0.5f, 0.5f, 1, 3};  // the last pair adds up to 4: normalised to 0.25 / 0.75
  const std::vector<float> points = {0, 0, 0, 1, 0, 0, 2, 0, 0};
  std::vector<float> outPoints, outNormals;
  skinPoints(points, {}, {}, Matrix4d::Identity(), in, skin, Matrix4d::Identity(), outPoints, outNormals);
  REQUIRE(outPoints.size() == 9);
  CHECK(outPoints[2] == Approx(0));
  CHECK(outPoints[5] == Approx(2));
  CHECK(outPoints[8] == Approx(3));

  SECTION("rigid: one set of influences for the whole mesh") {
    SkinInfluences rigid;
    rigid.perPoint = 1;
    rigid.rigid = true;
    rigid.joints = {1};
    rigid.weights = {1};
    skinPoints(points, {}, {}, translation(1, 0, 0), rigid, skin, Matrix4d::Identity(), outPoints, outNormals);
    CHECK(outPoints == std::vector<float>{1, 0, 4, 2, 0, 4, 3, 0, 4});  // geomBind first, then the joint
  }
  SECTION("per-corner normals turn with their corner's point") {
    const std::vector<Matrix4d> turned = {
        skelLocalTransform(Vec3d::Zero(), Quatd(Eigen::AngleAxisd(M_PI / 2, Vec3d::UnitZ())), Vec3d::Ones())};
    SkinInfluences one;
    one.perPoint = 1;
    one.joints = {0, 0, 0};
    one.weights = {1, 1, 1};
    const std::vector<float> normals = {1, 0, 0, 1, 0, 0};
    const std::vector<int32_t> corners = {2, 0};
    skinPoints(points, normals, corners, Matrix4d::Identity(), one, turned, Matrix4d::Identity(), outPoints, outNormals);
    REQUIRE(outNormals.size() == 6);
    CHECK(Vec3d(outNormals[0], outNormals[1], outNormals[2]).isApprox(Vec3d(0, 1, 0), 1e-6));
  }
}

TEST_CASE("usd skel: an arm bends at its elbow over its time samples", "[usd_skel][usd_import]") {
  test::ImportedStage imported;
  test::importText(readText(kArm), imported);
  REQUIRE_FALSE(imported.diag.hasErrors());
  const Prim* skin = imported.stage.find("/World/Arm/Skin");
  REQUIRE(skin != nullptr);
  // The mesh is at (5, 0, 0), the Skeleton at (0, 0, 1): skeleton space is
  // the mesh's space moved by (-5, 0, 1).
  const Value& start = *skin->value("points");
  CHECK(pointOf(start, 1).isApprox(Vec3d(2 - 5, 0, 1), 1e-6));
  CHECK(pointOf(start, 3).isApprox(Vec3d(0 - 5, 0.2, 1), 1e-6));

  const AnimatedValue* points = imported.stage.animation().find("/World/Arm/Skin", "points");
  REQUIRE(points != nullptr);
  CHECK(points->times == std::vector<double>{0, 12, 24});
  const double c = std::cos(M_PI / 4), s = std::sin(M_PI / 4);
  const Value at12 = points->at(12);
  CHECK(pointOf(at12, 0).isApprox(Vec3d(-5, 0, 1), 1e-6));                  // on the shoulder: still
  CHECK(pointOf(at12, 1).isApprox(Vec3d(1 + c - 5, s, 1), 1e-5));           // turned 45 degrees about the elbow
  CHECK(pointOf(points->at(24), 2).isApprox(Vec3d(0.8 - 5, 1, 1), 1e-5));  // (1, 0.2) turned 90 degrees
  CHECK(imported.stage.animation().find("/World/Arm/Skin", "normals") != nullptr);

  // Nothing of the skeleton is reported as dropped.
  CHECK(imported.report.losses.empty());
}

TEST_CASE("usd skel: a binding that cannot be read is a located error", "[usd_skel][usd_import]") {
  const std::string arm = readText(kArm);
  auto importWith = [&](const std::string& from, const std::string& to) {
    std::string text = arm;
    const size_t at = text.find(from);
    REQUIRE(at != std::string::npos);
    text.replace(at, from.size(), to);
    auto out = std::make_unique<test::ImportedStage>();
    test::importText(text, *out);
    return out;
  };
  SECTION("a joint index outside the joints") {
    auto out = importWith("jointIndices = [0, 1, 1, 0]", "jointIndices = [0, 1, 7, 0]");
    REQUIRE(out->diag.hasErrors());
    CHECK_THAT(out->diag.all().front().format(), Catch::Contains("jointIndices[2] is 7, outside the 2 joints"));
  }
  SECTION("bind transforms that are not one per joint") {
    auto out = importWith("uniform matrix4d[] bindTransforms = [( (1, 0, 0, 0), (0, 1, 0, 0), (0, 0, 1, 0), (0, 0, 0, 1) ), ",
                          "uniform matrix4d[] bindTransforms = [");
    REQUIRE(out->diag.hasErrors());
    CHECK_THAT(out->diag.all().front().format(), Catch::Contains("bindTransforms: expected 2 finite matrix4d"));
    CHECK_THAT(out->diag.all().front().format(), Catch::Contains("scene.usda:"));
  }
  SECTION("a skeleton binding to a prim that is no Skeleton") {
    auto out = importWith("rel skel:skeleton = </World/Arm/Skel>", "rel skel:skeleton = </World/Camera>");
    REQUIRE(out->diag.hasErrors());
    CHECK_THAT(out->diag.all().front().format(), Catch::Contains("which is a Camera, not a Skeleton"));
  }
  SECTION("an animation value that is not finite") {
    auto out = importWith("float3[] translations = [(1, 0, 0)]", "float3[] translations = [(inf, 0, 0)]");
    REQUIRE(out->diag.hasErrors());
    CHECK_THAT(out->diag.all().front().format(), Catch::Contains("gives points that are not finite"));
  }
  SECTION("weights fewer than indices") {
    auto out = importWith("jointWeights = [1, 1, 1, 1]", "jointWeights = [1, 1, 1]");
    REQUIRE(out->diag.hasErrors());
    CHECK_THAT(out->diag.all().front().format(), Catch::Contains("expected 4 items (as jointIndices), found 3"));
  }
}

}  // namespace sdg
