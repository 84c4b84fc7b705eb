// StageJournal: what a script changed is put back exactly, newest first,
// and prims it created go; prims it created are never journaled.
#include <catch2/catch.hpp>

#include "scripting/stage_journal.h"
#include "stage/stage.h"

namespace sdg::scripting {
namespace {

Stage twoPrims() {
  Stage stage;
  stage.definePrim("/World", PrimType::Xform);
  Prim& box = stage.definePrim("/World/Box", PrimType::Cube);
  box.setAttribute("size", Value::makeDouble(2.0));
  box.xformOps().push_back(XformOp{XformOpKind::Translate, "", Value::makeDouble3(Vec3d(1, 2, 3))});
  box.semantics()["class"] = {"box"};
  return stage;
}

}  // namespace

TEST_CASE("a journal restores attributes, ops and labels a script changed", "[scripting][journal]") {
  Stage stage = twoPrims();
  const Stage before = stage;
  StageJournal journal;
  Prim& box = *stage.find("/World/Box");
  journal.beforeAttributeWrite(box, "size");
  box.setAttribute("size", Value::makeDouble(5.0));
  journal.beforeAttributeWrite(box, "size");  // a second write saves nothing more
  box.setAttribute("size", Value::makeDouble(7.0));
  journal.beforeAttributeWrite(box, "custom:new");
  box.setAttribute("custom:new", Value::makeInt(1));
  journal.beforeXformWrite(box);
  box.xformOps().front().value = Value::makeDouble3(Vec3d(9, 9, 9));
  journal.beforeSemanticsWrite(box);
  box.semantics()["class"] = {"crate"};
  REQUIRE_FALSE(stage == before);
  journal.undo(stage);
  CHECK(stage == before);
  CHECK(journal.empty());
}

TEST_CASE("a journal removes the prims a script created, and keeps no record of their writes",
          "[scripting][journal]") {
  Stage stage = twoPrims();
  const Stage before = stage;
  StageJournal journal;
  Prim& made = stage.definePrim("/World/Made", PrimType::Sphere);
  journal.created(made);
  CHECK(journal.createdHere(made));
  CHECK_FALSE(journal.createdHere(*stage.find("/World/Box")));
  journal.beforeAttributeWrite(made, "radius");  // not saved: the prim goes
  made.setAttribute("radius", Value::makeDouble(3.0));
  journal.undo(stage);
  CHECK(stage.find("/World/Made") == nullptr);
  CHECK(stage == before);
}
}  // namespace sdg::scripting
